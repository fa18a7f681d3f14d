// An image a scene read in the page names that the browser has not decoded yet: thrown by
// load_image_file (page_images.cpp). It is not a std::exception, so that the scene reader,
// which turns those into located InputErrors, lets it through to lc_load; the page decodes the
// image and reads the scene again.
#pragma once

#include <string>

namespace lightcone {

struct ImageNotDecoded {
  std::string path;
};

}  // namespace lightcone
