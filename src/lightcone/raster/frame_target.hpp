// Where the raster renderer draws: a float colour texture with a depth buffer, and the display
// pass that shows such a texture, exposed and tone-mapped, in the viewer's window.
#pragma once

#include <vector>

#include "lightcone/scene/scene.hpp"

namespace lightcone {

// Needs a current OpenGL 3.3 context.
class FloatTarget {
 public:
  FloatTarget(int width, int height);
  ~FloatTarget();
  FloatTarget(const FloatTarget&) = delete;
  FloatTarget& operator=(const FloatTarget&) = delete;

  // Binds the target for drawing and sets the viewport to it.
  void bind() const;
  unsigned texture() const { return colour_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // The linear RGB of the target, rows from the top.
  Image read() const;
  // The same, added to `sum` (3 values a pixel, rows from the top); where `subject` is given
  // (a value a pixel), `weight` is added to it where a body moving relative to the camera was
  // drawn (its alpha is 2, body.frag's subject_alpha).
  void add_to(std::vector<double>& sum, std::vector<float>* subject = nullptr,
              float weight = 0) const;
  // The automatic exposure of one pass drawn here, as the viewer and the web page meter each
  // frame: the rule of both renderers (tone_map.hpp's auto_exposure) on the lattice of stride
  // kMeteringStep that an animation meters (frame/pixel_lattice.hpp), each pixel weighed as
  // render_raster weighs it at one sample (1 where a body moving relative to the camera is
  // drawn, else 0).
  static constexpr int kMeteringStep = 4;
  double metered_exposure(ToneMap curve) const;

 private:
  // The target's RGBA into pixels_, rows from the bottom (GL's).
  void read_back() const;

  int width_, height_;
  unsigned framebuffer_ = 0, colour_ = 0, depth_ = 0;
  mutable std::vector<float> pixels_;
  // metered_exposure's sample of the frame and its subject weights, kept from frame to frame.
  mutable Image metered_;
  mutable std::vector<float> metered_subject_;
};

// Draws float textures into the bound framebuffer: radiance times 2^exposure, tone-mapped and
// sRGB-encoded as a PNG of `lightcone render` is; with a classical texture too, its left half
// shows that one.
class DisplayPass {
 public:
  DisplayPass();
  ~DisplayPass();
  DisplayPass(const DisplayPass&) = delete;
  DisplayPass& operator=(const DisplayPass&) = delete;
  void draw(const FloatTarget& relativistic, const FloatTarget* classical, double exposure_ev,
            ToneMap curve) const;

 private:
  unsigned program_ = 0, vertex_array_ = 0;
};

}  // namespace lightcone
