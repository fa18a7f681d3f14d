// A ray through an analytic shape in its own coordinates (sphere, box, plane): where it enters
// and leaves, and where it first meets the surface within a parameter range (the texture
// coordinates and normal of the point met: frame/surface_coordinates.hpp). Inline: the tracer calls
// them for every ray a body's bounds let through.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <variant>

#include "lightcone/frame/surface_coordinates.hpp"
#include "lightcone/frame/surface_hit.hpp"
#include "lightcone/physics/vec.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct ShapeRay {
  Vec3 origin, direction;  // direction is not unit: the parameter is the common s
};

// The entry and exit parameters of a ray through a sphere or a box (false if it misses).
inline bool sphere_span(const Sphere& sphere, const ShapeRay& ray, double& in, double& out) {
  // In units of the radius, which leave the parameters as they are: the discriminant goes as the
  // fourth power of the lengths, which for a sphere of 1e100 (or 1e-100) units is no double.
  const double unit = sphere.radius > 0 ? 1 / sphere.radius : 1.0;
  const Vec3 o = ray.origin * unit, d = ray.direction * unit;
  const double r = sphere.radius * unit;  // 1, or 0 for a point
  const double a = dot(d, d), b = dot(o, d);
  const double c = dot(o, o) - r * r;
  const double disc = b * b - a * c;
  if (disc < 0 || a == 0) return false;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  in = q / a;
  out = c / q;
  if (in > out) std::swap(in, out);
  return true;
}

// The entry and exit parameters of a ray through the axis-aligned box from `lower` to `upper`.
inline bool bounds_span(const Vec3& lower, const Vec3& upper, const ShapeRay& ray, double& in,
                        double& out) {
  in = -std::numeric_limits<double>::infinity();
  out = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (ray.direction[i] == 0) {
      if (ray.origin[i] < lower[i] || ray.origin[i] > upper[i]) return false;
      continue;
    }
    const double inv = 1.0 / ray.direction[i];
    double t0 = (lower[i] - ray.origin[i]) * inv, t1 = (upper[i] - ray.origin[i]) * inv;
    if (t0 > t1) std::swap(t0, t1);
    in = std::max(in, t0);
    out = std::min(out, t1);
  }
  return in <= out;
}

inline bool box_span(const Box& box, const ShapeRay& ray, double& in, double& out) {
  return bounds_span(box.size * -0.5, box.size * 0.5, ray, in, out);
}

// The first end of a span [in, out] that lies in [tnear, tfar).
inline bool first_in(double in, double out, double tnear, double tfar, double& s) {
  if (in >= tnear && in < tfar) return s = in, true;
  if (out >= tnear && out < tfar) return s = out, true;
  return false;
}

inline bool intersect_sphere(const Sphere& sphere, const ShapeRay& ray, double tnear, double tfar,
                             double& s) {
  double in, out;
  return sphere_span(sphere, ray, in, out) && first_in(in, out, tnear, tfar, s);
}

inline bool intersect_box(const Box& box, const ShapeRay& ray, double tnear, double tfar,
                          double& s) {
  double in, out;
  return box_span(box, ray, in, out) && first_in(in, out, tnear, tfar, s);
}

inline bool intersect_plane(const Plane& plane, const ShapeRay& ray, double tnear, double tfar,
                            double& s) {
  if (ray.direction.y == 0) return false;
  const double t = -ray.origin.y / ray.direction.y;
  if (!(t >= tnear && t < tfar)) return false;
  const Vec3 p = ray.origin + ray.direction * t;
  if (std::abs(p.x) > plane.size_x * 0.5 || std::abs(p.z) > plane.size_z * 0.5) return false;
  s = t;
  return true;
}

// The same for any analytic shape (false for a mesh, which its own hierarchy meets).
inline bool intersect_analytic(const Shape& shape, const ShapeRay& ray, double tnear, double tfar,
                               double& s) {
  struct Visitor {
    const ShapeRay& ray;
    double tnear, tfar;
    double& s;
    bool operator()(const Sphere& x) const { return intersect_sphere(x, ray, tnear, tfar, s); }
    bool operator()(const Box& x) const { return intersect_box(x, ray, tnear, tfar, s); }
    bool operator()(const Plane& x) const { return intersect_plane(x, ray, tnear, tfar, s); }
    bool operator()(const MeshShape&) const { return false; }
  };
  return std::visit(Visitor{ray, tnear, tfar, s}, shape);
}

}  // namespace lightcone
