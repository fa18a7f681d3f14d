// The image bins (docs/design/tracer.md): the bodies before the camera listed by the cells of
// the image plane their bounds cover, each cell's list nearest first.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/vec.hpp"

namespace lightcone {

// Bodies listed by the cells of a grid over the directions from one point (the image plane for
// camera rays), each cell's list nearest first.
struct CellLists {
  struct Entry {
    float a_lo, a_hi, c_lo, c_hi;  // the body's rectangle in the grid's plane, rounded outwards
    float near;                    // its bounds' distance from the rays' common point, rounded down
    unsigned body;
  };
  std::vector<unsigned> start;  // cell k's entries are [start[k], start[k + 1])
  std::vector<Entry> entries;
};

// The cell of such a grid that holds x, |x| <= half.
inline int cell_of(double x, double half, int count) {
  return std::min(count - 1, static_cast<int>((x + half) / (2 * half) * count));
}

// Camera rays in the view: the bodies before the camera, binned by the rectangle their trace
// bounds project to in the image plane (a, c) = (u.right, u.up) / u.forward. Each cell lists
// those whose rectangle meets it, nearest first; a ray needs only its own cell's list.
struct ImageBins {
  double half_a = 0, half_c = 0;  // the plane's range in the view, a little enlarged
  int cells_a = 0, cells_c = 0;   // row c's cells are c cells_a + a
  CellLists lists;

  // The image plane's point of look direction u, and its cell; false outside the bins' range
  // (behind the camera, or out of the view).
  bool point(const CameraBasis& view, const Vec3& u, float& a, float& c, unsigned& cell) const {
    const double f = dot(u, view.forward);
    if (!(f > 0)) return false;
    const double pa = dot(u, view.right) / f, pc = dot(u, view.up) / f;
    if (!(std::abs(pa) <= half_a && std::abs(pc) <= half_c)) return false;
    a = static_cast<float>(pa);
    c = static_cast<float>(pc);
    cell = static_cast<unsigned>(cell_of(pc, half_c, cells_c) * cells_a +
                                 cell_of(pa, half_a, cells_a));
    return true;
  }
};

// The bins of the bodies before the camera, none for a view of no extent. `unbinned` gets, in
// order, the bodies the bins do not hold but rays in the view may meet: their bounds reach
// beside or behind the camera, or cover too much of the image to list cell by cell.
std::optional<ImageBins> image_bins(const CameraBasis& view, std::span<const ResolvedBody> bodies,
                                    std::vector<unsigned>& unbinned);

}  // namespace lightcone
