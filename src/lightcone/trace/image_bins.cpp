#include "lightcone/trace/image_bins.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace lightcone {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The range of (p.e) / (p.f) over the end balls of a capsule before the camera (e and f
// orthonormal): a plane through the camera with e.p = a f.p meets a ball (centre C, radius R)
// where (e.C - a f.C)^2 <= R^2 (1 + a^2), a quadratic in a.
std::pair<double, double> ball_image(const Capsule& capsule, const Vec3& e, const Vec3& f) {
  double lo = kInfinity, hi = -kInfinity;
  for (const Vec3& centre : {capsule.from, capsule.to}) {
    const double x = dot(centre, e), z = dot(centre, f), r2 = capsule.radius * capsule.radius;
    const double root = capsule.radius * std::sqrt(x * x + z * z - r2), scale = z * z - r2;
    lo = std::min(lo, (x * z - root) / scale);
    hi = std::max(hi, (x * z + root) / scale);
  }
  return {lo, hi};
}

// The distance from the camera to the segment from a to b.
double distance_to_segment(const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double dd = dot(d, d);
  const double t = dd > 0 ? std::clamp(-dot(a, d) / dd, 0.0, 1.0) : 0.0;
  return length(a + d * t);
}

// A body's rectangle in a grid's plane, and the cells it covers: columns a0..a1 of rows c0..c1.
struct BinnedRect {
  double a_lo, a_hi, c_lo, c_hi, near;
  unsigned body;
  int a0 = 0, a1 = 0, c0 = 0, c1 = 0;
  std::size_t cells() const { return std::size_t(a1 - a0 + 1) * std::size_t(c1 - c0 + 1); }
};

// The cells of a grid `count` cells wide over [-half, half] from lo to hi, clamped to it: in
// double before the cast, since a body far off the axis (near a hole of 1e300, say) has an edge
// at infinity; an edge that is no number is taken as the grid's, so that the body is kept.
std::pair<int, int> cell_range(double lo, double hi, double half, int count) {
  const auto at = [&](double x, int unknown) {
    const double cell = std::floor((x + half) / (2 * half) * count);
    if (std::isnan(cell)) return unknown;
    return static_cast<int>(std::clamp(cell, 0.0, static_cast<double>(count - 1)));
  };
  return {at(lo, 0), at(hi, count - 1)};
}

// The point of box b nearest to p.
Vec3 nearest_point(const Bounds3& b, const Vec3& p) {
  Vec3 q;
  for (int k = 0; k < 3; ++k) q[k] = std::clamp(p[k], b.lower[k], b.upper[k]);
  return q;
}

// The lists of a grid of `rows` rows of `columns` cells (row c's cells are c columns + a), from
// the bodies' rectangles (sorted here by distance).
CellLists cell_lists(std::vector<BinnedRect>& rects, int columns, int rows) {
  const std::size_t cell_count = std::size_t(columns) * std::size_t(rows);
  std::sort(rects.begin(), rects.end(), [](const BinnedRect& x, const BinnedRect& y) {
    return x.near < y.near || (x.near == y.near && x.body < y.body);
  });
  CellLists lists;
  lists.start.assign(cell_count + 1, 0);
  const auto each_cell = [&](const BinnedRect& r, auto&& visit) {
    for (int c = r.c0; c <= r.c1; ++c)
      for (int a = r.a0; a <= r.a1; ++a) visit(std::size_t(c) * columns + a);
  };
  for (const BinnedRect& r : rects) each_cell(r, [&](std::size_t k) { ++lists.start[k + 1]; });
  for (std::size_t k = 0; k < cell_count; ++k) lists.start[k + 1] += lists.start[k];
  lists.entries.resize(lists.start[cell_count]);
  std::vector<unsigned> filled(lists.start.begin(), lists.start.end() - 1);
  const auto down = [](double x) { return std::nextafter(static_cast<float>(x), -INFINITY); };
  const auto up = [](double x) { return std::nextafter(static_cast<float>(x), INFINITY); };
  // In order of distance, so each cell's list is nearest first.
  for (const BinnedRect& r : rects) {
    const CellLists::Entry e{down(r.a_lo), up(r.a_hi),   down(r.c_lo),
                             up(r.c_hi),   down(r.near), r.body};
    each_cell(r, [&](std::size_t k) { lists.entries[filled[k]++] = e; });
  }
  return lists;
}

}  // namespace

std::optional<ImageBins> image_bins(const CameraBasis& view, std::span<const ResolvedBody> bodies,
                                    std::vector<unsigned>& unbinned) {
  ImageBins bins;
  // Sample points reach the image's edges; the margin keeps them inside the range.
  bins.half_c = view.tan_half_fov * (1 + 1e-3);
  bins.half_a = bins.half_c * view.aspect;
  if (!(std::isfinite(bins.half_a) && std::isfinite(bins.half_c) && bins.half_a > 0 &&
        bins.half_c > 0))
    return std::nullopt;
  std::vector<BinnedRect> rects;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Bounds3& b = bodies[i].trace_bounds;
    const auto index = static_cast<unsigned>(i);
    if (!(b.lower.x <= b.upper.x && b.lower.y <= b.upper.y && b.lower.z <= b.upper.z)) continue;
    double f_lo = kInfinity, f_hi = -kInfinity, reach = 0;
    BinnedRect r{kInfinity, -kInfinity, kInfinity, -kInfinity, 0, index};
    for (int k = 0; k < 8; ++k) {
      const Vec3 p = corner(b, k);
      const double f = dot(p, view.forward);
      f_lo = std::min(f_lo, f);
      f_hi = std::max(f_hi, f);
      reach = std::max(reach, length(p));
      r.a_lo = std::min(r.a_lo, dot(p, view.right) / f);
      r.a_hi = std::max(r.a_hi, dot(p, view.right) / f);
      r.c_lo = std::min(r.c_lo, dot(p, view.up) / f);
      r.c_hi = std::max(r.c_hi, dot(p, view.up) / f);
    }
    if (f_hi < 0) continue;  // wholly behind the camera: no ray in the view meets it
    if (!(f_lo > 1e-9 * reach) || !std::isfinite(reach)) {
      unbinned.push_back(index);
      continue;
    }
    if (r.a_hi < -bins.half_a || r.a_lo > bins.half_a || r.c_hi < -bins.half_c ||
        r.c_lo > bins.half_c)
      continue;  // out of the view
    r.near = length(nearest_point(b, {}));
    // The capsule's own image is tighter: the hull of its end balls' images, so within the
    // union of their rectangles.
    const Capsule& capsule = bodies[i].trace_capsule;
    const double ra = capsule.radius;
    if (dot(capsule.from, view.forward) > ra * (1 + 1e-6) &&
        dot(capsule.to, view.forward) > ra * (1 + 1e-6)) {
      const auto [a_lo, a_hi] = ball_image(capsule, view.right, view.forward);
      const auto [c_lo, c_hi] = ball_image(capsule, view.up, view.forward);
      r.a_lo = std::max(r.a_lo, a_lo);
      r.a_hi = std::min(r.a_hi, a_hi);
      r.c_lo = std::max(r.c_lo, c_lo);
      r.c_hi = std::min(r.c_hi, c_hi);
      r.near = std::max(r.near, distance_to_segment(capsule.from, capsule.to) - ra);
    }
    r.near *= 1 - 1e-9;
    rects.push_back(r);
  }
  // About two cells a body, none smaller than 4 x 4 pixels (a packet's rays share a cell).
  const double pixels = static_cast<double>(view.width) * view.height;
  const double cells =
      std::clamp(2.0 * static_cast<double>(rects.size()), 1.0, std::max(1.0, pixels / 16));
  bins.cells_a = std::max(1, static_cast<int>(std::lround(std::sqrt(cells * view.aspect))));
  bins.cells_c = std::max(1, static_cast<int>(cells / bins.cells_a));
  std::size_t total = 0;
  for (BinnedRect& r : rects) {
    std::tie(r.a0, r.a1) = cell_range(r.a_lo, r.a_hi, bins.half_a, bins.cells_a);
    std::tie(r.c0, r.c1) = cell_range(r.c_lo, r.c_hi, bins.half_c, bins.cells_c);
    total += r.cells();
  }
  // The lists' size is held to a few entries a cell and a body: bodies that cover the most
  // cells go to the BVH instead.
  const std::size_t cell_count = std::size_t(bins.cells_a) * std::size_t(bins.cells_c);
  const std::size_t budget = 8 * (cell_count + rects.size());
  if (total > budget) {
    std::stable_sort(rects.begin(), rects.end(), [](const BinnedRect& x, const BinnedRect& y) {
      return x.cells() < y.cells();
    });
    std::size_t kept = 0;
    for (total = 0; kept < rects.size() && total + rects[kept].cells() <= budget; ++kept)
      total += rects[kept].cells();
    for (std::size_t k = kept; k < rects.size(); ++k) unbinned.push_back(rects[k].body);
    rects.resize(kept);
  }
  bins.lists = cell_lists(rects, bins.cells_a, bins.cells_c);
  std::sort(unbinned.begin(), unbinned.end());
  return bins;
}

}  // namespace lightcone
