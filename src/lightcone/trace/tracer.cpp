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
#include <unordered_map>
#include <vector>

#include "lightcone/frame/mesh_bvh.hpp"
#include "lightcone/frame/shape_intersection.hpp"
#include "lightcone/frame/spinning_intersection.hpp"
#include "lightcone/trace/embree_rays.hpp"
#include "lightcone/trace/image_bins.hpp"

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
  ImageBins bins;  // camera rays in the view, by the cell of the image plane they cross
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
    const MeshBall bounds = mesh_ball(mesh);
    Ball ball{bounds.centre, bounds.radius};
    double area = 0;
    for (const auto& t : mesh.triangles)
      area += 0.5 * length(cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                 mesh.positions[t[2]] - mesh.positions[t[0]]));
    if (!mesh.triangles.empty())
      ball.triangle_size = std::sqrt(area / static_cast<double>(mesh.triangles.size()));
    mesh_balls.emplace(&mesh, ball);
    return s;
  }

  void build_image_bins() {
    std::optional<ImageBins> built = image_bins(scene.camera, scene.bodies, unbinned_bodies);
    if (!built) return;
    bins = std::move(*built);
    if (!unbinned_bodies.empty()) {
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
    const ResolvedScene& scene = ref->impl->scene;
    const std::size_t index = ref->body(args->primID);
    *args->bounds_o = float_bounds(ref->shadow ? scene.world_maps[index].shadow_bounds
                                               : scene.bodies[index].trace_bounds);
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
  ShapeRay shape_ray(unsigned index, bool shadow, const Vec4& origin, const Vec4& direction) const {
    if (shadow) {
      const WorldShapeMap& map = scene.world_maps[index];
      return {map.shape_point(origin), map.shape_vector(direction)};
    }
    const ResolvedBody& body = scene.bodies[index];
    return {body.shape_point(origin), body.shape_vector(direction)};
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
    return intersect_shape(index, shape_ray(index, shadow, origin, direction), tnear, tfar,
                           context);
  }

  // A body that does not spin, met by a ray in its shape's coordinates.
  ShapeHit intersect_shape(unsigned index, const ShapeRay& ray, double tnear, double tfar,
                           RTCIntersectContext* context) const {
    const ResolvedBody& body = scene.bodies[index];
    ShapeHit hit;
    double s = 0;
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
    } else if (intersect_analytic(body.object->shape, ray, tnear, tfar, s)) {
      hit.s = s;
    }
    return hit;
  }

  // A spinning body (spinning_intersection.hpp), by its frozen ray and its clock along it.
  ShapeHit intersect_spinning(unsigned index, bool shadow, const Vec4& origin,
                              const Vec4& direction, double tnear, double tfar,
                              RTCIntersectContext* context) const {
    const ResolvedBody& body = scene.bodies[index];
    const ResolvedSpin& spin = scene.spins[body.spin];
    const Vec4& row = shadow ? spin.shadow_proper_time_row : body.proper_time_row;
    const double tau0 =
        shadow ? spin.shadow_proper_time_origin + row.t * origin.t + dot(row.x, origin.x)
               : body.proper_time(origin);
    const double tau1 = row.t * direction.t + dot(row.x, direction.x);
    MeshChordTest mesh;
    if (RTCScene mesh_scene = body_mesh_scene[index])
      mesh = [mesh_scene, context](const Vec3& from, const Vec3& to) -> std::optional<SegmentHit> {
        RTCRayHit rh = mesh_ray(ShapeRay{from, to - from}, 0, 1);
        rtcIntersect1(mesh_scene, context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
        return SegmentHit{rh.ray.tfar, rh.hit.primID, rh.hit.u, rh.hit.v};
      };
    return intersect_spinning_body(spin, *body.object, mesh,
                                   shape_ray(index, shadow, origin, direction), tau0, tau1, tnear,
                                   tfar);
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
    RTCRayHit ones[n];
    alignas(32) int inside[n] = {};
    unsigned count = 0;
    // Where the rays enter the mesh's ball: the box about those points.
    Vec3 lowest{kInfinity, kInfinity, kInfinity}, highest = lowest * -1.0;
    for (unsigned i = 0; i < n; ++i) {
      if (!valid[i]) continue;
      const ExactRay& exact = context.rays[RTCRayN_id(rays, n, i)];
      const ShapeRay ray = shape_ray(index, shadow, exact.origin, exact.direction);
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
    // Not zeroed (its 640 bytes were a twentieth of this function): every lane's ray and empty
    // hit are set below, and a hit's other fields are read only where Embree or a callback
    // wrote them.
    alignas(32) RTCRayHit8 rh;
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
      if (impl_->use_bins && impl_->bins.point(impl_->scene.camera, u, a[i], c[i], cell[i]))
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

std::optional<SegmentHit> Tracer::body_on_shape_segment(int body, const Vec3& from,
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
    mesh_surface(mesh, prim, bu, bv, hit);
  } else {
    if (!spinning) exact = intersect(index, false, {}, direction, 0, kInfinity, &context.embree);
    hit.s = std::isfinite(exact.s) ? exact.s : found.tfar;
    hit.shape_point = spinning ? exact.shape_point : ray.origin + ray.direction * hit.s;
    analytic_surface(body.object->shape, hit);
  }
  Vec3 incoming = ray.direction;
  if (spinning) {
    incoming = complete_spinning_hit(scene, body, exact, ray.direction, hit);
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
