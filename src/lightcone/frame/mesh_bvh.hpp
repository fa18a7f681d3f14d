// A mesh's bounds for meeting it: the ball that holds it (the tracer's test before Embree's), and
// its triangles in a bounding-volume hierarchy of its own, for the renderers that meet meshes
// without Embree: the raster renderer's exact shadows (raster/shadow_casters.hpp, which hands it
// to lighting.glsl's traversal) and the segments of curved rays met directly (body_segments.hpp,
// DirectBodySegments).
#pragma once

#include <cstdint>
#include <vector>

#include "lightcone/physics/vec.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The ball about a mesh's bounds centre that holds it, in its shape coordinates (widened by a
// part in a million for rounding): a segment that misses it misses the mesh.
struct MeshBall {
  Vec3 centre;
  double radius = 0;
};
MeshBall mesh_ball(const Mesh& mesh);

// Nodes depth first, each an inner node (its first child the next node, `second` the other) or
// a leaf (`count` triangles from `first` of `order`), every node's box holding its triangles.
struct MeshBvh {
  struct Node {
    Vec3 lower, upper;
    int count = 0;   // 0 for an inner node
    int second = 0;  // inner: the index of its second child
    int first = 0;   // leaf: its first triangle in `order`
  };
  std::vector<Node> nodes;
  std::vector<std::uint32_t> order;  // the mesh's triangles, leaf by leaf
  int depth = 0;                     // the most nodes on a path from the root
};

// The most nodes on a root-to-leaf path: the traversal stacks (lighting.glsl's too) hold this
// many.
inline constexpr int kMeshBvhMaxDepth = 32;

// Median splits along the widest axis of the triangles' centres, at most 4 triangles a leaf.
MeshBvh build_mesh_bvh(const Mesh& mesh);

}  // namespace lightcone
