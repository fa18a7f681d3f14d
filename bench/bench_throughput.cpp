// lightcone's throughput against raw Embree on the same triangles (issue 13), one run:
//   Throughput/raw_embree/threads:T      rtcIntersect1 per pixel through the same 100 instances
//                                        of one mesh, nothing else (what a user could write)
//   Throughput/lightcone_static/threads:T   lightcone's render of the same scene, bodies at rest,
//                                        unlit, doppler off, 1 sample
//   Throughput/lightcone_moving/threads:T   the same bodies moving at 0.9c
// The scene: a 10 x 10 grid of unit UV spheres (100 x 10,082 triangles, one shared mesh) at
// distance 20, camera at rest, fov 70, 1920 x 1080. The figures are rays_per_s; the targets are
// ratios to raw_embree at the same thread count: >= 0.70 at rest, >= 0.60 in motion.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <numbers>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/trace/renderer.hpp"

using namespace lightcone;

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

const std::shared_ptr<const Mesh>& sphere_mesh() {
  static const std::shared_ptr<const Mesh> mesh = uv_sphere(71, 72);
  return mesh;
}

Vec3 grid_position(int i) {
  return {2.5 * (i % 10) - 11.25, 2.5 * (i / 10) - 11.25, -20.0};
}

Scene grid(bool moving) {
  Scene s;
  s.camera.width = kWidth;
  s.camera.height = kHeight;
  s.camera.fov_degrees = 70;
  s.render.doppler = DopplerModel::kOff;
  s.render.searchlight = SearchlightModel::kOff;
  for (int i = 0; i < 100; ++i) {
    Object o;
    o.name = "sphere" + std::to_string(i);
    o.shape = MeshShape{sphere_mesh()};
    o.world_line.position = grid_position(i);
    if (moving) {
      // Moving at 0.9c along x, placed where the camera sees them where they stand at rest.
      o.world_line.velocity = {0.9, 0, 0};
      o.world_line.time = -length(grid_position(i));
    }
    s.objects.push_back(std::move(o));
  }
  return s;
}

void Throughput_raw_embree(benchmark::State& state) {
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(0)));
  const Mesh& mesh = *sphere_mesh();
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene object = rtcNewScene(device);
  rtcSetSceneBuildQuality(object, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry triangles = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(triangles, RTC_BUFFER_TYPE_VERTEX, 0,
                                                        RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                        mesh.positions.size()));
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(mesh.positions[i][k]);
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(triangles, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                             mesh.triangles.size()));
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) idx[3 * i + k] = mesh.triangles[i][k];
  rtcCommitGeometry(triangles);
  rtcAttachGeometry(object, triangles);
  rtcReleaseGeometry(triangles);
  rtcCommitScene(object);
  RTCScene top = rtcNewScene(device);
  for (int i = 0; i < 100; ++i) {
    RTCGeometry instance = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(instance, object);
    const Vec3 p = grid_position(i);
    const float transform[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, float(p.x), float(p.y), float(p.z)};
    rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, transform);
    rtcCommitGeometry(instance);
    rtcAttachGeometry(top, instance);
    rtcReleaseGeometry(instance);
  }
  rtcCommitScene(top);
  const CameraBasis camera = camera_basis(grid(false).camera);
  std::atomic<long long> hits{0};
  for (auto _ : state) {
    tbb::parallel_for(0, kHeight, [&](int y) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      long long row_hits = 0;
      for (int x = 0; x < kWidth; ++x) {
        const Vec3 u = look_direction(camera, x + 0.5, y + 0.5);
        RTCRayHit rh{};
        rh.ray.dir_x = float(u.x);
        rh.ray.dir_y = float(u.y);
        rh.ray.dir_z = float(u.z);
        rh.ray.tfar = INFINITY;
        rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(top, &context, &rh);
        row_hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      }
      hits += row_hits;
    });
  }
  state.counters["rays_per_s"] =
      benchmark::Counter(double(kWidth) * kHeight, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["hit_fraction"] = double(hits) / (double(kWidth) * kHeight * state.iterations());
  rtcReleaseScene(top);
  rtcReleaseScene(object);
  rtcReleaseDevice(device);
}

void Throughput_lightcone(benchmark::State& state, bool moving) {
  const Scene scene = grid(moving);
  RenderOptions options;
  options.threads = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(render_image(scene, options));
  state.counters["rays_per_s"] =
      benchmark::Counter(double(kWidth) * kHeight, benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK(Throughput_raw_embree)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(Throughput_lightcone, static, false)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(Throughput_lightcone, moving, true)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
