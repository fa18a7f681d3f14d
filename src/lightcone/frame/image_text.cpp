#include "lightcone/frame/image_text.hpp"

#include <stb_easy_font.h>

#include <algorithm>
#include <cmath>
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

void draw_notes(Image& image, const std::vector<std::string>& lines,
                const std::vector<std::array<double, 2>>& marks) {
  constexpr int kLine = 18;  // a line of scale 2 (14 pixels) and its spacing
  for (std::size_t k = 0; k < marks.size(); ++k) {
    const int cx = static_cast<int>(std::floor(marks[k][0]));
    const int cy = static_cast<int>(std::floor(marks[k][1]));
    // A ring of radius 6 about the point, and its number beside it.
    for (int dy = -7; dy <= 7; ++dy)
      for (int dx = -7; dx <= 7; ++dx) {
        const double r = std::hypot(dx, dy);
        const int x = cx + dx, y = cy + dy;
        if (r < 5.5 || r > 7 || x < 0 || y < 0 || x >= image.width || y >= image.height) continue;
        float* p = &image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)];
        p[0] = p[1] = p[2] = 1.0f;
      }
    draw_text(image, cx + 9, cy - 18, std::to_string(k + 1));
  }
  if (lines.empty()) return;
  const int band = static_cast<int>(lines.size()) * kLine + 8;
  for (int y = std::max(image.height - band, 0); y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c)
        image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x) + c] *= 0.2f;
  for (std::size_t k = 0; k < lines.size(); ++k)
    draw_text(image, 8, image.height - band + 6 + static_cast<int>(k) * kLine, lines[k]);
}

}  // namespace lightcone
