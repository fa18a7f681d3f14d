#include "lightcone/frame/image_text.hpp"

#include <stb_easy_font.h>

#include <algorithm>
#include <vector>

namespace lightcone {

void draw_text(Image& image, int x, int y, const std::string& text, int scale) {
  std::vector<char> buffer(text.size() * 300 + 64);
  std::string copy = text;
  unsigned char colour[4] = {255, 255, 255, 255};
  const int quads = stb_easy_font_print(0, 0, copy.data(), colour, buffer.data(),
                                        static_cast<int>(buffer.size()));
  const float* v = reinterpret_cast<const float*>(buffer.data());
  for (int q = 0; q < quads; ++q) {
    const float* quad = v + q * 16;  // 4 vertices of x, y, z and 4 colour bytes
    const int x0 = static_cast<int>(scale * quad[0]), y0 = static_cast<int>(scale * quad[1]);
    const int x1 = static_cast<int>(scale * quad[8]), y1 = static_cast<int>(scale * quad[9]);
    for (int yy = std::max(y + std::min(y0, y1), 0);
         yy < std::min(y + std::max(y0, y1), image.height); ++yy)
      for (int xx = std::max(x + std::min(x0, x1), 0);
           xx < std::min(x + std::max(x0, x1), image.width); ++xx) {
        float* p = &image.rgb[3 * (static_cast<std::size_t>(yy) * image.width + xx)];
        p[0] = p[1] = p[2] = 1.0f;
      }
  }
}

int text_width(const std::string& text, int scale) {
  std::string copy = text;
  return scale * stb_easy_font_width(copy.data());
}

void draw_caption(Image& image, const std::string& caption) {
  for (int y = 0; y < std::min(kCaptionHeight, image.height); ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x) + c] *= 0.2f;
  draw_text(image, (image.width - text_width(caption)) / 2, 6, caption);
}

}  // namespace lightcone
