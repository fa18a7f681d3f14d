// A lattice of an image's pixels: from each stride x stride block (blocks counted from the top
// left corner), its middle pixel, or the last one where the image's edge cuts the block short.
// An animation meters its automatic exposure on the lattice of a frame (stride 4: a sixteenth
// of the pixels), and the ray tracer renders the lattice alone (RenderOptions::lattice).
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "lightcone/scene/scene.hpp"

namespace lightcone {

// How many lattice pixels a row (or column) of `extent` pixels has.
inline int lattice_size(int extent, int stride) {
  return (extent + stride - 1) / stride;
}

// The pixel of lattice index `index` along a row (or column) of `extent` pixels.
inline int lattice_pixel(int index, int extent, int stride) {
  return std::min(stride * index + stride / 2, extent - 1);
}

// The lattice index of `pixel`, or -1 where it is not on the lattice.
inline int lattice_index(int pixel, int extent, int stride) {
  const int index = pixel / stride;
  return lattice_pixel(index, extent, stride) == pixel ? index : -1;
}

// The lattice's values of a row-major picture of width x height pixels, `per_pixel` floats each.
inline std::vector<float> lattice_of(std::span<const float> values, int width, int height,
                                     int per_pixel, int stride) {
  const int columns = lattice_size(width, stride), rows = lattice_size(height, stride);
  std::vector<float> out;
  out.reserve(static_cast<std::size_t>(columns) * rows * per_pixel);
  for (int b = 0; b < rows; ++b)
    for (int a = 0; a < columns; ++a) {
      const std::size_t at = static_cast<std::size_t>(lattice_pixel(b, height, stride)) * width +
                             lattice_pixel(a, width, stride);
      out.insert(out.end(), values.begin() + at * per_pixel, values.begin() + (at + 1) * per_pixel);
    }
  return out;
}

// The lattice of an image's colour (its output variables are not carried).
inline Image lattice_of(const Image& image, int stride) {
  Image out;
  out.width = lattice_size(image.width, stride);
  out.height = lattice_size(image.height, stride);
  out.rgb = lattice_of(image.rgb, image.width, image.height, 3, stride);
  out.exposure = image.exposure;
  return out;
}

}  // namespace lightcone
