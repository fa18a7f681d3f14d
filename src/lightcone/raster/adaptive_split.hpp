// The tessellation's edge rule, for every way a shape point can be seen (straight rays in flat
// spacetime, the images of each order near a black hole): a triangle's edges are split at their
// midpoints until each is drawn within the error bound, and the triangle is cut by how many of
// its edges split. Each edge's split depends only on its own ends and level, so neighbouring
// triangles agree (no cracks) (docs/design/raster.md).
#pragma once

#include <algorithm>

#include "lightcone/physics/vec.hpp"

namespace lightcone {

// `Seeing` provides
//   Corner corner(const Vec3& shape_point) const;  // where the point is seen (Corner has .p)
//   Corner middle(const Corner& a, const Corner& b, const Vec3& shape_point) const;  // the same,
//       for the midpoint of edge ab (which may start from where a and b are seen)
//   bool needs_split(const Corner& a, const Corner& b, const Corner& middle) const;
//   void emit(const Corner& a, const Corner& b, const Corner& c) const;
// and a midpoint rule `mesh.midpoint(a, b)` comes from the RestMesh.
template <class Seeing, class Mesh>
class AdaptiveSplit {
 public:
  using Corner = typename Seeing::Corner;
  AdaptiveSplit(const Seeing& seeing, const Mesh& mesh, int max_level)
      : seeing_(seeing), mesh_(mesh), max_level_(max_level) {}

  // Triangle (a, b, c) whose edges ab, bc, ca are at the given levels.
  void triangle(const Corner& a, const Corner& b, const Corner& c, int lab = 0, int lbc = 0,
                int lca = 0) const {
    Corner mab, mbc, mca;
    const bool sab = split(a, b, lab, mab), sbc = split(b, c, lbc, mbc),
               sca = split(c, a, lca, mca);
    cut(a, b, c, mab, mbc, mca, lab, lbc, lca, sab, sbc, sca);
  }

  // Whether edge ab (at `level`) is split; its midpoint is set when it is.
  bool split(const Corner& a, const Corner& b, int level, Corner& middle) const {
    if (level >= max_level_) return false;
    middle = seeing_.middle(a, b, mesh_.midpoint(a.p, b.p));
    return seeing_.needs_split(a, b, middle);
  }

  // An untessellated triangle whose edges' decisions (split) were made beforehand, once for
  // both triangles that share each.
  void triangle(const Corner& a, const Corner& b, const Corner& c, const Corner& mab,
                const Corner& mbc, const Corner& mca, bool sab, bool sbc, bool sca) const {
    cut(a, b, c, mab, mbc, mca, 0, 0, 0, sab, sbc, sca);
  }

 private:
  // The same, with each edge's decision (and midpoint) made, so that rotating the triangle
  // decides nothing twice.
  void cut(const Corner& a, const Corner& b, const Corner& c, const Corner& mab, const Corner& mbc,
           const Corner& mca, int lab, int lbc, int lca, bool sab, bool sbc, bool sca) const {
    const int count = int(sab) + int(sbc) + int(sca);
    if (count == 0) return seeing_.emit(a, b, c);
    if (count == 3) {
      const int l = std::max({lab, lbc, lca}) + 1;
      triangle(a, mab, mca, lab + 1, l, lca + 1);
      triangle(mab, b, mbc, lab + 1, lbc + 1, l);
      triangle(mca, mbc, c, l, lbc + 1, lca + 1);
      triangle(mab, mbc, mca, l, l, l);
      return;
    }
    // One or two edges split: rotate so that ab is split (and, for two, bc as well).
    if (!sab) {
      if (sbc) return cut(b, c, a, mbc, mca, mab, lbc, lca, lab, sbc, sca, sab);
      return cut(c, a, b, mca, mab, mbc, lca, lab, lbc, sca, sab, sbc);
    }
    if (count == 2 && !sbc) return cut(c, a, b, mca, mab, mbc, lca, lab, lbc, sca, sab, sbc);
    if (count == 1) {
      // The new edge from the midpoint to c lies inside: its level follows the split edge's.
      triangle(a, mab, c, lab + 1, lab + 1, lca);
      triangle(mab, b, c, lab + 1, lbc, lab + 1);
      return;
    }
    // ab and bc split (ca not).
    const int l = std::max(lab, lbc) + 1;
    triangle(mab, b, mbc, lab + 1, lbc + 1, l);
    triangle(a, mab, mbc, lab + 1, l, l);
    triangle(a, mbc, c, l, lbc + 1, lca);
  }

  const Seeing& seeing_;
  const Mesh& mesh_;
  int max_level_;
};

}  // namespace lightcone
