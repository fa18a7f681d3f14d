#include "lightcone/frame/mesh_bvh.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "lightcone/frame/resolved_scene.hpp"

namespace lightcone {
namespace {

constexpr int kLeafTriangles = 4;

struct BvhBuilder {
  const Mesh& mesh;
  std::vector<Vec3> centres;
  MeshBvh bvh;

  Bounds3 bounds_of(std::size_t begin, std::size_t end) const {
    Bounds3 b = empty_bounds();
    for (std::size_t i = begin; i < end; ++i)
      for (const std::uint32_t v : mesh.triangles[bvh.order[i]]) expand(b, mesh.positions[v]);
    return b;
  }

  void build(std::size_t begin, std::size_t end, int depth) {
    bvh.depth = std::max(bvh.depth, depth);
    const int index = static_cast<int>(bvh.nodes.size());
    bvh.nodes.emplace_back();
    const Bounds3 box = bounds_of(begin, end);
    bvh.nodes[index].lower = box.lower;
    bvh.nodes[index].upper = box.upper;
    // Median splits halve the count, so the depth stays within the stack for any mesh that
    // fits a texture; the guard keeps it there regardless.
    if (end - begin <= kLeafTriangles || depth == kMeshBvhMaxDepth) {
      bvh.nodes[index].count = static_cast<int>(end - begin);
      bvh.nodes[index].first = static_cast<int>(begin);
      return;
    }
    Bounds3 spread = empty_bounds();
    for (std::size_t i = begin; i < end; ++i) expand(spread, centres[bvh.order[i]]);
    const Vec3 size = spread.upper - spread.lower;
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
    const std::size_t middle = begin + (end - begin) / 2;
    std::nth_element(
        bvh.order.begin() + static_cast<std::ptrdiff_t>(begin),
        bvh.order.begin() + static_cast<std::ptrdiff_t>(middle),
        bvh.order.begin() + static_cast<std::ptrdiff_t>(end),
        [&](std::uint32_t a, std::uint32_t b) { return centres[a][axis] < centres[b][axis]; });
    build(begin, middle, depth + 1);
    bvh.nodes[index].second = static_cast<int>(bvh.nodes.size());
    build(middle, end, depth + 1);
  }
};

}  // namespace

MeshBall mesh_ball(const Mesh& mesh) {
  Vec3 lower = mesh.positions.empty() ? Vec3{} : mesh.positions[0], upper = lower;
  for (const Vec3& p : mesh.positions)
    for (int k = 0; k < 3; ++k) {
      lower[k] = std::min(lower[k], p[k]);
      upper[k] = std::max(upper[k], p[k]);
    }
  MeshBall ball{(lower + upper) * 0.5, 0};
  for (const Vec3& p : mesh.positions) ball.radius = std::max(ball.radius, length(p - ball.centre));
  ball.radius = ball.radius * (1 + 1e-6) + 1e-9;
  return ball;
}

MeshBvh build_mesh_bvh(const Mesh& mesh) {
  BvhBuilder builder{mesh, {}, {}};
  builder.centres.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    builder.centres.push_back((mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) /
                              3.0);
  builder.bvh.order.resize(mesh.triangles.size());
  std::iota(builder.bvh.order.begin(), builder.bvh.order.end(), 0u);
  if (!mesh.triangles.empty()) builder.build(0, mesh.triangles.size(), 1);
  return std::move(builder.bvh);
}

}  // namespace lightcone
