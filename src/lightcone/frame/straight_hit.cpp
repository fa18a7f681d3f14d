#include "lightcone/frame/straight_hit.hpp"

#include <algorithm>
#include <limits>

#include "lightcone/frame/shape_intersection.hpp"
#include "lightcone/frame/spinning_intersection.hpp"

namespace lightcone {

std::optional<Hit> first_straight_hit(const ResolvedScene& scene, const BodySegments& segments,
                                      const Vec3& u) {
  std::optional<Hit> nearest;
  double nearest_s = std::numeric_limits<double>::infinity();
  for (std::size_t index = 0; index < scene.bodies.size(); ++index) {
    const ResolvedBody& body = scene.bodies[index];
    const int b = static_cast<int>(index);
    // Where the ray (u s in F) can meet the body: within its bounds, before the nearest hit.
    double in, out;
    if (!bounds_span(body.trace_bounds.lower, body.trace_bounds.upper, ShapeRay{{0, 0, 0}, u}, in,
                     out))
      continue;
    in = std::max(in, 0.0);
    out = std::min(out, nearest_s);
    if (!(in <= out)) continue;
    const ShapeRay ray{body.shape_origin, body.shape_direction(u)};
    Hit hit;
    hit.body = b;
    unsigned prim = 0;
    Vec3 incoming = ray.direction;
    if (body.spin >= 0) {
      MeshChordTest mesh;
      if (std::holds_alternative<MeshShape>(body.object->shape))
        mesh = [&segments, b](const Vec3& from, const Vec3& to) {
          return segments.body_on_shape_segment(b, from, to);
        };
      // The camera ray leaves the origin event of F; the body's clock along it.
      const double tau0 = body.proper_time(Vec4{0, {0, 0, 0}});
      const double tau1 = body.proper_time_row.t * scene.ray_time + dot(body.proper_time_row.x, u);
      const ShapeHit exact = intersect_spinning_body(scene.spins[body.spin], *body.object, mesh,
                                                     ray, tau0, tau1, in, out);
      if (!(exact.s <= out)) continue;
      hit.s = exact.s;
      hit.shape_point = exact.shape_point;
      prim = exact.prim;
      incoming = complete_spinning_hit(scene, body, exact, ray.direction, hit);
    } else {
      const Vec3 from = ray.origin + ray.direction * in, to = ray.origin + ray.direction * out;
      const std::optional<SegmentHit> met = segments.body_on_shape_segment(b, from, to);
      if (!met) continue;
      hit.s = in + met->s * (out - in);
      hit.shape_point = from + (to - from) * met->s;
      prim = met->prim;
      hit.proper_time = body.proper_time(Vec4{scene.ray_time * hit.s, u * hit.s});
      hit.velocity = body.velocity;
    }
    complete_surface_hit(scene, incoming, hit, prim);
    nearest = hit;
    nearest_s = hit.s;
  }
  return nearest;
}

}  // namespace lightcone
