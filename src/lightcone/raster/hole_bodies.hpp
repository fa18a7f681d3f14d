// The raster renderer's bodies near a black hole (docs/design/black-hole.md, "The raster
// renderer"): each body is drawn once per image order, 0 (the primary image) and 1 (the
// secondary, round the far side). Every vertex is a point of the body seen along that order's
// exact ray from its own retarded event (frame/locate.hpp, hole_body_point_image), and the
// tessellation splits edges until the drawn chord lies within half a pixel of the image of the
// edge's midpoint, so that the straight edges bend as the lens bends them.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/hole_leg_starts.hpp"
#include "lightcone/frame/hole_view.hpp"
#include "lightcone/frame/lighting.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/physics/hole_world_line.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/tessellation.hpp"

namespace lightcone {

// The image orders drawn: what lies beyond (orders >= 2, squeezed against the shadow's edge)
// is left to the ray tracer.
constexpr int kRasterHoleOrders = 2;

// Per vertex: its apparent position in F (the look direction times the coordinate time the
// light took, which orders the images met along one ray), its shape point, ln g and the body's
// clock at its emission; for a lit body the linear RGB it sends the camera in each of its
// material's two fixed colours (zero for an emitter, whose colour comes from its rows); on a
// mesh with texture coordinates, the face's coordinates at the point (triangle_uv_map); and the
// angle its light swept about the hole from the camera (hole_swept_angle), which an accretion
// disk crossed at a smaller angle on the same ray hides.
constexpr int kHoleVertexFloats = 17;

// The angle swept about the hole by the light of image `order` (0 or 1) from a point, relative
// to the hole, to a camera in direction `outward` from it: the angle between them for the
// direct image, the rest of the turn for the one round the far side. frame/curved_ray.cpp's
// follow_curved_ray measures a disk's crossings, and the bodies met, by this angle from the
// camera along a ray.
double hole_swept_angle(const Vec3& from_hole, const Vec3& outward, int order);

// A lit body: its colours per vertex are the ray tracer's Lighting at the vertex's surface
// point (a lit texture's albedo the texel there, read as the tracer reads it), and a lit edge
// longer than a pixel is also split until the colours interpolated along it lie within 1/128
// of the brightest of them.
struct HoleLitBody {
  const Lighting* lighting = nullptr;
  std::size_t body = 0;                          // in the resolved scene's bodies
  std::array<const PointEmission*, 2> albedo{};  // its fixed colours (the same twice for one)
  // A lit texture's albedo at a point: the emission table's (EmissionTable::surface) for
  // object `object` (in the scene's objects); null for fixed colours.
  const EmissionTable* texture_albedo = nullptr;
  std::size_t object = 0;
  // Where its lights' legs start their solves (the last ones solved), where given: its
  // vertices follow one another across the body, as a tile's points do in the tracer.
  HoleLegStarts* leg_starts = nullptr;
};

// Appends the triangles of image `order` of the body drawn with `mesh` on `line` (in units of the
// hole's mass: hole_world_line(hole, object), frame/hole_view.hpp). A triangle is
// left out where a corner has no image of this order (inside the horizon) and where the body's
// emission points wind round the line through the hole and the camera: such a triangle's image
// wraps round the shadow (an Einstein ring) and has no straight-edged drawing.
void tessellate_hole_image(const ResolvedScene& scene, const Object& object,
                           const HoleWorldLine& line, const RestMesh& mesh, int order,
                           const TessellationLimits& limits, std::vector<float>& out,
                           const HoleLitBody* lit = nullptr);

// The bodies' images as one vertex buffer, drawn with the program for them
// (shaders/hole_body.vert and .frag); needs a current OpenGL 3.3 context.
class HoleBodiesPass {
 public:
  // A body to draw: its colour rows and pattern (as the flat bodies' draws).
  struct Body {
    std::size_t index = 0;  // in the resolved scene's bodies
    const RestMesh* mesh = nullptr;
    int first_row = 0, pattern = 0;
    bool lit = false;
    GLuint texture = 0;  // an unlit texture's image (pattern 2)
  };

  HoleBodiesPass();
  ~HoleBodiesPass();
  HoleBodiesPass(const HoleBodiesPass&) = delete;
  HoleBodiesPass& operator=(const HoleBodiesPass&) = delete;

  // Its program, built with the first frame that needs it: with `disk`, each fragment also
  // follows its pixel's ray to the accretion disk (shaders/black_hole.glsl) and is left out
  // where the disk is crossed first; with `surface_variables`, the fragments write what the
  // output variables need instead of a colour (raster/surface_variables.cpp).
  GLuint program(bool disk, bool surface_variables = false);
  // Tessellates each body's images of orders 0 and 1 (in parallel) and uploads them; returns
  // the number of triangles. The meshes, `emission` and `lighting` need only last the call.
  std::size_t prepare(const ResolvedScene& scene, const std::vector<Body>& bodies,
                      const EmissionTable& emission, const Lighting& lighting,
                      const TessellationLimits& limits);
  // The least and greatest ln g of the prepared vertices (none without vertices).
  std::optional<LogShiftRange> log_shift_range() const { return log_shift_range_; }
  // Draws them with `program` (program(disk)) in use, its camera, colour and (with a disk) black
  // hole uniforms set.
  void draw(const ResolvedScene& scene, GLuint program) const;

 private:
  struct Draw {
    Body body;
    GLint first_vertex = 0;
    GLsizei vertex_count = 0;
  };
  GLuint programs_[2][2] = {{0, 0}, {0, 0}};
  GLuint vertex_array_ = 0, vertex_buffer_ = 0;
  std::vector<Draw> draws_;
  std::optional<LogShiftRange> log_shift_range_;
};

// The CPU's part of HoleBodiesPass::prepare: each body's vertices of orders 0 and 1, in that
// order (kHoleVertexFloats each), tessellated in parallel.
std::vector<std::vector<float>> hole_body_vertices(const ResolvedScene& scene,
                                                   const std::vector<HoleBodiesPass::Body>& bodies,
                                                   const EmissionTable& emission,
                                                   const Lighting& lighting,
                                                   const TessellationLimits& limits);

}  // namespace lightcone
