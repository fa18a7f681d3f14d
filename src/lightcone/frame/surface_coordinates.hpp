// The texture coordinates and normal of a point on a shape's surface (an analytic shape's, or a
// mesh triangle's), in its own coordinates: where the tracer's rays meet them
// (frame/shape_intersection.hpp) and where the raster renderer's vertices near a black hole lie
// (raster/hole_bodies.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <variant>

#include "lightcone/frame/surface_hit.hpp"
#include "lightcone/physics/vec.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

inline std::array<double, 2> sphere_uv(const Vec3& p) {
  const Vec3 n = normalize(p);
  return {0.5 + std::atan2(n.x, n.z) / (2 * std::numbers::pi),
          std::acos(std::clamp(n.y, -1.0, 1.0)) / std::numbers::pi};
}

// The face of the box a surface point lies on: the axis where it is relatively farthest out.
inline int box_face_axis(const Box& box, const Vec3& p) {
  const Vec3 rel = component_div(p, box.size);
  int axis = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(rel[i]) > std::abs(rel[axis])) axis = i;
  return axis;
}

// Each face shows the whole image, read from outside the box the right way round (not
// mirrored): the side faces upright, the top with its image's top toward -z, the bottom toward
// +z (docs/scene-format.md, "Texture coordinates").
inline std::array<double, 2> box_uv(const Box& box, const Vec3& p, int axis) {
  const Vec3 rel = component_div(p, box.size);
  const double outward = p[axis] < 0 ? -1.0 : 1.0;
  if (axis == 0) return {0.5 - outward * rel.z, 0.5 - rel.y};
  if (axis == 1) return {0.5 + rel.x, 0.5 + outward * rel.z};
  return {0.5 + outward * rel.x, 0.5 - rel.y};
}

inline std::array<double, 2> plane_uv(const Plane& plane, const Vec3& p) {
  return {0.5 + p.x / plane.size_x, 0.5 + p.z / plane.size_z};
}

// The texture coordinates and normal of an analytic shape's surface point. Points on flat faces
// are put exactly on the face, so that procedural patterns (a checker boundary at the face) do
// not flip with rounding.
inline void analytic_surface(const Shape& shape, Hit& hit) {
  if (const auto* sphere = std::get_if<Sphere>(&shape)) {
    // In units of the radius: the point's square need not be a double.
    const Vec3 n = hit.shape_point / sphere->radius;
    hit.uv = sphere_uv(n);
    hit.shape_normal = n;
  } else if (const auto* box = std::get_if<Box>(&shape)) {
    const int axis = box_face_axis(*box, hit.shape_point);
    hit.shape_point[axis] = std::copysign(box->size[axis] * 0.5, hit.shape_point[axis]);
    hit.uv = box_uv(*box, hit.shape_point, axis);
    hit.shape_normal[axis] = std::copysign(1.0, hit.shape_point[axis]);
  } else if (const auto* plane = std::get_if<Plane>(&shape)) {
    hit.shape_point.y = 0;
    hit.uv = plane_uv(*plane, hit.shape_point);
    hit.shape_normal = {0, 1, 0};
  }
}

// The texture coordinates (where the mesh has them) and the normal, not of unit length, of
// mesh triangle `prim` at the point of barycentric coordinates (bu, bv) of its second and third
// corners.
inline void mesh_surface(const Mesh& mesh, unsigned prim, double bu, double bv, Hit& hit) {
  const auto& tri = mesh.triangles[prim];
  const double bw = 1 - bu - bv;
  if (!mesh.uvs.empty())
    for (int k = 0; k < 2; ++k)
      hit.uv[k] = mesh.uvs[tri[0]][k] * bw + mesh.uvs[tri[1]][k] * bu + mesh.uvs[tri[2]][k] * bv;
  hit.shape_normal = cross(mesh.positions[tri[1]] - mesh.positions[tri[0]],
                           mesh.positions[tri[2]] - mesh.positions[tri[0]]);
}

}  // namespace lightcone
