// lightcone's throughput against raw Embree on the same triangles, and its per-ray cost as a
// swarm of fast bodies gets denser (issue 13), each comparison within one run:
//   Throughput_raw_embree/single/case:C/threads:T  rtcIntersect1 per pixel (pixel centres)
//                                                 through the scene's triangles at rest, one
//                                                 instance per body, nothing else: what a user
//                                                 could write by hand; the baseline
//   Throughput_raw_embree/packets/case:C/threads:T the same through rtcIntersect8, 4 x 2
//                                                 pixels a packet (lightcone traces its camera
//                                                 rays so): what a hand-written tracer could
//                                                 reach with Embree's packets
//   Throughput_lightcone/static/case:C/threads:T   lightcone's render of the same scene at rest
//                                                 (unlit, doppler and searchlight off, 1 sample)
//   Throughput_lightcone/moving/case:C/threads:T   the same scene in motion
// The cases, all at 1920 x 1080:
//   0 grid: a 10 x 10 grid of unit UV spheres (100 x 10,080 triangles, one shared mesh) at
//     distance 20, fov 70; in motion the spheres move at 0.9c along x. Targets: rays_per_s at
//     least 0.70 of raw_embree/single's at the same thread count at rest, 0.60 in motion.
//   1 street: scenes/street.json (boxes and planes; raw Embree traces their 12 and 2 triangles
//     each); at rest the camera stands still, in motion it flies at 0.8c as in the file.
//   2 swarm: 1,000 instances of one 1,280-triangle icosphere; in motion they move in random
//     directions at up to 0.9c.
//   DenseSwarm/bodies:N/lit:L   N icospheres in a slab before the camera, moving in random
//     directions at speeds up to 0.99c, their radius chosen so that every N covers the same
//     30 % of the image (radius, hit_fraction); lit: every body lit by one point light, so each
//     hit casts a shadow ray through the swarm. s_per_ray is render_image's time per camera ray
//     (one thread, 960 x 540, 1 sample), apart from its setup (setup_s).
//     The figure is the s_per_ray of 10,000 bodies against 100 (target <= 2x).
//   DenseSwarm_raw_embree/bodies:N  raw Embree's s_per_ray in the same swarm at rest (where the
//     camera sees each body at rest, covering 30 % too): each body an instance of the mesh,
//     rtcIntersect8 through blocks of 4 x 2 pixels, one thread, nothing else. How the swarm's
//     cost grows with N in a hand-written tracer.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <random>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/lighting.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/trace/renderer.hpp"
#include "lightcone/trace/tracer.hpp"
#include "meshes.hpp"

using namespace lightcone;
using lightcone::bench::icosphere;

namespace {

constexpr int kWidth = 1920, kHeight = 1080;

// A UV sphere of radius 1: `stacks` rings of `slices` quads, two triangles each (the poles'
// degenerate ones dropped).
std::shared_ptr<const Mesh> uv_sphere(int stacks, int slices) {
  auto mesh = std::make_shared<Mesh>();
  for (int i = 0; i <= stacks; ++i) {
    const double theta = std::numbers::pi * i / stacks;
    for (int j = 0; j <= slices; ++j) {
      const double phi = 2 * std::numbers::pi * j / slices;
      mesh->positions.push_back(
          {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)});
    }
  }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * (slices + 1) + j); };
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      if (i > 0) mesh->triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
      if (i + 1 < stacks) mesh->triangles.push_back({at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)});
    }
  return mesh;
}

const std::shared_ptr<const Mesh>& small_sphere() {
  static const std::shared_ptr<const Mesh> mesh = icosphere(3);
  return mesh;
}

// The triangles raw Embree traces for analytic shapes: a UV sphere, a box's 12, a plane's 2.
std::shared_ptr<const Mesh> unit_box() {
  auto mesh = std::make_shared<Mesh>();
  for (int i = 0; i < 8; ++i)
    mesh->positions.push_back({(i & 1) - 0.5, (i >> 1 & 1) - 0.5, (i >> 2 & 1) - 0.5});
  mesh->triangles = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1},
                     {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
  return mesh;
}

std::shared_ptr<const Mesh> unit_plane() {
  auto mesh = std::make_shared<Mesh>();
  mesh->positions = {{-0.5, 0, -0.5}, {0.5, 0, -0.5}, {0.5, 0, 0.5}, {-0.5, 0, 0.5}};
  mesh->triangles = {{0, 1, 2}, {0, 2, 3}};
  return mesh;
}

Vec3 grid_position(int i) {
  return {2.5 * (i % 10) - 11.25, 2.5 * (i / 10) - 11.25, -20.0};
}

Scene camera_scene() {
  Scene s;
  s.camera.width = kWidth;
  s.camera.height = kHeight;
  s.camera.fov_degrees = 70;
  s.render.doppler = DopplerModel::kOff;
  s.render.searchlight = SearchlightModel::kOff;
  return s;
}

// Placed so that the camera, at rest at the origin, sees a body moving with `velocity` about
// where `position` is.
WorldLine seen_at(const Vec3& position, const Vec3& velocity) {
  WorldLine line;
  line.position = position;
  line.velocity = velocity;
  line.time = -length(position);
  return line;
}

Scene grid(bool moving) {
  static const std::shared_ptr<const Mesh> mesh = uv_sphere(71, 72);
  Scene s = camera_scene();
  for (int i = 0; i < 100; ++i) {
    Object o;
    o.name = "sphere" + std::to_string(i);
    o.shape = MeshShape{mesh};
    o.world_line = seen_at(grid_position(i), moving ? Vec3{0.9, 0, 0} : Vec3{});
    s.objects.push_back(std::move(o));
  }
  return s;
}

Scene street(bool moving) {
  SceneLoadReport report;
  Scene s =
      load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/street.json",
                      {"camera.width=1920", "camera.height=1080", "camera.samples=1"}, report);
  s.render.doppler = DopplerModel::kOff;
  s.render.searchlight = SearchlightModel::kOff;
  s.lights.clear();
  for (Object& o : s.objects) o.material.unlit = true;
  if (!moving) s.camera.world_line.velocity = {};
  return s;
}

// `count` icospheres of radius `radius` in a slab in front of the camera, moving in random
// directions at speeds uniform in [0, max_speed].
Scene swarm(int count, double radius, double max_speed) {
  Scene s = camera_scene();
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < count; ++i) {
    Object o;
    o.name = "body-" + std::to_string(i);
    o.shape = MeshShape{small_sphere()};
    const Vec3 position{u(rng) * 40, u(rng) * 22, -30 + u(rng) * 25};
    const Vec3 direction = normalize(Vec3{u(rng), u(rng), u(rng)});
    o.world_line = seen_at(position, direction * (max_speed * std::abs(u(rng))));
    o.scale = {radius, radius, radius};
    s.objects.push_back(std::move(o));
  }
  return s;
}

enum Case { kGrid, kStreet, kSwarm };

Scene test_case(int which, bool moving) {
  if (which == kGrid) return grid(moving);
  if (which == kStreet) return street(moving);
  Scene s = swarm(1000, 1.2, 0.9);
  if (!moving)
    for (Object& o : s.objects) o.world_line.velocity = {};
  return s;
}

// Raw Embree over a scene at rest: one instance per object of its triangles.
struct RawEmbree {
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene top = rtcNewScene(device);
  std::map<const Mesh*, RTCScene> meshes;
  std::vector<std::shared_ptr<const Mesh>> kept;

  RTCScene mesh_scene(const std::shared_ptr<const Mesh>& mesh) {
    if (auto it = meshes.find(mesh.get()); it != meshes.end()) return it->second;
    kept.push_back(mesh);
    RTCScene object = rtcNewScene(device);
    rtcSetSceneBuildQuality(object, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v =
        static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                    3 * sizeof(float), mesh->positions.size()));
    for (std::size_t i = 0; i < mesh->positions.size(); ++i)
      for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(mesh->positions[i][k]);
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                mesh->triangles.size()));
    for (std::size_t i = 0; i < mesh->triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) idx[3 * i + k] = mesh->triangles[i][k];
    rtcCommitGeometry(g);
    rtcAttachGeometry(object, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(object);
    return meshes[mesh.get()] = object;
  }

  explicit RawEmbree(const Scene& scene) {
    static const std::shared_ptr<const Mesh> sphere = uv_sphere(71, 72), box = unit_box(),
                                             plane = unit_plane();
    for (const Object& o : scene.objects) {
      Vec3 size{1, 1, 1};
      std::shared_ptr<const Mesh> mesh;
      if (const auto* m = std::get_if<MeshShape>(&o.shape)) mesh = m->mesh;
      if (const auto* x = std::get_if<Sphere>(&o.shape))
        mesh = sphere, size = {x->radius, x->radius, x->radius};
      if (const auto* x = std::get_if<Box>(&o.shape)) mesh = box, size = x->size;
      if (const auto* x = std::get_if<Plane>(&o.shape))
        mesh = plane, size = {x->size_x, 1, x->size_z};
      // World point = position + rotation (scale (size p)).
      const Mat3 linear = o.rotation * Mat3::diagonal(component_mul(o.scale, size));
      float transform[12];
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) transform[3 * c + r] = static_cast<float>(linear.m[r][c]);
      for (int r = 0; r < 3; ++r) transform[9 + r] = static_cast<float>(o.world_line.position[r]);
      RTCGeometry instance = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(instance, mesh_scene(mesh));
      rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, transform);
      rtcCommitGeometry(instance);
      rtcAttachGeometry(top, instance);
      rtcReleaseGeometry(instance);
    }
    rtcCommitScene(top);
  }
  ~RawEmbree() {
    rtcReleaseScene(top);
    for (auto& [mesh, s] : meshes) rtcReleaseScene(s);
    rtcReleaseDevice(device);
  }
};

void set_rates(benchmark::State& state, double rays_per_iteration) {
  state.counters["rays_per_s"] =
      benchmark::Counter(rays_per_iteration, benchmark::Counter::kIsIterationInvariantRate);
}

// The camera ray through pixel (x, y)'s centre, as Embree takes it.
struct RawRay {
  float org[3], dir[3];
};

RawRay raw_ray(const CameraBasis& camera, const Vec3& eye, int x, int y) {
  const Vec3 u = look_direction(camera, x + 0.5, y + 0.5);
  return {{float(eye.x), float(eye.y), float(eye.z)}, {float(u.x), float(u.y), float(u.z)}};
}

// rtcIntersect8 through the blocks of 4 x 2 pixels of rows y0 and y0 + 1 (width a multiple of
// 4): the hits.
long long raw_packet_rows(const RawEmbree& raw, const CameraBasis& camera, const Vec3& eye,
                          int width, int y0) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  long long hits = 0;
  for (int x0 = 0; x0 < width; x0 += 4) {
    alignas(32) RTCRayHit8 rh{};
    alignas(32) int valid[8];
    for (int k = 0; k < 8; ++k) {
      const RawRay r = raw_ray(camera, eye, x0 + k % 4, y0 + k / 4);
      valid[k] = -1;
      rh.ray.org_x[k] = r.org[0];
      rh.ray.org_y[k] = r.org[1];
      rh.ray.org_z[k] = r.org[2];
      rh.ray.dir_x[k] = r.dir[0];
      rh.ray.dir_y[k] = r.dir[1];
      rh.ray.dir_z[k] = r.dir[2];
      rh.ray.tfar[k] = INFINITY;
      rh.ray.mask[k] = ~0u;
      rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, raw.top, &context, &rh);
    for (int k = 0; k < 8; ++k) hits += rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
  }
  return hits;
}

// rtcIntersect1 per pixel (packets: false), or rtcIntersect8 per block of 4 x 2 pixels.
void Throughput_raw_embree(benchmark::State& state, bool packets) {
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(1)));
  const Scene scene = test_case(static_cast<int>(state.range(0)), false);
  const RawEmbree raw(scene);
  const CameraBasis camera = camera_basis(scene.camera);
  const Vec3 eye = scene.camera.world_line.position;
  std::atomic<long long> hits{0};
  static_assert(kHeight % 2 == 0 && kWidth % 4 == 0);
  for (auto _ : state) {
    tbb::parallel_for(0, kHeight / 2, [&](int row_pair) {
      if (packets) {
        hits += raw_packet_rows(raw, camera, eye, kWidth, 2 * row_pair);
        return;
      }
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      long long row_hits = 0;
      for (int y = 2 * row_pair; y < 2 * row_pair + 2; ++y)
        for (int x = 0; x < kWidth; ++x) {
          const RawRay r = raw_ray(camera, eye, x, y);
          RTCRayHit rh{};
          rh.ray.org_x = r.org[0];
          rh.ray.org_y = r.org[1];
          rh.ray.org_z = r.org[2];
          rh.ray.dir_x = r.dir[0];
          rh.ray.dir_y = r.dir[1];
          rh.ray.dir_z = r.dir[2];
          rh.ray.tfar = INFINITY;
          rh.ray.mask = ~0u;
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(raw.top, &context, &rh);
          row_hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
      hits += row_hits;
    });
  }
  set_rates(state, double(kWidth) * kHeight);
  state.counters["hit_fraction"] = double(hits) / (double(kWidth) * kHeight * state.iterations());
}

void Throughput_lightcone(benchmark::State& state, bool moving) {
  const Scene scene = test_case(static_cast<int>(state.range(0)), moving);
  RenderOptions options;
  options.threads = static_cast<int>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(render_image(scene, options));
  set_rates(state, double(kWidth) * kHeight);
}

// The radius of swarm(count, radius, max_speed) for which camera rays through pixel centres hit
// a body in `coverage` of a 240 x 135 image (bisection: the coverage grows with the radius).
double radius_covering(int count, double coverage, double max_speed) {
  double lo = 0.01 * std::sqrt(100.0 / count), hi = 5 * std::sqrt(100.0 / count);
  for (int i = 0; i < 12; ++i) {
    const double mid = std::sqrt(lo * hi);
    Scene scene = swarm(count, mid, max_speed);
    scene.camera.width = 240;
    scene.camera.height = 135;
    const ResolvedScene resolved = resolve_scene(scene);
    const Tracer tracer(resolved);
    int hits = 0;
    for (int y = 0; y < scene.camera.height; ++y)
      for (int x = 0; x < scene.camera.width; ++x)
        hits += tracer.trace(look_direction(resolved.camera, x + 0.5, y + 0.5)).has_value();
    (hits < coverage * scene.camera.width * scene.camera.height ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

void DenseSwarm(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  const bool lit = state.range(1) == 1;
  Scene scene = swarm(count, radius_covering(count, 0.3, 0.99), 0.99);
  scene.camera.width = 960;
  scene.camera.height = 540;
  if (lit) {
    for (Object& o : scene.objects) o.material.unlit = false;
    Light light;
    light.kind = PointLight{};
    light.world_line.position = {10, 20, 0};
    light.intensity = 500;
    scene.lights.push_back(light);
  }
  // The renderer's time apart from its setup (setup_s), on one thread.
  RenderOptions options;
  options.threads = 1;
  RenderStats stats;
  double ray_seconds = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(render_image(scene, options, &stats));
    state.SetIterationTime(stats.seconds - stats.setup_seconds);
    ray_seconds += stats.seconds - stats.setup_seconds;
  }
  const ResolvedScene resolved = resolve_scene(scene);
  const Tracer tracer(resolved);
  std::size_t hits = 0;
  for (int y = 0; y < scene.camera.height; ++y)
    for (int x = 0; x < scene.camera.width; ++x)
      hits += tracer.trace(look_direction(resolved.camera, x + 0.5, y + 0.5)).has_value();
  const double rays = double(scene.camera.width) * scene.camera.height;
  state.counters["radius"] = scene.objects[0].scale.x;
  state.counters["hit_fraction"] = hits / rays;
  state.counters["setup_s"] = stats.setup_seconds;
  state.counters["s_per_ray"] = ray_seconds / (rays * static_cast<double>(state.iterations()));
}

// Raw Embree's own cost in a dense swarm: the same swarm at rest (at the places the camera
// sees its bodies), each body an instance of the icosphere, covering 30 % of the image too;
// rtcIntersect8 through blocks of 4 x 2 pixels, one thread, no shading.
void DenseSwarm_raw_embree(benchmark::State& state) {
  constexpr int kSwarmWidth = 960, kSwarmHeight = 540;
  const int count = static_cast<int>(state.range(0));
  Scene scene = swarm(count, radius_covering(count, 0.3, 0), 0);
  scene.camera.width = kSwarmWidth;
  scene.camera.height = kSwarmHeight;
  const RawEmbree raw(scene);
  const CameraBasis camera = camera_basis(scene.camera);
  const Vec3 eye = scene.camera.world_line.position;
  long long hits = 0;
  for (auto _ : state)
    for (int y0 = 0; y0 < kSwarmHeight; y0 += 2)
      hits += raw_packet_rows(raw, camera, eye, kSwarmWidth, y0);
  const double rays = double(kSwarmWidth) * kSwarmHeight;
  state.counters["hit_fraction"] = double(hits) / (rays * static_cast<double>(state.iterations()));
  state.counters["s_per_ray"] = benchmark::Counter(
      rays, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void cases_and_threads(benchmark::internal::Benchmark* b) {
  b->ArgNames({"case", "threads"});
  for (int c : {kGrid, kStreet, kSwarm})
    for (int t : {1, 2}) b->Args({c, t});
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK_CAPTURE(Throughput_raw_embree, single, false)->Apply(cases_and_threads);
BENCHMARK_CAPTURE(Throughput_raw_embree, packets, true)->Apply(cases_and_threads);
BENCHMARK_CAPTURE(Throughput_lightcone, static, false)->Apply(cases_and_threads);
BENCHMARK_CAPTURE(Throughput_lightcone, moving, true)->Apply(cases_and_threads);
BENCHMARK(DenseSwarm)
    ->ArgNames({"bodies", "lit"})
    ->ArgsProduct({{100, 1000, 10000}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime();
BENCHMARK(DenseSwarm_raw_embree)
    ->ArgNames({"bodies"})
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);

}  // namespace
