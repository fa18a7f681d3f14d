// Which image format a file's name says (image_file.hpp): apart from the codecs, so that the
// web page, which decodes images in the browser, shares it.
#include <algorithm>
#include <cctype>
#include <string>

#include "lightcone/io/image_file.hpp"

namespace lightcone {

std::optional<ImageFormat> image_format_of(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".png") return ImageFormat::kPng;
  if (ext == ".jpg" || ext == ".jpeg") return ImageFormat::kJpeg;
  if (ext == ".exr") return ImageFormat::kExr;
  return std::nullopt;
}

}  // namespace lightcone
