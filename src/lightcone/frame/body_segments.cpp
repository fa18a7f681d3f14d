#include "lightcone/frame/body_segments.hpp"

#include <algorithm>
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

DirectBodySegments::DirectBodySegments(const ResolvedScene& scene)
    : scene_(scene), mesh_balls_(scene.bodies.size()) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (const auto* m = std::get_if<MeshShape>(&scene.bodies[i].object->shape))
      mesh_balls_[i] = mesh_ball(*m->mesh);
}

std::optional<SegmentHit> DirectBodySegments::body_on_shape_segment(int body, const Vec3& from,
                                                                    const Vec3& to) const {
  const ShapeRay ray{from, to - from};
  const Shape& shape = scene_.bodies[body].object->shape;
  if (const auto* m = std::get_if<MeshShape>(&shape)) {
    const MeshBall& ball = mesh_balls_[body];
    double in, out;
    if (!sphere_span(Sphere{ball.radius}, ShapeRay{ray.origin - ball.centre, ray.direction}, in,
                     out) ||
        out < 0 || in > 1)
      return std::nullopt;
    const Mesh& mesh = *m->mesh;
    std::optional<SegmentHit> nearest;
    SegmentHit hit;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
      const auto& tri = mesh.triangles[i];
      if (segment_meets_triangle(ray, mesh.positions[tri[0]], mesh.positions[tri[1]],
                                 mesh.positions[tri[2]], hit) &&
          (!nearest || hit.s < nearest->s)) {
        hit.prim = static_cast<unsigned>(i);
        nearest = hit;
      }
    }
    return nearest;
  }
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
    const double bu = (d22 * p1 - d12 * p2) / det, bv = (d11 * p2 - d12 * p1) / det;
    const double bw = 1 - bu - bv;
    if (!mesh.uvs.empty())
      for (int k = 0; k < 2; ++k)
        hit.uv[k] = mesh.uvs[tri[0]][k] * bw + mesh.uvs[tri[1]][k] * bu + mesh.uvs[tri[2]][k] * bv;
    hit.shape_normal = cross(e1, e2);
  } else {
    analytic_surface(object.shape, hit);
  }
  hit.shape_normal = normalize(hit.shape_normal);
  if (dot(hit.shape_normal, incoming) > 0) hit.shape_normal = -hit.shape_normal;
}

}  // namespace lightcone
