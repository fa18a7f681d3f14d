// Text stamped into display images (values in [0, 1]): the labels of a `--map` picture and the
// caption of the viewer's split view, in the stb_easy_font bitmap font (Debian's libstb-dev).
#pragma once

#include <array>
#include <string>
#include <vector>

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

// `lines` along the bottom left of the image, white on a dark band (as the caption's), and each
// of `marks` (image points) circled in white and numbered from 1: the viewer's probe readouts in
// its screenshots.
void draw_notes(Image& image, const std::vector<std::string>& lines,
                const std::vector<std::array<double, 2>>& marks);

}  // namespace lightcone
