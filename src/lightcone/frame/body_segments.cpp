#include "lightcone/frame/body_segments.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <variant>

#include "lightcone/frame/shape_intersection.hpp"
#include "lightcone/frame/surface_coordinates.hpp"

namespace lightcone {

namespace {

// Where the segment origin + s direction, s in [0, 1], meets triangle (a, b, c), both sides
// (Moller & Trumbore, "Fast, minimum storage ray-triangle intersection", 1997).
bool segment_meets_triangle(const ShapeRay& ray, const Vec3& a, const Vec3& b, const Vec3& c,
                            SegmentHit& hit) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = cross(ray.direction, e2);
  const double det = dot(e1, p);
  if (det == 0) return false;  // parallel to the triangle's plane
  const double inverse = 1 / det;
  const Vec3 t = ray.origin - a;
  const double u = dot(t, p) * inverse;
  if (!(u >= 0 && u <= 1)) return false;
  const Vec3 q = cross(t, e1);
  const double v = dot(ray.direction, q) * inverse;
  if (!(v >= 0 && u + v <= 1)) return false;
  const double s = dot(e2, q) * inverse;
  if (!(s >= 0 && s <= 1)) return false;
  hit.s = s;
  hit.bary_u = u;
  hit.bary_v = v;
  return true;
}

// Whether the segment origin + s direction, s in [0, far], passes through the node's box (the
// box widened by rounding, so that a flat leaf's own triangles are never skipped).
bool meets_box(const MeshBvh::Node& node, const ShapeRay& ray, double far) {
  double in, out;
  if (!bounds_span(node.lower, node.upper, ray, in, out)) return false;
  const double leave = std::min(out, far);
  return std::max(in, 0.0) <= leave + 1e-12 * (1 + std::abs(leave));
}

// The nearest triangle of `mesh` that the segment meets, through its hierarchy.
std::optional<SegmentHit> nearest_on_mesh(const Mesh& mesh, const MeshBvh& bvh,
                                          const ShapeRay& ray) {
  if (bvh.nodes.empty()) return std::nullopt;
  std::optional<SegmentHit> nearest;
  SegmentHit hit;
  std::array<int, kMeshBvhMaxDepth> stack;
  int top = 0;
  int node = 0;
  while (true) {
    const MeshBvh::Node& n = bvh.nodes[static_cast<std::size_t>(node)];
    if (meets_box(n, ray, nearest ? nearest->s : 1.0)) {
      if (n.count == 0) {
        stack[static_cast<std::size_t>(top++)] = n.second;
        ++node;
        continue;
      }
      for (int i = n.first; i < n.first + n.count; ++i) {
        const std::uint32_t t = bvh.order[static_cast<std::size_t>(i)];
        const auto& tri = mesh.triangles[t];
        if (segment_meets_triangle(ray, mesh.positions[tri[0]], mesh.positions[tri[1]],
                                   mesh.positions[tri[2]], hit) &&
            (!nearest || hit.s < nearest->s)) {
          hit.prim = t;
          nearest = hit;
        }
      }
    }
    if (top == 0) return nearest;
    node = stack[static_cast<std::size_t>(--top)];
  }
}

}  // namespace

DirectBodySegments::DirectBodySegments(const ResolvedScene& scene)
    : scene_(scene), body_hierarchies_(scene.bodies.size(), nullptr) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (const auto* m = std::get_if<MeshShape>(&scene.bodies[i].object->shape)) {
      auto [it, added] = hierarchies_.try_emplace(m->mesh.get());
      if (added) it->second = build_mesh_bvh(*m->mesh);
      body_hierarchies_[i] = &it->second;
    }
}

std::optional<SegmentHit> DirectBodySegments::body_on_shape_segment(int body, const Vec3& from,
                                                                    const Vec3& to) const {
  const ShapeRay ray{from, to - from};
  const Shape& shape = scene_.bodies[body].object->shape;
  if (const auto* m = std::get_if<MeshShape>(&shape))
    return nearest_on_mesh(*m->mesh, *body_hierarchies_[static_cast<std::size_t>(body)], ray);
  double s = 0;
  if (!intersect_analytic(shape, ray, 0, 1, s)) return std::nullopt;
  return SegmentHit{s, 0, 0, 0};
}

void complete_surface_hit(const ResolvedScene& scene, const Vec3& incoming, Hit& hit,
                          unsigned prim) {
  const Object& object = *scene.bodies[hit.body].object;
  if (const auto* m = std::get_if<MeshShape>(&object.shape)) {
    // The point's barycentric coordinates in its triangle, for the texture coordinates.
    const Mesh& mesh = *m->mesh;
    const auto& tri = mesh.triangles[prim];
    const Vec3 a = mesh.positions[tri[0]], e1 = mesh.positions[tri[1]] - a,
               e2 = mesh.positions[tri[2]] - a, p = hit.shape_point - a;
    const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
    const double p1 = dot(p, e1), p2 = dot(p, e2), det = d11 * d22 - d12 * d12;
    mesh_surface(mesh, prim, (d22 * p1 - d12 * p2) / det, (d11 * p2 - d12 * p1) / det, hit);
  } else {
    analytic_surface(object.shape, hit);
  }
  hit.shape_normal = normalize(hit.shape_normal);
  if (dot(hit.shape_normal, incoming) > 0) hit.shape_normal = -hit.shape_normal;
}

}  // namespace lightcone
