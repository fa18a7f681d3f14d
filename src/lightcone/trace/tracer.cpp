#include "lightcone/trace/tracer.hpp"

#include <embree3/rtcore.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace lightcone {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Embree lets the application extend the intersect context; we carry the exact (double) rays,
// an origin event and a 4-direction each (in F for camera rays, in W for shadow rays), so that
// the body callbacks do not work from Embree's float copy of their spatial part. A ray's Embree
// id is its index here: Embree may reorder a packet's rays when it calls back.
struct ExactRay {
  Vec4 origin, direction;
};
struct TraceContext {
  RTCIntersectContext embree;
  ExactRay rays[Tracer::kPacketSize];
};

struct ShapeRay {
  Vec3 origin, direction;  // direction is not unit: the parameter is the common s
};

struct ShapeHit {
  double s = kInfinity;
  unsigned prim = 0;
  float bary_u = 0, bary_v = 0;
  // On a spinning body: the point met in shape coordinates and in the rest frame, and the
  // body's clock there.
  Vec3 shape_point, rest_point;
  double proper_time = 0;
};

// A spinning body's turn is sampled along each ray so that the chords between samples stay
// within R (1 - cos(angle / 2)) ~ 1.1e-4 R of the true path through the shape's coordinates
// (docs/design/spinning-bodies.md); the hit is then solved on the true path exactly.
constexpr double kSpinChordAngle = 0.03;
constexpr int kMaxSpinChords = 4096;

// A labelled light's shadow bounds (ShadowLight) are kLabelParts motion-blur BVHs, each over an
// equal part of its labels, with bounds at evenly spaced time steps: 3 a part for a point, spot
// or sphere light, 2 (which is exact: its bounds move linearly with the label) for a directional
// one. One BVH over all labels does far worse in dense swarms of fast bodies: bodies moving
// apart over the whole range loosen its inner nodes, and Embree's builder joins steps into
// leaves whose linear bounds hold the bodies' curved paths loosely.
constexpr unsigned kLabelParts = 8;
constexpr unsigned kPointLightPartSteps = 3;
// A camera packet's rays through a moving mesh go through the mesh's BVH as a packet where at
// least kMinMeshPacket of them meet its ball there within kCoherentTriangles triangle sizes of
// each other (rays farther apart take different paths down the BVH: one by one is faster).
constexpr unsigned kMinMeshPacket = 4;
constexpr double kCoherentTriangles = 4;

// The surface a chord crossed, by which side of it a point is: positive on the side the chord
// came from. A sphere |p|^2 = offset, or a plane normal . p = offset.
struct CrossedSurface {
  bool sphere = false;
  Vec3 normal;
  double offset = 0;
  double side(const Vec3& p) const { return (sphere ? dot(p, p) : dot(normal, p)) - offset; }
};

// The entry and exit parameters of a ray through a sphere or a box (false if it misses).
bool sphere_span(const Sphere& sphere, const ShapeRay& ray, double& in, double& out) {
  const double a = dot(ray.direction, ray.direction), b = dot(ray.origin, ray.direction);
  const double c = dot(ray.origin, ray.origin) - sphere.radius * sphere.radius;
  const double disc = b * b - a * c;
  if (disc < 0 || a == 0) return false;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  in = q / a;
  out = c / q;
  if (in > out) std::swap(in, out);
  return true;
}

bool box_span(const Box& box, const ShapeRay& ray, double& in, double& out) {
  in = -kInfinity;
  out = kInfinity;
  for (int i = 0; i < 3; ++i) {
    const double h = box.size[i] * 0.5;
    if (ray.direction[i] == 0) {
      if (std::abs(ray.origin[i]) > h) return false;
      continue;
    }
    const double inv = 1.0 / ray.direction[i];
    double t0 = (-h - ray.origin[i]) * inv, t1 = (h - ray.origin[i]) * inv;
    if (t0 > t1) std::swap(t0, t1);
    in = std::max(in, t0);
    out = std::min(out, t1);
  }
  return in <= out;
}

// The first end of a span [in, out] that lies in [tnear, tfar).
bool first_in(double in, double out, double tnear, double tfar, double& s) {
  if (in >= tnear && in < tfar) return s = in, true;
  if (out >= tnear && out < tfar) return s = out, true;
  return false;
}

// A ray as Embree traces it, in single precision, with no hit yet (the parameter range clamped
// to what a float holds).
RTCRayHit embree_ray(const Vec3& origin, const Vec3& direction, double tnear, double tfar,
                     float time = 0) {
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(origin.x);
  rh.ray.org_y = static_cast<float>(origin.y);
  rh.ray.org_z = static_cast<float>(origin.z);
  rh.ray.dir_x = static_cast<float>(direction.x);
  rh.ray.dir_y = static_cast<float>(direction.y);
  rh.ray.dir_z = static_cast<float>(direction.z);
  rh.ray.tnear = static_cast<float>(tnear);
  rh.ray.tfar = static_cast<float>(std::min(tfar, 3.0e38));
  rh.ray.time = time;
  rh.ray.mask = ~0u;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// The ray through a mesh's BVH.
RTCRayHit mesh_ray(const ShapeRay& ray, double tnear, double tfar) {
  return embree_ray(ray.origin, ray.direction, tnear, tfar);
}

// Lane i of an 8-wide packet set from a single ray (and its empty hit), and a lane's result read
// back: the two layouts hold the same fields.
void put_lane(RTCRay8& packet, unsigned i, const RTCRay& ray) {
  packet.org_x[i] = ray.org_x;
  packet.org_y[i] = ray.org_y;
  packet.org_z[i] = ray.org_z;
  packet.tnear[i] = ray.tnear;
  packet.dir_x[i] = ray.dir_x;
  packet.dir_y[i] = ray.dir_y;
  packet.dir_z[i] = ray.dir_z;
  packet.time[i] = ray.time;
  packet.tfar[i] = ray.tfar;
  packet.mask[i] = ray.mask;
  packet.id[i] = ray.id;
  packet.flags[i] = ray.flags;
}

void put_lane(RTCRayHit8& packet, unsigned i, const RTCRayHit& rh) {
  put_lane(packet.ray, i, rh.ray);
  packet.hit.geomID[i] = rh.hit.geomID;
  packet.hit.instID[0][i] = rh.hit.instID[0];
}

void take_lane(const RTCRayHit8& packet, unsigned i, RTCRayHit& rh) {
  rh.ray.tfar = packet.ray.tfar[i];
  rh.hit.geomID = packet.hit.geomID[i];
  rh.hit.primID = packet.hit.primID[i];
  rh.hit.u = packet.hit.u[i];
  rh.hit.v = packet.hit.v[i];
  rh.hit.instID[0] = packet.hit.instID[0][i];
}

// A hit of this code's own into lane i of the hits Embree passes through: geomID holds the
// body, primID the triangle of a mesh body.
void record_hit(RTCHitN* hits, unsigned n, unsigned i, unsigned body, unsigned prim, float u,
                float v) {
  RTCHitN_geomID(hits, n, i) = body;
  RTCHitN_primID(hits, n, i) = prim;
  RTCHitN_u(hits, n, i) = u;
  RTCHitN_v(hits, n, i) = v;
  RTCHitN_instID(hits, n, i, 0) = RTC_INVALID_GEOMETRY_ID;
}

bool intersect_sphere(const Sphere& sphere, const ShapeRay& ray, double tnear, double tfar,
                      double& s) {
  double in, out;
  return sphere_span(sphere, ray, in, out) && first_in(in, out, tnear, tfar, s);
}

bool intersect_box(const Box& box, const ShapeRay& ray, double tnear, double tfar, double& s) {
  double in, out;
  return box_span(box, ray, in, out) && first_in(in, out, tnear, tfar, s);
}

bool intersect_plane(const Plane& plane, const ShapeRay& ray, double tnear, double tfar,
                     double& s) {
  if (ray.direction.y == 0) return false;
  const double t = -ray.origin.y / ray.direction.y;
  if (!(t >= tnear && t < tfar)) return false;
  const Vec3 p = ray.origin + ray.direction * t;
  if (std::abs(p.x) > plane.size_x * 0.5 || std::abs(p.z) > plane.size_z * 0.5) return false;
  s = t;
  return true;
}

std::array<double, 2> sphere_uv(const Vec3& p) {
  const Vec3 n = normalize(p);
  return {0.5 + std::atan2(n.x, n.z) / (2 * std::numbers::pi),
          std::acos(std::clamp(n.y, -1.0, 1.0)) / std::numbers::pi};
}

// The face of the box a surface point lies on: the axis where it is relatively farthest out.
int box_face_axis(const Box& box, const Vec3& p) {
  const Vec3 rel = component_div(p, box.size);
  int axis = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(rel[i]) > std::abs(rel[axis])) axis = i;
  return axis;
}

std::array<double, 2> box_uv(const Box& box, const Vec3& p, int axis) {
  const Vec3 rel = component_div(p, box.size);
  if (axis == 0) return {0.5 + rel.z, 0.5 - rel.y};
  if (axis == 1) return {0.5 + rel.x, 0.5 + rel.z};
  return {0.5 + rel.x, 0.5 - rel.y};
}

// The texture coordinates and normal of an analytic shape's surface point. Points on flat faces
// are put exactly on the face, so that procedural patterns (a checker boundary at the face) do
// not flip with rounding.
void analytic_surface(const Shape& shape, Hit& hit) {
  if (std::holds_alternative<Sphere>(shape)) {
    hit.uv = sphere_uv(hit.shape_point);
    hit.shape_normal = hit.shape_point;
  } else if (const auto* box = std::get_if<Box>(&shape)) {
    const int axis = box_face_axis(*box, hit.shape_point);
    hit.shape_point[axis] = std::copysign(box->size[axis] * 0.5, hit.shape_point[axis]);
    hit.uv = box_uv(*box, hit.shape_point, axis);
    hit.shape_normal[axis] = std::copysign(1.0, hit.shape_point[axis]);
  } else if (const auto* plane = std::get_if<Plane>(&shape)) {
    hit.shape_point.y = 0;
    hit.uv = {0.5 + hit.shape_point.x / plane->size_x, 0.5 + hit.shape_point.z / plane->size_z};
    hit.shape_normal = {0, 1, 0};
  }
}

// Bodies listed by the cells of a grid over the directions from one point (the image plane for
// camera rays), each cell's list nearest first.
struct CellLists {
  struct Entry {
    float a_lo, a_hi, c_lo, c_hi;  // the body's rectangle in the grid's plane, rounded outwards
    float near;                    // its bounds' distance from the rays' common point, rounded down
    unsigned body;
  };
  std::vector<unsigned> start;  // cell k's entries are [start[k], start[k + 1])
  std::vector<Entry> entries;
};

// A body's rectangle in a grid's plane, and the cells it covers: columns a0..a1 of rows c0..c1.
struct BinnedRect {
  double a_lo, a_hi, c_lo, c_hi, near;
  unsigned body;
  int a0 = 0, a1 = 0, c0 = 0, c1 = 0;
  std::size_t cells() const { return std::size_t(a1 - a0 + 1) * std::size_t(c1 - c0 + 1); }
};

// The cells of a grid `count` cells wide over [-half, half] from lo to hi, clamped to it.
std::pair<int, int> cell_range(double lo, double hi, double half, int count) {
  const auto at = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x + half) / (2 * half) * count)), 0, count - 1);
  };
  return {at(lo), at(hi)};
}

// The point of box b nearest to p.
Vec3 nearest_point(const Bounds3& b, const Vec3& p) {
  Vec3 q;
  for (int k = 0; k < 3; ++k) q[k] = std::clamp(p[k], b.lower[k], b.upper[k]);
  return q;
}

// The cell of such a grid that holds x, |x| <= half.
int cell_of(double x, double half, int count) {
  return std::min(count - 1, static_cast<int>((x + half) / (2 * half) * count));
}

// The lists of a grid of `rows` rows of `columns` cells (row c's cells are c columns + a).
CellLists cell_lists(std::vector<BinnedRect>& rects, int columns, int rows) {
  const std::size_t cell_count = std::size_t(columns) * std::size_t(rows);
  std::sort(rects.begin(), rects.end(), [](const BinnedRect& x, const BinnedRect& y) {
    return x.near < y.near || (x.near == y.near && x.body < y.body);
  });
  CellLists lists;
  lists.start.assign(cell_count + 1, 0);
  const auto each_cell = [&](const BinnedRect& r, auto&& visit) {
    for (int c = r.c0; c <= r.c1; ++c)
      for (int a = r.a0; a <= r.a1; ++a) visit(std::size_t(c) * columns + a);
  };
  for (const BinnedRect& r : rects) each_cell(r, [&](std::size_t k) { ++lists.start[k + 1]; });
  for (std::size_t k = 0; k < cell_count; ++k) lists.start[k + 1] += lists.start[k];
  lists.entries.resize(lists.start[cell_count]);
  std::vector<unsigned> filled(lists.start.begin(), lists.start.end() - 1);
  const auto down = [](double x) { return std::nextafter(static_cast<float>(x), -INFINITY); };
  const auto up = [](double x) { return std::nextafter(static_cast<float>(x), INFINITY); };
  // In order of distance, so each cell's list is nearest first.
  for (const BinnedRect& r : rects) {
    const CellLists::Entry e{down(r.a_lo), up(r.a_hi),   down(r.c_lo),
                             up(r.c_hi),   down(r.near), r.body};
    each_cell(r, [&](std::size_t k) { lists.entries[filled[k]++] = e; });
  }
  return lists;
}

}  // namespace

struct Tracer::Impl {
  const ResolvedScene& scene;
  RTCDevice device = nullptr;
  RTCScene top = nullptr;      // camera rays: bodies within their trace bounds
  RTCScene shadows = nullptr;  // shadow rays: bodies within their shadow bounds
  std::unordered_map<const Mesh*, RTCScene> mesh_scenes;
  std::vector<RTCScene> body_mesh_scene;  // per body, null for analytic shapes
  // The ball about a mesh's bounds centre that holds it, in shape coordinates: a ray that misses
  // it (most of those a fast body's loose box lets through) skips the mesh's BVH.
  struct Ball {
    Vec3 centre;
    double radius = 0;
    double triangle_size = 0;  // the side of a square of a triangle's mean area
  };
  std::unordered_map<const Mesh*, Ball> mesh_balls;
  std::vector<const Ball*> body_mesh_ball;
  // A light's labelled shadow bounds, while its scenes are built: body b's box at time step j of
  // `steps` over all its labels (boxes[b steps + j], label_step_bounds) holds its events for
  // that step's label and, interpolated with the next step's, for every label between. Computed
  // once: Embree's multi-segment builder asks for each box many times.
  struct LabelSteps {
    std::vector<RTCBounds> boxes;
    unsigned steps = 0;
  };
  // Every body is one primitive of one user geometry per scene, so that Embree keeps no
  // geometry object per body; except, for camera rays, a mesh body whose shape coordinates are
  // an affine map of F's (at rest in F, or any body in the simultaneous picture: its rays carry
  // no time term), which is a native Embree instance of its mesh.
  struct BodiesRef {
    const Impl* impl;
    bool shadow;                           // which bounds
    const std::vector<unsigned>* indices;  // primitive -> body (null: the same)
    const LabelSteps* labels = nullptr;    // shadow bounds by label, while building
    unsigned first_step = 0;               // of its part of the labels, among labels->steps
    unsigned body(unsigned primitive) const { return indices ? (*indices)[primitive] : primitive; }
  };
  std::vector<unsigned> user_trace_bodies;  // the bodies camera rays meet through callbacks
  std::vector<unsigned> instance_body;      // geometry ID in `top` -> body, for instances
  BodiesRef trace_bodies{this, false, &user_trace_bodies}, shadow_bodies{this, true, nullptr};
  // Camera rays in the view: the bodies before the camera, binned by the rectangle their trace
  // bounds project to in the image plane (a, c) = (u.right, u.up) / u.forward. Each cell lists
  // those whose rectangle meets it, nearest first; a ray needs only its own cell's list.
  struct ImageBins {
    double half_a = 0, half_c = 0;  // the plane's range in the view, a little enlarged
    int cells_a = 0, cells_c = 0;   // row c's cells are c cells_a + a
    CellLists lists;
  } bins;
  bool use_bins = false;
  // Bodies the bins do not hold but rays in the view may meet: their bounds reach beside or
  // behind the camera, or cover too much of the image to list cell by cell.
  std::vector<unsigned> unbinned_bodies;
  BodiesRef unbinned_ref{this, false, &unbinned_bodies};
  RTCScene unbinned = nullptr;
  // Per light: the scenes of its parts of the labels in order, or none if it is not labelled.
  std::vector<std::vector<RTCScene>> labelled_shadows;
  std::deque<BodiesRef> labelled_bodies;  // their user data
  std::atomic<long long> embree_bytes{0};

  Impl(const ResolvedScene& s, ShadowBounds shadow_bounds, CameraRays camera_rays) : scene(s) {
    device = rtcNewDevice(nullptr);
    if (!device) throw std::runtime_error("cannot create the Embree device");
    rtcSetDeviceMemoryMonitorFunction(
        device,
        [](void* user, ssize_t bytes, bool) {
          static_cast<Impl*>(user)->embree_bytes += bytes;
          return true;
        },
        this);
    top = rtcNewScene(device);
    body_mesh_scene.resize(scene.bodies.size(), nullptr);
    body_mesh_ball.resize(scene.bodies.size(), nullptr);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
      if (const auto* m = std::get_if<MeshShape>(&scene.bodies[i].object->shape)) {
        body_mesh_scene[i] = mesh_scene(*m->mesh);
        body_mesh_ball[i] = &mesh_balls.at(m->mesh.get());
      }
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const ResolvedBody& body = scene.bodies[i];
      const Vec3& o = body.ray_offset;
      if (body_mesh_scene[i] && body.spin < 0 && o.x == 0 && o.y == 0 && o.z == 0)
        attach_instance(static_cast<unsigned>(i));
      else
        user_trace_bodies.push_back(static_cast<unsigned>(i));
    }
    if (!user_trace_bodies.empty())
      attach_bodies(top, trace_bodies, static_cast<unsigned>(user_trace_bodies.size()));
    rtcCommitScene(top);
    if (camera_rays == CameraRays::kImageBins) build_image_bins();
    // Labels matter only where a body moves in W: bodies at rest there have the same bounds at
    // every label.
    const bool moving = std::any_of(scene.bodies.begin(), scene.bodies.end(), [](const auto& b) {
      const Vec3& v = b.object->world_line.velocity;
      return v.x != 0 || v.y != 0 || v.z != 0;
    });
    const auto count = static_cast<unsigned>(scene.bodies.size());
    bool swept = false;
    labelled_shadows.resize(scene.shadow_lights.size());
    for (std::size_t l = 0; l < scene.shadow_lights.size(); ++l) {
      const ShadowLight& light = scene.shadow_lights[l];
      if (count == 0 || !scene.scene->render.shadows) continue;
      if (!light.labelled || !moving || shadow_bounds == ShadowBounds::kSwept) {
        swept = true;
        continue;
      }
      const unsigned part_steps = light.directional() ? 2 : kPointLightPartSteps;
      LabelSteps labels;
      labels.steps = kLabelParts * (part_steps - 1) + 1;
      labels.boxes.resize(std::size_t{count} * labels.steps);
      tbb::parallel_for(0u, count, [&](unsigned b) {
        const LabelledBounds bounds = labelled_bounds(scene, scene.bodies[b], light);
        for (unsigned j = 0; j < labels.steps; ++j)
          labels.boxes[std::size_t{b} * labels.steps + j] =
              float_bounds(padded_step_bounds(bounds, light, labels.steps, j));
      });
      for (unsigned part = 0; part < kLabelParts; ++part) {
        BodiesRef& ref = labelled_bodies.emplace_back(
            BodiesRef{this, true, nullptr, &labels, part * (part_steps - 1)});
        RTCScene target = labelled_shadows[l].emplace_back(rtcNewScene(device));
        attach_bodies(target, ref, count, part_steps);
        rtcCommitScene(target);
        ref.labels = nullptr;
      }
    }
    if (swept) {
      shadows = rtcNewScene(device);
      attach_bodies(shadows, shadow_bodies, count);
      rtcCommitScene(shadows);
    }
    check("building the scene");
  }

  ~Impl() {
    for (auto& [mesh, s] : mesh_scenes) rtcReleaseScene(s);
    for (const auto& parts : labelled_shadows)
      for (RTCScene s : parts) rtcReleaseScene(s);
    if (top) rtcReleaseScene(top);
    if (unbinned) rtcReleaseScene(unbinned);
    if (shadows) rtcReleaseScene(shadows);
    if (device) rtcReleaseDevice(device);
  }

  void check(const char* what) const {
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE)
      throw std::runtime_error(std::string("Embree failed while ") + what + " (error " +
                               std::to_string(static_cast<int>(e)) + ")");
  }

  RTCScene mesh_scene(const Mesh& mesh) {
    if (auto it = mesh_scenes.find(&mesh); it != mesh_scenes.end()) return it->second;
    RTCScene s = rtcNewScene(device);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
      for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(mesh.positions[i][k]);
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                mesh.triangles.size()));
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) idx[3 * i + k] = mesh.triangles[i][k];
    rtcCommitGeometry(g);
    rtcAttachGeometry(s, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(s);
    check("building a mesh");
    mesh_scenes.emplace(&mesh, s);
    Vec3 lower = mesh.positions.empty() ? Vec3{} : mesh.positions[0], upper = lower;
    for (const Vec3& p : mesh.positions)
      for (int k = 0; k < 3; ++k) {
        lower[k] = std::min(lower[k], p[k]);
        upper[k] = std::max(upper[k], p[k]);
      }
    Ball ball{(lower + upper) * 0.5, 0};
    for (const Vec3& p : mesh.positions)
      ball.radius = std::max(ball.radius, length(p - ball.centre));
    ball.radius = ball.radius * (1 + 1e-6) + 1e-9;
    double area = 0;
    for (const auto& t : mesh.triangles)
      area += 0.5 * length(cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                 mesh.positions[t[2]] - mesh.positions[t[0]]));
    if (!mesh.triangles.empty())
      ball.triangle_size = std::sqrt(area / static_cast<double>(mesh.triangles.size()));
    mesh_balls.emplace(&mesh, ball);
    return s;
  }

  // The image plane's point of look direction u, and its cell; false outside the bins' range
  // (behind the camera, or out of the view).
  bool bin_point(const Vec3& u, float& a, float& c, unsigned& cell) const {
    const CameraBasis& view = scene.camera;
    const double f = dot(u, view.forward);
    if (!(f > 0)) return false;
    const double pa = dot(u, view.right) / f, pc = dot(u, view.up) / f;
    if (!(std::abs(pa) <= bins.half_a && std::abs(pc) <= bins.half_c)) return false;
    a = static_cast<float>(pa);
    c = static_cast<float>(pc);
    cell = static_cast<unsigned>(cell_of(pc, bins.half_c, bins.cells_c) * bins.cells_a +
                                 cell_of(pa, bins.half_a, bins.cells_a));
    return true;
  }

  // The range of (p.e) / (p.f) over the end balls of a capsule before the camera (e and f
  // orthonormal): a plane through the camera with e.p = a f.p meets a ball (centre C, radius R)
  // where (e.C - a f.C)^2 <= R^2 (1 + a^2), a quadratic in a.
  static std::pair<double, double> ball_image(const Capsule& capsule, const Vec3& e,
                                              const Vec3& f) {
    double lo = kInfinity, hi = -kInfinity;
    for (const Vec3& centre : {capsule.from, capsule.to}) {
      const double x = dot(centre, e), z = dot(centre, f), r2 = capsule.radius * capsule.radius;
      const double root = capsule.radius * std::sqrt(x * x + z * z - r2), scale = z * z - r2;
      lo = std::min(lo, (x * z - root) / scale);
      hi = std::max(hi, (x * z + root) / scale);
    }
    return {lo, hi};
  }

  // The distance from the camera to the segment from a to b.
  static double distance_to_segment(const Vec3& a, const Vec3& b) {
    const Vec3 d = b - a;
    const double dd = dot(d, d);
    const double t = dd > 0 ? std::clamp(-dot(a, d) / dd, 0.0, 1.0) : 0.0;
    return length(a + d * t);
  }

  void build_image_bins() {
    const CameraBasis& view = scene.camera;
    // Sample points reach the image's edges; the margin keeps them inside the range.
    bins.half_c = view.tan_half_fov * (1 + 1e-3);
    bins.half_a = bins.half_c * view.aspect;
    if (!(std::isfinite(bins.half_a) && std::isfinite(bins.half_c) && bins.half_a > 0 &&
          bins.half_c > 0))
      return;
    std::vector<BinnedRect> rects;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Bounds3& b = scene.bodies[i].trace_bounds;
      const auto index = static_cast<unsigned>(i);
      if (!(b.lower.x <= b.upper.x && b.lower.y <= b.upper.y && b.lower.z <= b.upper.z)) continue;
      double f_lo = kInfinity, f_hi = -kInfinity, reach = 0;
      BinnedRect r{kInfinity, -kInfinity, kInfinity, -kInfinity, 0, index};
      for (int k = 0; k < 8; ++k) {
        const Vec3 p = corner(b, k);
        const double f = dot(p, view.forward);
        f_lo = std::min(f_lo, f);
        f_hi = std::max(f_hi, f);
        reach = std::max(reach, length(p));
        r.a_lo = std::min(r.a_lo, dot(p, view.right) / f);
        r.a_hi = std::max(r.a_hi, dot(p, view.right) / f);
        r.c_lo = std::min(r.c_lo, dot(p, view.up) / f);
        r.c_hi = std::max(r.c_hi, dot(p, view.up) / f);
      }
      if (f_hi < 0) continue;  // wholly behind the camera: no ray in the view meets it
      if (!(f_lo > 1e-9 * reach) || !std::isfinite(reach)) {
        unbinned_bodies.push_back(index);
        continue;
      }
      if (r.a_hi < -bins.half_a || r.a_lo > bins.half_a || r.c_hi < -bins.half_c ||
          r.c_lo > bins.half_c)
        continue;  // out of the view
      r.near = length(nearest_point(b, {}));
      // The capsule's own image is tighter: the hull of its end balls' images, so within the
      // union of their rectangles.
      const Capsule& capsule = scene.bodies[i].trace_capsule;
      const double ra = capsule.radius;
      if (dot(capsule.from, view.forward) > ra * (1 + 1e-6) &&
          dot(capsule.to, view.forward) > ra * (1 + 1e-6)) {
        const auto [a_lo, a_hi] = ball_image(capsule, view.right, view.forward);
        const auto [c_lo, c_hi] = ball_image(capsule, view.up, view.forward);
        r.a_lo = std::max(r.a_lo, a_lo);
        r.a_hi = std::min(r.a_hi, a_hi);
        r.c_lo = std::max(r.c_lo, c_lo);
        r.c_hi = std::min(r.c_hi, c_hi);
        r.near = std::max(r.near, distance_to_segment(capsule.from, capsule.to) - ra);
      }
      r.near *= 1 - 1e-9;
      rects.push_back(r);
    }
    // About two cells a body, none smaller than 4 x 4 pixels (a packet's rays share a cell).
    const double pixels = static_cast<double>(view.width) * view.height;
    const double cells =
        std::clamp(2.0 * static_cast<double>(rects.size()), 1.0, std::max(1.0, pixels / 16));
    bins.cells_a = std::max(1, static_cast<int>(std::lround(std::sqrt(cells * view.aspect))));
    bins.cells_c = std::max(1, static_cast<int>(cells / bins.cells_a));
    std::size_t total = 0;
    for (BinnedRect& r : rects) {
      std::tie(r.a0, r.a1) = cell_range(r.a_lo, r.a_hi, bins.half_a, bins.cells_a);
      std::tie(r.c0, r.c1) = cell_range(r.c_lo, r.c_hi, bins.half_c, bins.cells_c);
      total += r.cells();
    }
    // The lists' size is held to a few entries a cell and a body: bodies that cover the most
    // cells go to the BVH instead.
    const std::size_t cell_count = std::size_t(bins.cells_a) * std::size_t(bins.cells_c);
    const std::size_t budget = 8 * (cell_count + rects.size());
    if (total > budget) {
      std::stable_sort(rects.begin(), rects.end(), [](const BinnedRect& x, const BinnedRect& y) {
        return x.cells() < y.cells();
      });
      std::size_t kept = 0;
      for (total = 0; kept < rects.size() && total + rects[kept].cells() <= budget; ++kept)
        total += rects[kept].cells();
      for (std::size_t k = kept; k < rects.size(); ++k) unbinned_bodies.push_back(rects[k].body);
      rects.resize(kept);
    }
    bins.lists = cell_lists(rects, bins.cells_a, bins.cells_c);
    if (!unbinned_bodies.empty()) {
      std::sort(unbinned_bodies.begin(), unbinned_bodies.end());
      unbinned = rtcNewScene(device);
      attach_bodies(unbinned, unbinned_ref, static_cast<unsigned>(unbinned_bodies.size()));
      rtcCommitScene(unbinned);
    }
    use_bins = true;
  }

  // Camera rays meet shape coordinates shape_origin + s spatial u: the instance's transform,
  // from shape coordinates to F, is the inverse of that affine map.
  void attach_instance(unsigned index) {
    const ResolvedBody& body = scene.bodies[index];
    const Mat3 to_trace = body.spatial.inverse();
    const Vec3 offset = (to_trace * body.shape_origin) * -1.0;
    float transform[12];  // column-major 3x4
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) transform[3 * c + r] = static_cast<float>(to_trace.m[r][c]);
    for (int r = 0; r < 3; ++r) transform[9 + r] = static_cast<float>(offset[r]);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, body_mesh_scene[index]);
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, transform);
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(top, g);
    rtcReleaseGeometry(g);
    if (instance_body.size() <= id) instance_body.resize(id + 1, 0);
    instance_body[id] = index;
  }

  void attach_bodies(RTCScene target, BodiesRef& ref, unsigned count, unsigned time_steps = 1) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, count);
    if (time_steps > 1) rtcSetGeometryTimeStepCount(g, time_steps);
    rtcSetGeometryUserData(g, &ref);
    rtcSetGeometryBoundsFunction(g, &Impl::bounds_callback, nullptr);
    rtcSetGeometryIntersectFunction(g, &Impl::intersect_callback);
    rtcSetGeometryOccludedFunction(g, &Impl::occluded_callback);
    rtcCommitGeometry(g);
    rtcAttachGeometry(target, g);
    rtcReleaseGeometry(g);
  }

  // Rounded outwards, so that the float bounds still contain the double ones.
  static RTCBounds float_bounds(const Bounds3& b) {
    RTCBounds f{};
    f.lower_x = std::nextafter(static_cast<float>(b.lower.x), -INFINITY);
    f.lower_y = std::nextafter(static_cast<float>(b.lower.y), -INFINITY);
    f.lower_z = std::nextafter(static_cast<float>(b.lower.z), -INFINITY);
    f.upper_x = std::nextafter(static_cast<float>(b.upper.x), INFINITY);
    f.upper_y = std::nextafter(static_cast<float>(b.upper.y), INFINITY);
    f.upper_z = std::nextafter(static_cast<float>(b.upper.z), INFINITY);
    return f;
  }

  static void bounds_callback(const RTCBoundsFunctionArguments* args) {
    const auto* ref = static_cast<const BodiesRef*>(args->geometryUserPtr);
    if (ref->labels) {
      *args->bounds_o = ref->labels->boxes[std::size_t{args->primID} * ref->labels->steps +
                                           ref->first_step + args->timeStep];
      return;
    }
    const ResolvedBody& body = ref->impl->scene.bodies[ref->body(args->primID)];
    *args->bounds_o = float_bounds(ref->shadow ? body.shadow_bounds : body.trace_bounds);
  }

  // Embree interpolates in single precision, at a label rounded to a float time: a margin of
  // 1e-6 of the label range in the times and of the box's reach in space.
  static Bounds3 padded_step_bounds(const LabelledBounds& bounds, const ShadowLight& light,
                                    unsigned steps, unsigned step) {
    Bounds3 box = label_step_bounds(bounds, light, steps, step);
    const double late =
        1e-6 * (std::abs(bounds.t1) + length(bounds.b)) * (light.label_max - light.label_min);
    double reach = 0;
    for (int i = 0; i < 3; ++i)
      reach = std::max({reach, std::abs(box.lower[i]), std::abs(box.upper[i])});
    const double pad = 1e-6 * reach + late * std::max({std::abs(bounds.v.x), std::abs(bounds.v.y),
                                                       std::abs(bounds.v.z)});
    for (int i = 0; i < 3; ++i) {
      box.lower[i] -= pad;
      box.upper[i] += pad;
    }
    return box;
  }

  // `origin` and `direction` are in F for camera rays, in W for shadow rays.
  static ShapeRay shape_ray(const ResolvedBody& body, bool shadow, const Vec4& origin,
                            const Vec4& direction) {
    return shadow ? ShapeRay{body.shadow_shape_point(origin), body.shadow_shape_vector(direction)}
                  : ShapeRay{body.shape_point(origin), body.shape_vector(direction)};
  }

  bool meets_mesh_ball(unsigned index, const ShapeRay& ray, double tnear, double tfar,
                       double* entry = nullptr) const {
    const Ball& ball = *body_mesh_ball[index];
    double in, out;
    if (!sphere_span(Sphere{ball.radius}, ShapeRay{ray.origin - ball.centre, ray.direction}, in,
                     out) ||
        out < tnear || in >= tfar)
      return false;
    if (entry) *entry = in;
    return true;
  }

  // `origin` and `direction` are in F for camera rays, in W for shadow rays.
  ShapeHit intersect(unsigned index, bool shadow, const Vec4& origin, const Vec4& direction,
                     double tnear, double tfar, RTCIntersectContext* context) const {
    const ResolvedBody& body = scene.bodies[index];
    if (body.spin >= 0)
      return intersect_spinning(index, shadow, origin, direction, tnear, tfar, context);
    return intersect_shape(index, shape_ray(body, shadow, origin, direction), tnear, tfar, context);
  }

  // A body that does not spin, met by a ray in its shape's coordinates.
  ShapeHit intersect_shape(unsigned index, const ShapeRay& ray, double tnear, double tfar,
                           RTCIntersectContext* context) const {
    const ResolvedBody& body = scene.bodies[index];
    ShapeHit hit;
    double s = 0;
    struct Visitor {
      const ShapeRay& ray;
      double tnear, tfar;
      double& s;
      bool operator()(const Sphere& x) const { return intersect_sphere(x, ray, tnear, tfar, s); }
      bool operator()(const Box& x) const { return intersect_box(x, ray, tnear, tfar, s); }
      bool operator()(const Plane& x) const { return intersect_plane(x, ray, tnear, tfar, s); }
      bool operator()(const MeshShape&) const { return false; }
    };
    if (RTCScene mesh = body_mesh_scene[index]) {
      if (!meets_mesh_ball(index, ray, tnear, tfar)) return hit;
      RTCRayHit rh = mesh_ray(ray, tnear, tfar);
      rtcIntersect1(mesh, context, &rh);
      if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        hit.s = rh.ray.tfar;
        hit.prim = rh.hit.primID;
        hit.bary_u = rh.hit.u;
        hit.bary_v = rh.hit.v;
      }
    } else if (std::visit(Visitor{ray, tnear, tfar, s}, body.object->shape)) {
      hit.s = s;
    }
    return hit;
  }

  // A spinning body: the straight ray in its rest frame is a curve in its shape's coordinates,
  // followed in chords (kSpinChordAngle); the first chord that meets the shape brackets the
  // hit, which is then found on the curve by bisection of the surface met (a face's plane, a
  // triangle's plane, the sphere).
  ShapeHit intersect_spinning(unsigned index, bool shadow, const Vec4& origin,
                              const Vec4& direction, double tnear, double tfar,
                              RTCIntersectContext* context) const {
    const ResolvedBody& body = scene.bodies[index];
    const ResolvedSpin& spin = scene.spins[body.spin];
    const ShapeRay frozen =
        shadow ? ShapeRay{body.shadow_shape_point(origin), body.shadow_shape_vector(direction)}
               : ShapeRay{body.shape_point(origin), body.shape_vector(direction)};
    const Vec3 o = spin.rest_from_shape * frozen.origin;
    const Vec3 d = spin.rest_from_shape * frozen.direction;
    const Vec4& row = shadow ? spin.shadow_proper_time_row : body.proper_time_row;
    const double tau0 =
        shadow ? spin.shadow_proper_time_origin + row.t * origin.t + dot(row.x, origin.x)
               : body.proper_time(origin);
    const double tau1 = row.t * direction.t + dot(row.x, direction.x);
    ShapeHit hit;
    // The part of the ray inside the ball that holds the shape at every angle.
    double in, out;
    if (!sphere_span(Sphere{spin.radius}, ShapeRay{o, d}, in, out)) return hit;
    const double lo = std::max(in, tnear), hi = std::min(out, tfar);
    if (!(lo < hi)) return hit;
    const auto shape_at = [&](double s) {
      return spin.shape_of_rest * rotated(spin.axis, -spin.rate * (tau0 + s * tau1), o + d * s);
    };
    const Shape& shape = body.object->shape;
    const auto* ball = std::get_if<Sphere>(&shape);
    const Vec3& k = body.object->scale;
    if (ball && k.x == k.y && k.y == k.z) {
      // A round ball turning about its centre is the same ball at every angle: the straight
      // ray meets it where the curve does.
      double s;
      if (!intersect_sphere(Sphere{ball->radius * std::abs(k.x)}, ShapeRay{o, d}, tnear, tfar, s))
        return hit;
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
    RTCScene mesh = body_mesh_scene[index];
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
        RTCRayHit rh = mesh_ray(chord, 0, 1);
        rtcIntersect1(mesh, context, &rh);
        if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
          met = true;
          prim = rh.hit.primID;
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

  // Embree calls back with packets of N rays (one for rtcIntersect1), of which those `valid`
  // are to be intersected.
  static void intersect_callback(const RTCIntersectFunctionNArguments* args) {
    const auto* ref = static_cast<const BodiesRef*>(args->geometryUserPtr);
    ref->impl->intersect_rays(ref->body(args->primID), ref->shadow,
                              *reinterpret_cast<TraceContext*>(args->context), args->valid, args->N,
                              args->rayhit);
  }

  // The `valid` ones of n rays against one body, each hit nearer than its ray's tfar recorded.
  void intersect_rays(unsigned body, bool shadow, TraceContext& context, const int* valid,
                      unsigned n, RTCRayHitN* rayhit) const {
    RTCRayN* rays = RTCRayHitN_RayN(rayhit, n);
    RTCHitN* hits = RTCRayHitN_HitN(rayhit, n);
    if (n == kPacketSize && body_mesh_scene[body] && scene.bodies[body].spin < 0) {
      intersect_mesh_packet(body, shadow, context, valid, rays, hits);
      return;
    }
    for (unsigned i = 0; i < n; ++i) {
      if (!valid[i]) continue;
      float& tfar = RTCRayN_tfar(rays, n, i);
      const ExactRay& ray = context.rays[RTCRayN_id(rays, n, i)];
      const ShapeHit hit = intersect(body, shadow, ray.origin, ray.direction,
                                     RTCRayN_tnear(rays, n, i), tfar, &context.embree);
      if (!(hit.s < tfar)) continue;
      tfar = static_cast<float>(hit.s);
      record_hit(hits, n, i, body, hit.prim, hit.bary_u, hit.bary_v);
    }
  }

  // The packet's rays in the bins (in_bins, with their plane points and cells) against the
  // bodies of their cells, nearest first, until a cell's next body lies beyond every hit.
  void trace_bins(const int* in_bins, const float* a, const float* c, const unsigned* cell,
                  TraceContext& context, RTCRayHit8& packet) const {
    constexpr unsigned n = kPacketSize;
    bool done[n] = {};
    for (unsigned i = 0; i < n; ++i) {
      if (!in_bins[i] || done[i]) continue;
      bool lanes[n] = {};
      for (unsigned j = i; j < n; ++j)
        if (in_bins[j] && cell[j] == cell[i]) lanes[j] = done[j] = true;
      const CellLists::Entry* e = bins.lists.entries.data() + bins.lists.start[cell[i]];
      const CellLists::Entry* end = bins.lists.entries.data() + bins.lists.start[cell[i] + 1];
      for (; e != end; ++e) {
        alignas(32) int meets[n] = {};
        bool nearer = false, any = false;
        for (unsigned j = i; j < n; ++j) {
          if (!lanes[j] || !(packet.ray.tfar[j] > e->near)) continue;
          nearer = true;
          if (a[j] >= e->a_lo && a[j] <= e->a_hi && c[j] >= e->c_lo && c[j] <= e->c_hi)
            meets[j] = -1, any = true;
        }
        if (!nearer) break;
        if (any)
          intersect_rays(e->body, false, context, meets, n, reinterpret_cast<RTCRayHitN*>(&packet));
      }
    }
  }

  // A packet's rays through a mesh body (not spinning) together, a packet through the mesh's own
  // BVH: their straight rays in its shape coordinates leave from nearby and run alike.
  void intersect_mesh_packet(unsigned index, bool shadow, const TraceContext& context,
                             const int* valid, RTCRayN* rays, RTCHitN* hits) const {
    constexpr unsigned n = kPacketSize;
    const ResolvedBody& body = scene.bodies[index];
    RTCRayHit ones[n];
    alignas(32) int inside[n] = {};
    unsigned count = 0;
    // Where the rays enter the mesh's ball: the box about those points.
    Vec3 lowest{kInfinity, kInfinity, kInfinity}, highest = lowest * -1.0;
    for (unsigned i = 0; i < n; ++i) {
      if (!valid[i]) continue;
      const ExactRay& exact = context.rays[RTCRayN_id(rays, n, i)];
      const ShapeRay ray = shape_ray(body, shadow, exact.origin, exact.direction);
      const double tnear = RTCRayN_tnear(rays, n, i), tfar = RTCRayN_tfar(rays, n, i);
      double entry = 0;
      if (!meets_mesh_ball(index, ray, tnear, tfar, &entry)) continue;
      const Vec3 at = ray.origin + ray.direction * std::max(entry, tnear);
      for (int k = 0; k < 3; ++k) {
        lowest[k] = std::min(lowest[k], at[k]);
        highest[k] = std::max(highest[k], at[k]);
      }
      ones[i] = mesh_ray(ray, tnear, tfar);
      inside[i] = -1;
      ++count;
    }
    RTCIntersectContext nested;
    rtcInitIntersectContext(&nested);
    const double spread = count > 0 ? length(highest - lowest) : 0;
    if (count >= kMinMeshPacket &&
        spread <= kCoherentTriangles * body_mesh_ball[index]->triangle_size) {
      alignas(32) RTCRayHit8 packet{};
      for (unsigned i = 0; i < n; ++i)
        if (inside[i]) put_lane(packet, i, ones[i]);
      nested.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      rtcIntersect8(inside, body_mesh_scene[index], &nested, &packet);
      for (unsigned i = 0; i < n; ++i)
        if (inside[i]) take_lane(packet, i, ones[i]);
    } else {
      // Few rays, or far apart: each alone is faster.
      for (unsigned i = 0; i < n; ++i)
        if (inside[i]) rtcIntersect1(body_mesh_scene[index], &nested, &ones[i]);
    }
    for (unsigned i = 0; i < n; ++i) {
      if (!inside[i] || ones[i].hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      float& tfar = RTCRayN_tfar(rays, n, i);
      if (!(ones[i].ray.tfar < tfar)) continue;
      tfar = ones[i].ray.tfar;
      record_hit(hits, n, i, index, ones[i].hit.primID, ones[i].hit.u, ones[i].hit.v);
    }
  }

  static void occluded_callback(const RTCOccludedFunctionNArguments* args) {
    const auto* ref = static_cast<const BodiesRef*>(args->geometryUserPtr);
    auto* context = reinterpret_cast<TraceContext*>(args->context);
    const unsigned body = ref->body(args->primID), n = args->N;
    for (unsigned i = 0; i < n; ++i) {
      if (!args->valid[i]) continue;
      float& tfar = RTCRayN_tfar(args->ray, n, i);
      const ExactRay& ray = context->rays[RTCRayN_id(args->ray, n, i)];
      const ShapeHit hit =
          ref->impl->intersect(body, ref->shadow, ray.origin, ray.direction,
                               RTCRayN_tnear(args->ray, n, i), tfar, args->context);
      if (hit.s < tfar) tfar = -std::numeric_limits<float>::infinity();
    }
  }

  // What Embree found for a camera ray: the body, and for a mesh body the triangle, its
  // barycentric coordinates and the ray parameter.
  struct EmbreeHit {
    unsigned body;
    unsigned prim;
    float bary_u, bary_v, tfar;
  };

  // The body of a camera ray's Embree hit: an instance's, or the one our callback recorded.
  unsigned hit_body(unsigned geometry, unsigned instance) const {
    return instance != RTC_INVALID_GEOMETRY_ID ? instance_body[instance] : geometry;
  }

  std::optional<Hit> camera_hit(const Vec3& u, const EmbreeHit& found, TraceContext& context) const;
};

}  // namespace lightcone

namespace lightcone {

Tracer::Tracer(const ResolvedScene& scene, ShadowBounds shadow_bounds, CameraRays camera_rays)
    : impl_(std::make_unique<Impl>(scene, shadow_bounds, camera_rays)) {}
Tracer::~Tracer() = default;

std::size_t Tracer::acceleration_bytes() const {
  return static_cast<std::size_t>(std::max<long long>(0, impl_->embree_bytes.load()));
}

std::optional<Hit> Tracer::trace(const Vec3& u) const {
  std::optional<Hit> hit;
  trace(std::span(&u, 1), std::span(&hit, 1));
  return hit;
}

void Tracer::trace(std::span<const Vec3> directions, std::span<std::optional<Hit>> hits) const {
  for (std::size_t first = 0; first < directions.size(); first += kPacketSize) {
    const std::size_t count = std::min<std::size_t>(kPacketSize, directions.size() - first);
    TraceContext context;
    rtcInitIntersectContext(&context.embree);
    context.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(32) RTCRayHit8 rh{};
    // Rays in the view go through the bins (and the bodies they do not hold), the rest through
    // the BVH over all bodies.
    alignas(32) int in_bins[kPacketSize] = {}, elsewhere[kPacketSize] = {};
    float a[kPacketSize], c[kPacketSize];
    unsigned cell[kPacketSize];
    bool any_in_bins = false, any_elsewhere = false;
    for (unsigned i = 0; i < kPacketSize; ++i) {
      // Lanes past the last ray repeat it, unused.
      const Vec3& u = directions[first + std::min<std::size_t>(i, count - 1)];
      context.rays[i] = {{}, {impl_->scene.ray_time, u}};
      RTCRayHit one = embree_ray({}, u, 0, kInfinity);
      one.ray.id = i;
      put_lane(rh, i, one);
      if (i >= count) continue;
      if (impl_->use_bins && impl_->bin_point(u, a[i], c[i], cell[i]))
        in_bins[i] = -1, any_in_bins = true;
      else
        elsewhere[i] = -1, any_elsewhere = true;
    }
    if (any_elsewhere) rtcIntersect8(elsewhere, impl_->top, &context.embree, &rh);
    if (any_in_bins) {
      if (impl_->unbinned) rtcIntersect8(in_bins, impl_->unbinned, &context.embree, &rh);
      impl_->trace_bins(in_bins, a, c, cell, context, rh);
    }
    for (std::size_t i = 0; i < count; ++i) {
      std::optional<Hit>& hit = hits[first + i];
      hit.reset();
      if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
      const unsigned index = impl_->hit_body(rh.hit.geomID[i], rh.hit.instID[0][i]);
      hit = impl_->camera_hit(directions[first + i],
                              {index, rh.hit.primID[i], rh.hit.u[i], rh.hit.v[i], rh.ray.tfar[i]},
                              context);
    }
  }
}

void Tracer::surface_at(const Vec3& incoming, Hit& hit, unsigned prim) const {
  const Object& object = *impl_->scene.bodies[hit.body].object;
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

std::optional<Tracer::SegmentHit> Tracer::body_on_world_segment(int body, const Vec4& from,
                                                                const Vec4& to) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const ShapeHit hit =
      impl_->intersect(static_cast<unsigned>(body), true, from, to - from, 0, 1, &context);
  if (!(hit.s <= 1)) return std::nullopt;
  return SegmentHit{hit.s, hit.prim, hit.bary_u, hit.bary_v};
}

std::optional<Tracer::SegmentHit> Tracer::body_on_shape_segment(int body, const Vec3& from,
                                                                const Vec3& to) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const ShapeHit hit = impl_->intersect_shape(static_cast<unsigned>(body),
                                              ShapeRay{from, to - from}, 0, 1, &context);
  if (!(hit.s <= 1)) return std::nullopt;
  return SegmentHit{hit.s, hit.prim, hit.bary_u, hit.bary_v};
}

// Embree chose the body (an instance's, or the one our callback recorded); an analytic hit is
// recomputed in double precision.
std::optional<Hit> Tracer::Impl::camera_hit(const Vec3& u, const EmbreeHit& found,
                                            TraceContext& context) const {
  const unsigned index = found.body;
  const ResolvedBody& body = scene.bodies[index];
  const bool spinning = body.spin >= 0;
  const Vec4 direction{scene.ray_time, u};
  Hit hit;
  hit.body = static_cast<int>(index);
  const ShapeRay ray{body.shape_origin, body.shape_direction(u)};
  ShapeHit exact;
  if (spinning) {
    exact = intersect(index, false, {}, direction, 0, kInfinity, &context.embree);
    if (!std::isfinite(exact.s)) return std::nullopt;
  }
  if (const auto* m = std::get_if<MeshShape>(&body.object->shape)) {
    const Mesh& mesh = *m->mesh;
    const unsigned prim = spinning ? exact.prim : found.prim;
    const auto& tri = mesh.triangles[prim];
    const double bu = spinning ? exact.bary_u : found.bary_u,
                 bv = spinning ? exact.bary_v : found.bary_v;
    const double bw = 1.0 - bu - bv;
    hit.shape_point = spinning ? exact.shape_point
                               : mesh.positions[tri[0]] * bw + mesh.positions[tri[1]] * bu +
                                     mesh.positions[tri[2]] * bv;
    hit.s = spinning ? exact.s : found.tfar;
    if (!mesh.uvs.empty())
      for (int k = 0; k < 2; ++k)
        hit.uv[k] = mesh.uvs[tri[0]][k] * bw + mesh.uvs[tri[1]][k] * bu + mesh.uvs[tri[2]][k] * bv;
    hit.shape_normal = cross(mesh.positions[tri[1]] - mesh.positions[tri[0]],
                             mesh.positions[tri[2]] - mesh.positions[tri[0]]);
  } else {
    if (!spinning) exact = intersect(index, false, {}, direction, 0, kInfinity, &context.embree);
    hit.s = std::isfinite(exact.s) ? exact.s : found.tfar;
    hit.shape_point = spinning ? exact.shape_point : ray.origin + ray.direction * hit.s;
    analytic_surface(body.object->shape, hit);
  }
  Vec3 incoming = ray.direction;
  if (spinning) {
    // The point's own motion: rate axis x r in the rest frame, carried to F.
    const ResolvedSpin& spin = scene.spins[body.spin];
    hit.proper_time = exact.proper_time;
    hit.spin_angle = spin.rate * exact.proper_time;
    const Vec3 rest_velocity = cross(spin.axis, exact.rest_point) * spin.rate;
    hit.velocity = velocity_of(spin.trace_from_rest * Vec4{1, rest_velocity});
    incoming = spin.shape_of_rest *
               rotated(spin.axis, -hit.spin_angle, spin.rest_from_shape * ray.direction);
  } else {
    hit.proper_time = body.proper_time(Vec4{scene.ray_time * hit.s, u * hit.s});
    hit.velocity = body.velocity;
  }
  // Facing the ray: surfaces are two-sided.
  hit.shape_normal = normalize(hit.shape_normal);
  if (dot(hit.shape_normal, incoming) > 0) hit.shape_normal = -hit.shape_normal;
  return hit;
}

// Shadow rays go to their light's labelled scene for the part of its labels theirs lies in (at
// the time of their label within it), or else to the swept scene; those bound for one scene are
// traced together, a packet at a time.
void Tracer::occluded(std::span<const ShadowRay> rays, std::span<bool> blocked) const {
  struct Query {
    RTCScene target;
    float time;
  };
  const auto query = [&](const ShadowRay& shadow) {
    if (shadow.light < 0 || impl_->labelled_shadows[shadow.light].empty())
      return Query{impl_->shadows, 0};
    const ShadowLight& light = impl_->scene.shadow_lights[shadow.light];
    const auto& parts = impl_->labelled_shadows[shadow.light];
    const double at =
        std::clamp((shadow.label - light.label_min) / (light.label_max - light.label_min), 0.0,
                   1.0) *
        static_cast<double>(parts.size());
    const std::size_t part = std::min(parts.size() - 1, static_cast<std::size_t>(at));
    return Query{parts[part], static_cast<float>(std::min(1.0, at - static_cast<double>(part)))};
  };
  // The rays still to trace, in order; each round takes up to a packet of those bound for the
  // first one's scene.
  std::size_t waiting[kMaxShadowBatch];
  Query queries[kMaxShadowBatch];
  for (std::size_t first = 0; first < rays.size(); first += kMaxShadowBatch) {
    const std::size_t count = std::min(kMaxShadowBatch, rays.size() - first);
    std::size_t left = 0;
    for (std::size_t r = 0; r < count; ++r) {
      queries[r] = query(rays[first + r]);
      blocked[first + r] = false;
      if (queries[r].target) waiting[left++] = r;  // none: no bodies, or shadows off
    }
    while (left > 0) {
      const RTCScene target = queries[waiting[0]].target;
      TraceContext context;
      rtcInitIntersectContext(&context.embree);
      RTCRay ones[kPacketSize];
      alignas(32) int valid[kPacketSize] = {};
      std::size_t lanes = 0, kept = 0, lane_ray[kPacketSize];
      for (std::size_t w = 0; w < left; ++w) {
        const std::size_t r = waiting[w];
        if (queries[r].target != target || lanes == kPacketSize) {
          waiting[kept++] = r;
          continue;
        }
        const ShadowRay& shadow = rays[first + r];
        context.rays[lanes] = {shadow.origin, shadow.direction};
        ones[lanes] = embree_ray(shadow.origin.x, shadow.direction.x, shadow.t_near, shadow.t_far,
                                 queries[r].time)
                          .ray;
        ones[lanes].id = static_cast<unsigned>(lanes);
        valid[lanes] = -1;
        lane_ray[lanes++] = r;
      }
      left = kept;
      if (lanes == 1) {
        // A ray alone goes faster through the single-ray traversal.
        rtcOccluded1(target, &context.embree, &ones[0]);
        blocked[first + lane_ray[0]] = ones[0].tfar < 0;
        continue;
      }
      alignas(32) RTCRay8 packet{};
      for (unsigned l = 0; l < lanes; ++l) put_lane(packet, l, ones[l]);
      context.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      rtcOccluded8(valid, target, &context.embree, &packet);
      for (std::size_t l = 0; l < lanes; ++l) blocked[first + lane_ray[l]] = packet.tfar[l] < 0;
    }
  }
}

}  // namespace lightcone
