// Adaptive tessellation for the real-time renderer: a straight edge of a moving body is seen as
// a curve (each of its points is seen at its own retarded event), while the rasteriser draws
// the chord between its ends. Edges are split until their apparent midpoint lies within half a
// pixel of where the rasteriser draws it (docs/design/raster.md).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/resolved_scene.hpp"

namespace lightcone {

// A body's world-lines for one frame: the shape point p is at
// shape_to_trace (p - shape_origin) + velocity t in F at F-time t (the inverse of the map from F
// events to shape coordinates that ResolvedBody holds).
struct BodyView {
  Mat3 shape_to_trace;
  Vec3 shape_origin;
  Vec3 velocity;
  TraceWorldLine world_line(const Vec3& shape_point) const {
    return {shape_to_trace * (shape_point - shape_origin), velocity};
  }
  // A spinning body: each shape point turns on its own world-line in the rest frame of the
  // body's centre, with coordinates (its proper time, rest_from_shape of the frozen shape
  // coordinates) = rest_of_trace(F event).
  const ResolvedSpin* spin = nullptr;
  AffineMap4 rest_of_trace, trace_of_rest;
  Vec3 trace_velocity_at_rest;  // F's velocity in those coordinates (0: classical picture)
};
BodyView body_view(const ResolvedScene& scene, const ResolvedBody& body);

// The shape's triangles in shape coordinates before tessellation, and how an edge's midpoint
// is found: the chord's for flat faces, the great circle's for a sphere (so that tessellation
// also follows the sphere's curvature).
struct RestMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // A mesh's texture coordinates per vertex, empty when it has none (Mesh::uvs).
  std::vector<std::array<float, 2>> uvs;
  double sphere_radius = 0;  // > 0: a sphere about the origin
  // Each edge once (its two vertices, the lower index first; of vertices at one point, the
  // lowest index stands for all), and each triangle's edges ab, bc, ca as indices into it, so
  // that an edge two triangles share is decided once.
  std::vector<std::array<std::uint32_t, 2>> edges;
  std::vector<std::array<std::uint32_t, 3>> triangle_edges;
  // A closed surface, its triangles turning counter-clockwise seen from outside: each edge
  // shared by two triangles that run along it in opposite directions, enclosing a positive
  // volume.
  bool closed_outward = false;
  Vec3 midpoint(const Vec3& a, const Vec3& b) const;
};
// Box faces start as face_grid x face_grid quads and planes as 4 face_grid x 4 face_grid, so
// that no triangle is large against its body and long edges reach their curvature within the
// maximum level (2 for the CPU path's 2^10 pieces an edge, 8 for the GPU's 64).
RestMesh rest_mesh(const Shape& shape, int face_grid = 2);
// The identity of a shape (its alternative's address): bodies sharing a Shape share its mesh.
inline const void* shape_identity(const Shape& shape) {
  return std::visit([](const auto& x) -> const void* { return &x; }, shape);
}

// The drawn triangles that the rasteriser may skip as hidden (docs/design/raster.md): a closed
// surface seen from outside hides every face it turns away from the camera, and the apparent
// surface of a closed body is closed and keeps its orientation, since the map from shape points
// to where they are seen is one to one and orientation-preserving. The faces turned away are
// those wound clockwise on screen (OpenGL's back faces) or, for a mirrored body (scale of
// negative determinant), counter-clockwise. None are skipped for an open or unoriented mesh,
// a spinning body, or a camera within the body's trace capsule.
enum class HiddenFaces { kNone, kBack, kFront };
HiddenFaces hidden_faces(const RestMesh& mesh, const ResolvedBody& body);

// Where a shape point is seen: its event on the camera's ray family and that event's image
// point (pixels), for the tessellation's decisions.
struct ApparentPoint {
  Vec3 position;  // in F, relative to the camera (the vertex the GPU draws)
  ImagePoint image;
};
ApparentPoint apparent_point(const ResolvedScene& scene, const BodyView& view,
                             const Vec3& shape_point);

// How far, in pixels, the apparent midpoint of an edge (seen at `midpoint`, its ends at a and b)
// lies from where the rasteriser draws it: the projection of the midpoint of the chord between the
// apparent ends (clip space is linear in the apparent positions, so that is where the midpoint's
// attributes land, not at the midpoint of the projected ends); the same from both ends.
double edge_error_pixels(const CameraBasis& camera, const ApparentPoint& a, const ApparentPoint& b,
                         const ApparentPoint& midpoint);

// An upper bound on edge_error_pixels for the straight edges of one body without spin, seen on
// the scene's ray family, from an edge's ends alone (where it is well in front of the camera;
// infinity elsewhere): edges it shows to be within the error bound are left whole without their
// midpoints. The per-body parts are worked out once.
class EdgeErrorBound {
 public:
  EdgeErrorBound(const ResolvedScene& scene, const BodyView& view);
  // Between shape points shape_a and shape_b, seen at a and b (`distance_*`: the length of
  // their apparent positions, worked out once per point).
  double pixels(const Vec3& shape_a, const ApparentPoint& a, double distance_a, const Vec3& shape_b,
                const ApparentPoint& b, double distance_b) const;

 private:
  const CameraBasis& camera_;
  const Mat3& shape_to_trace_;
  Vec3 beta_, direction_;  // the body's velocity in F, and its direction (0 at rest)
  double speed_ = 0, one_minus_beta2_ = 1, focal_ = 1;
  bool delayed_ = false;  // light delay on: the ray family is backward light rays
};

// Whether any point of `bounds` (in F, relative to the camera) can lie in the camera's view:
// false when all of it lies beyond one side of the view or behind the camera. A body whose
// trace bounds (every event where a camera ray can meet it) fail this is not drawn.
bool may_be_in_view(const CameraBasis& camera, const Bounds3& bounds);

// The depth buffer holds the light travel distance (near a black hole, the light's coordinate
// time of flight) on a log scale between these.
inline constexpr float kDepthNear = 1e-6f, kDepthFar = 1e12f;

struct TessellationLimits {
  double max_error_pixels = 0.5;
  int max_level = 10;  // an edge is split into at most 2^max_level pieces
};

// A triangle's texture coordinates over its plane as an affine map of the shape point p: rows
// (a, b) with uv = (a.xyz . p + a.w, b.xyz . p + b.w), the barycentric interpolation of its
// corners' coordinates that the ray tracer does at a hit (complete_surface_hit). Zero for a
// degenerate triangle.
std::array<double, 8> triangle_uv_map(const std::array<Vec3, 3>& corners,
                                      const std::array<std::array<float, 2>, 3>& uvs);

// Appends the tessellated triangles to `out`: per vertex its apparent position (in F, relative
// to the camera: apparent_point) and the plane of the untessellated triangle it lies in, in
// shape coordinates (unit normal, offset), seven floats; and where `uv_maps` is
// given, to it the texture coordinates' map of that triangle (triangle_uv_map, zero for a mesh
// without them), eight floats a vertex. Each edge's split depends only on its own ends and
// level, so neighbouring triangles agree (no cracks). Triangles that the rasteriser would cull as
// `hidden` (hidden_faces) are left out, so that no vertex is shaded for them.
void tessellate(const ResolvedScene& scene, const BodyView& view, const RestMesh& mesh,
                const TessellationLimits& limits, std::vector<float>& out,
                std::vector<float>* uv_maps = nullptr, HiddenFaces hidden = HiddenFaces::kNone);

// A shape's untessellated triangles for the tessellation shaders (on the GPU), laid out as
// tessellate() lays out its own but with each vertex's shape point, not its apparent position.
void rest_patches(const RestMesh& mesh, std::vector<float>& out,
                  std::vector<float>* uv_maps = nullptr);

}  // namespace lightcone
