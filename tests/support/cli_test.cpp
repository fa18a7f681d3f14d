#include "support/cli_test.hpp"

#include <algorithm>

#include "lightcone/frame/tone_map.hpp"

namespace lightcone::test {

std::string edited(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "no '" << from << "' in the scene";
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "'" << from << "' is not unique";
  if (at == std::string::npos) return text;
  return text.substr(0, at) + to + text.substr(at + from.size());
}

std::size_t line_count(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

int png_byte(float linear) {
  for (int i = 0; i < 256; ++i)
    if (static_cast<float>(srgb_decode(i / 255.0)) == linear) return i;
  return -1;
}

std::string moving_black_ball() {
  const std::string moving = edited(kScene, "\n      \"velocity\": [0, 0, 0]",
                                    "\n      \"velocity\": [0.8, 0, 0],\n      \"time\": -10");
  return edited(edited(moving, "\"color\": [0, 0, 1]", "\"color\": [1, 0, 0]"),
                "\"color\": [0, 1, 0]", "\"color\": [0, 0, 0]");
}

}  // namespace lightcone::test
