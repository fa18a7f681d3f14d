// The tessellation's edge rule, for every way a shape point can be seen (straight rays in flat
// spacetime, the images of each order near a black hole): a triangle's edges are split at their
// midpoints until each is drawn within the error bound, and the triangle is cut by how many of
// its edges split. Each edge's split depends only on its own ends and level, so neighbouring
// triangles agree (no cracks) (docs/design/raster.md).
#pragma once

#include <algorithm>
#include <vector>

#include "lightcone/physics/vec.hpp"

namespace lightcone {

// `Seeing` provides
//   Corner corner(const Vec3& shape_point) const;  // where the point is seen (Corner has .p)
//   Corner middle(const Corner& a, const Corner& b, const Vec3& shape_point) const;  // the same,
//       for the midpoint of edge ab (which may start from where a and b are seen)
//   bool needs_split(const Corner& a, const Corner& b, const Corner& middle) const;
//   void emit(const Corner& a, const Corner& b, const Corner& c) const;
// and optionally
//   bool surely_whole(const Corner& a, const Corner& b) const;  // true only where needs_split
//       would say no whatever the midpoint: the edge is then left whole without it
// and a midpoint rule `mesh.midpoint(a, b)` comes from the RestMesh.
//
// Every edge is decided once, with all its halves down to the last level (an edge that splits
// is always cut into its two halves, whichever way its triangles are cut): the mesh's edges
// before their triangles (decide(), once for both triangles that share each), and each edge a
// cut makes inside a triangle before the two triangles that share it. Deciding each half in
// each triangle that has it instead took twice the midpoints.
template <class Seeing, class Mesh>
class AdaptiveSplit {
 public:
  using Corner = typename Seeing::Corner;

  // An edge's decisions, as seen from one of its ends (`reversed`: from the other end than the
  // one it was decided from); node < 0: not split.
  struct Edge {
    int node = -1;
    bool reversed = false;
    Edge flipped() const { return {node, !reversed}; }
  };

  // A split edge's midpoint and its halves' decisions.
  struct Node {
    Corner middle;
    Edge halves[2];  // from the end it was decided from, and to the other
  };
  // `nodes`: where the decisions are kept, cleared here (a caller keeps it, so that a frame like
  // the last allocates nothing).
  AdaptiveSplit(const Seeing& seeing, const Mesh& mesh, int max_level, std::vector<Node>& nodes)
      : seeing_(seeing), mesh_(mesh), max_level_(max_level), nodes_(nodes) {
    nodes_.clear();
  }

  // Edge ab at `level` and all its halves. (a and b are not the nodes' own: deciding moves
  // them.)
  Edge decide(const Corner& a, const Corner& b, int level) const {
    if (level >= max_level_) return {};
    if constexpr (requires { seeing_.surely_whole(a, b); })
      if (seeing_.surely_whole(a, b)) return {};
    const Corner middle = seeing_.middle(a, b, mesh_.midpoint(a.p, b.p));
    if (!seeing_.needs_split(a, b, middle)) return {};
    const int node = static_cast<int>(nodes_.size());
    nodes_.push_back({middle, {}});
    const Edge first = decide(a, middle, level + 1);
    const Edge second = decide(middle, b, level + 1);
    nodes_[node].halves[0] = first;
    nodes_[node].halves[1] = second;
    return {node, false};
  }

  // Triangle (a, b, c) at level 0, its edges decided here.
  void triangle(const Corner& a, const Corner& b, const Corner& c) const {
    triangle(a, b, c, decide(a, b, 0), decide(b, c, 0), decide(c, a, 0));
  }

  // Triangle (a, b, c) at level 0 whose edges ab, bc, ca were decided beforehand.
  void triangle(const Corner& a, const Corner& b, const Corner& c, Edge ab, Edge bc,
                Edge ca) const {
    cut(a, b, c, ab, bc, ca, 0, 0, 0);
  }

 private:
  const Corner& middle(Edge e) const { return nodes_[e.node].middle; }
  // The half of split edge e from its start, and the half to its end (seen as e is).
  Edge first_half(Edge e) const {
    const Node& n = nodes_[e.node];
    return e.reversed ? n.halves[1].flipped() : n.halves[0];
  }
  Edge second_half(Edge e) const {
    const Node& n = nodes_[e.node];
    return e.reversed ? n.halves[0].flipped() : n.halves[1];
  }

  // Triangle (a, b, c) with its edges' decisions and levels.
  void cut(const Corner& a, const Corner& b, const Corner& c, Edge ab, Edge bc, Edge ca, int lab,
           int lbc, int lca) const {
    const bool sab = ab.node >= 0, sbc = bc.node >= 0, sca = ca.node >= 0;
    const int count = int(sab) + int(sbc) + int(sca);
    if (count == 0) return seeing_.emit(a, b, c);
    if (count == 3) {
      const int l = std::max({lab, lbc, lca}) + 1;
      // (Copies: deciding the inner edges may move the nodes.)
      const Corner mab = middle(ab), mbc = middle(bc), mca = middle(ca);
      const Edge inner_ab_ca = decide(mab, mca, l), inner_bc_ab = decide(mbc, mab, l),
                 inner_ca_bc = decide(mca, mbc, l);
      cut(a, mab, mca, first_half(ab), inner_ab_ca, second_half(ca), lab + 1, l, lca + 1);
      cut(mab, b, mbc, second_half(ab), first_half(bc), inner_bc_ab, lab + 1, lbc + 1, l);
      cut(mca, mbc, c, inner_ca_bc, second_half(bc), first_half(ca), l, lbc + 1, lca + 1);
      cut(mab, mbc, mca, inner_bc_ab.flipped(), inner_ca_bc.flipped(), inner_ab_ca.flipped(), l, l,
          l);
      return;
    }
    // One or two edges split: rotate so that ab is split (and, for two, bc as well).
    if (!sab) {
      if (sbc) return cut(b, c, a, bc, ca, ab, lbc, lca, lab);
      return cut(c, a, b, ca, ab, bc, lca, lab, lbc);
    }
    if (count == 2 && !sbc) return cut(c, a, b, ca, ab, bc, lca, lab, lbc);
    const Corner mab = middle(ab);
    if (count == 1) {
      // The new edge from the midpoint to c lies inside: its level follows the split edge's.
      const Edge inner = decide(mab, c, lab + 1);
      cut(a, mab, c, first_half(ab), inner, ca, lab + 1, lab + 1, lca);
      cut(mab, b, c, second_half(ab), bc, inner.flipped(), lab + 1, lbc, lab + 1);
      return;
    }
    // ab and bc split (ca not).
    const int l = std::max(lab, lbc) + 1;
    const Corner mbc = middle(bc);
    const Edge inner_ab_bc = decide(mab, mbc, l), inner_a_bc = decide(a, mbc, l);
    cut(mab, b, mbc, second_half(ab), first_half(bc), inner_ab_bc.flipped(), lab + 1, lbc + 1, l);
    cut(a, mab, mbc, first_half(ab), inner_ab_bc, inner_a_bc.flipped(), lab + 1, l, l);
    cut(a, mbc, c, inner_a_bc, second_half(bc), ca, l, lbc + 1, lca);
  }

  const Seeing& seeing_;
  const Mesh& mesh_;
  int max_level_;
  std::vector<Node>& nodes_;
};

}  // namespace lightcone
