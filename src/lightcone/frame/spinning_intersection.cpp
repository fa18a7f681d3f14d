#include "lightcone/frame/spinning_intersection.hpp"

#include <algorithm>
#include <cmath>

#include "lightcone/physics/lorentz.hpp"

namespace lightcone {
namespace {

// The surface a chord crossed, by which side of it a point is: positive on the side the chord
// came from. A sphere |p|^2 = offset, or a plane normal . p = offset.
struct CrossedSurface {
  bool sphere = false;
  Vec3 normal;
  double offset = 0;
  double side(const Vec3& p) const { return (sphere ? dot(p, p) : dot(normal, p)) - offset; }
};

}  // namespace

ShapeHit intersect_spinning_body(const ResolvedSpin& spin, const Object& object,
                                 const MeshChordTest& mesh, const ShapeRay& frozen, double tau0,
                                 double tau1, double tnear, double tfar) {
  const Vec3 o = spin.rest_from_shape * frozen.origin;
  const Vec3 d = spin.rest_from_shape * frozen.direction;
  ShapeHit hit;
  // The part of the ray inside the ball that holds the shape at every angle.
  double in, out;
  if (!sphere_span(Sphere{spin.radius}, ShapeRay{o, d}, in, out)) return hit;
  const double lo = std::max(in, tnear), hi = std::min(out, tfar);
  if (!(lo < hi)) return hit;
  const auto shape_at = [&](double s) {
    return spin.shape_of_rest * rotated(spin.axis, -spin.rate * (tau0 + s * tau1), o + d * s);
  };
  const Shape& shape = object.shape;
  const Vec3& k = object.scale;
  if (spin.round) {
    // A round ball turning about its centre is the same ball at every angle: the straight
    // ray meets it where the curve does.
    double s;
    const double radius = std::get<Sphere>(shape).radius * std::abs(k.x);
    if (!intersect_sphere(Sphere{radius}, ShapeRay{o, d}, tnear, tfar, s)) return hit;
    hit.s = s;
    hit.rest_point = o + d * s;
    hit.proper_time = tau0 + s * tau1;
    hit.shape_point = shape_at(s);
    return hit;
  }
  const double sweep = std::abs(spin.rate * tau1) * (hi - lo);
  // A light ray crosses the ball in rest-frame time 2R, so the sweep is below twice the rim
  // speed; only the simultaneous picture (spacelike rays) can sweep more.
  const int chunks = std::isfinite(sweep)
                         ? static_cast<int>(std::clamp(std::ceil(sweep / kSpinChordAngle), 1.0,
                                                       static_cast<double>(kMaxSpinChords)))
                         : kMaxSpinChords;
  Vec3 pa = shape_at(lo);
  for (int k = 0; k < chunks; ++k) {
    const double sa = lo + (hi - lo) * k / chunks, sb = lo + (hi - lo) * (k + 1) / chunks;
    const Vec3 pb = shape_at(sb);
    const ShapeRay chord{pa, pb - pa};
    // The surface the chord meets, as a function that changes sign across it, and a chord
    // parameter on its far side.
    double far = 1;
    unsigned prim = 0;
    CrossedSurface surface;
    bool met = false;
    if (const auto* sphere = std::get_if<Sphere>(&shape)) {
      double a, b;
      if (sphere_span(*sphere, chord, a, b) && a >= 0 && a < 1) {
        met = true;
        far = std::min(1.0, 0.5 * (a + b));
        surface = {true, {}, sphere->radius * sphere->radius};
      }
    } else if (const auto* box = std::get_if<Box>(&shape)) {
      double a, b;
      if (box_span(*box, chord, a, b) && a >= 0 && a < 1) {
        met = true;
        far = std::min(1.0, 0.5 * (a + b));
        const Vec3 entry = chord.origin + chord.direction * a;
        const int axis = box_face_axis(*box, entry);
        const double face = std::copysign(box->size[axis] * 0.5, entry[axis]);
        Vec3 normal;
        normal[axis] = std::copysign(1.0, face);
        surface = {false, normal, std::abs(face)};
      }
    } else if (const auto* plane = std::get_if<Plane>(&shape)) {
      double a;
      if (intersect_plane(*plane, chord, 0, 1, a)) {
        met = true;
        surface = {false, {0, pa.y >= 0 ? 1.0 : -1.0, 0}, 0};
      }
    } else if (mesh) {
      if (const std::optional<SegmentHit> met_mesh = mesh(pa, pb)) {
        met = true;
        prim = met_mesh->prim;
        const Mesh& m = *std::get<MeshShape>(shape).mesh;
        const auto& tri = m.triangles[prim];
        const Vec3 v0 = m.positions[tri[0]];
        const Vec3 n = cross(m.positions[tri[1]] - v0, m.positions[tri[2]] - v0);
        const Vec3 outward = dot(n, pa - v0) >= 0 ? n : -n;
        surface = {false, outward, dot(outward, v0)};
      }
    }
    if (met) {
      // Bisection on the curve between the chunk's start (outside) and the far point.
      double s_out = sa, s_in = sa + far * (sb - sa);
      if (surface.side(shape_at(s_in)) <= 0) {
        for (int i = 0; i < 200; ++i) {
          const double mid = 0.5 * (s_out + s_in);
          if (mid == s_out || mid == s_in) break;
          (surface.side(shape_at(mid)) > 0 ? s_out : s_in) = mid;
        }
        hit.s = s_in;
      } else {
        hit.s = sa + far * (sb - sa);  // the curve grazes the surface: the chord's point
      }
      hit.prim = prim;
      hit.rest_point = o + d * hit.s;
      hit.proper_time = tau0 + hit.s * tau1;
      hit.shape_point = shape_at(hit.s);
      if (mesh) {
        // Barycentric coordinates of the point in its triangle's plane.
        const Mesh& m = *std::get<MeshShape>(shape).mesh;
        const auto& tri = m.triangles[prim];
        const Vec3 e1 = m.positions[tri[1]] - m.positions[tri[0]];
        const Vec3 e2 = m.positions[tri[2]] - m.positions[tri[0]];
        const Vec3 q = hit.shape_point - m.positions[tri[0]];
        const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
        const double q1 = dot(q, e1), q2 = dot(q, e2), det = d11 * d22 - d12 * d12;
        hit.bary_u = static_cast<float>((d22 * q1 - d12 * q2) / det);
        hit.bary_v = static_cast<float>((d11 * q2 - d12 * q1) / det);
      }
      return hit;
    }
    pa = pb;
  }
  return hit;
}

Vec3 complete_spinning_hit(const ResolvedScene& scene, const ResolvedBody& body,
                           const ShapeHit& exact, const Vec3& frozen_direction, Hit& hit) {
  // The point's own motion: rate axis x r in the rest frame, carried to F.
  const ResolvedSpin& spin = scene.spins[body.spin];
  hit.proper_time = exact.proper_time;
  hit.spin_angle = spin.rate * exact.proper_time;
  const Vec3 rest_velocity = cross(spin.axis, exact.rest_point) * spin.rate;
  hit.velocity = velocity_of(spin.trace_from_rest * Vec4{1, rest_velocity});
  return spin.shape_of_rest *
         rotated(spin.axis, -hit.spin_angle, spin.rest_from_shape * frozen_direction);
}

}  // namespace lightcone
