#include "lightcone/scene/speed_text.hpp"

#include <fmt/format.h>

#include <string>

namespace lightcone {

std::string speed_text(double beta, int digits) {
  std::string text = fmt::format("{:.{}g}", beta, digits);
  // The digits printed are those of the double the text parses to; 17 tell every double apart.
  for (int more = digits + 1; beta < 1 && std::stod(text) >= 1 && more <= 17; ++more)
    text = fmt::format("{:.{}g}", beta, more);
  return text;
}

}  // namespace lightcone
