// Text stamped into display images (values in [0, 1]): the labels of a `--map` picture and the
// caption of the viewer's split view, in the stb_easy_font bitmap font (Debian's libstb-dev).
#pragma once

#include <string>

#include "lightcone/scene/scene.hpp"

namespace lightcone {

// White text with its top left at (x, y), `scale` pixels a font unit (a line is 7 units high);
// what falls outside the image is left out.
void draw_text(Image& image, int x, int y, const std::string& text, int scale = 2);
int text_width(const std::string& text, int scale = 2);

// `caption` centred along the top of the image, white on a dark band kCaptionHeight pixels high
// (the picture beneath is dimmed to a fifth, so that the text reads over any picture).
inline constexpr int kCaptionHeight = 26;
void draw_caption(Image& image, const std::string& caption);

}  // namespace lightcone
