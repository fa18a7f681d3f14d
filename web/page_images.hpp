// The images a scene read in the page asked for that the browser has not decoded yet
// (page_images.cpp): the page decodes them and reads the scene again.
#pragma once

#include <string>
#include <vector>

namespace lightcone {

std::vector<std::string>& wanted_images();

}  // namespace lightcone
