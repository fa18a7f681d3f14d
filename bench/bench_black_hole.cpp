// The black hole (issue: "Tracer: the black-hole.json sky and disk at 1920x1080, 1 sample, in at
// most 0.5 s on 2 threads"):
//   BlackHole              scenes/black-hole.json at 1920x1080, 1 sample, on 2 threads: the
//                          time is render_image's whole (setup, tracing, exposure); cpu_s is the
//                          process's CPU time per render, summed over its threads, which a
//                          shared machine disturbs less than the wall time; setup_s the
//                          time to resolve the scene and build its tables (RenderStats).
//   BlackHoleRays          follow_curved_rays and curved_radiance alone through every pixel
//                          centre of that image, on one thread, in packets of 4x2 pixels as the
//                          renderer takes them: ns_per_ray.
//   LitBodies/hole:1 and /hole:0
//                          ("A lit scene of bodies with a hole costs at most 3x the same scene
//                          without one"): twelve lit spheres and boxes at rest at 8 to 20 M
//                          about a hole of mass 1, a point lamp and a sun, shadows on, seen
//                          from 40M at 480x270, 1 sample, 1 thread; and the same scene without
//                          the hole. The ratio of the two times is the figure.
//   HoleBodyFrame/<scene>  the CPU's share of one raster frame of a scene with bodies near the
//                          hole, at 640x360 (the viewer's "black-hole.json at 640x360 at least
//                          25 fps" for scenes with bodies): resolving the scene, its emission
//                          and lighting tables (tables_ms) and the images of orders 0 and 1 of
//                          every body, lit ones coloured per vertex (images_ms), on one thread.
//   HoleShadowFrame/<segments>
//                          the same for LitBodies' scene with the hole, two of its boxes
//                          replaced by the bundled wheel (a mesh of 1,056 triangles), shadows
//                          cast: the chords of the shadow paths met through the ray tracer's
//                          Embree scenes (embree), or directly, as the browser's page meets
//                          them (direct, frame/body_segments.hpp).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "lightcone/frame/body_segments.hpp"
#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/curved_bodies.hpp"
#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/lighting.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/raster/hole_bodies.hpp"
#include "lightcone/trace/curved_shadows.hpp"
#include "lightcone/trace/renderer.hpp"

using namespace lightcone;

namespace {

Scene black_hole_1080p() {
  SceneLoadReport report;
  return load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/black-hole.json",
                         {"camera.width=1920", "camera.height=1080", "camera.samples=1"}, report);
}

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void BM_BlackHole(benchmark::State& state) {
  const Scene scene = black_hole_1080p();
  RenderOptions options;
  options.threads = 2;
  RenderStats stats;
  double cpu = 0, setup = 0;
  for (auto _ : state) {
    const double before = process_cpu_seconds();
    Image image = render_image(scene, options, &stats);
    cpu += process_cpu_seconds() - before;
    setup += stats.setup_seconds;
    benchmark::DoNotOptimize(image.rgb.data());
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(stats.rays) * n, benchmark::Counter::kIsRate);
  state.counters["cpu_s"] = cpu / n;
  state.counters["setup_s"] = setup / n;
}
BENCHMARK(BM_BlackHole)->Unit(benchmark::kMillisecond)->Iterations(5)->UseRealTime();

void BM_BlackHoleRays(benchmark::State& state) {
  const Scene scene = black_hole_1080p();
  const ResolvedScene resolved = resolve_scene(scene);
  const EmissionTable emission(resolved);
  const int width = scene.camera.width, height = scene.camera.height;
  for (auto _ : state) {
    double sum = 0;
    for (int by = 0; by < height; by += 2)
      for (int bx = 0; bx < width; bx += 4) {
        Vec3 u[8];
        CurvedRay rays[8];
        std::size_t n = 0;
        for (int j = by; j < std::min(by + 2, height); ++j)
          for (int i = bx; i < std::min(bx + 4, width); ++i)
            u[n++] = look_direction(resolved.camera, i + 0.5, j + 0.5);
        follow_curved_rays(*resolved.hole, std::span(u, n), nullptr, std::span(rays, n));
        for (std::size_t l = 0; l < n; ++l) sum += curved_radiance(resolved, emission, rays[l]).g;
      }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["ns_per_ray"] = benchmark::Counter(
      static_cast<double>(width) * height * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_BlackHoleRays)->Unit(benchmark::kMillisecond)->Iterations(3);

Scene lit_bodies(bool hole) {
  Scene s;
  s.camera.world_line.position = {0, 6, 40};
  s.camera.forward = normalize(Vec3{0, -0.15, -1});
  s.camera.fov_degrees = 40;
  s.camera.width = 480;
  s.camera.height = 270;
  s.camera.samples = 1;
  if (hole) s.black_hole = BlackHole{{0, 0, 0}, 1, std::nullopt};
  for (int i = 0; i < 12; ++i) {
    Object o;
    o.name = "body" + std::to_string(i);
    const double angle = 0.52 * i, r = 8 + i;
    o.world_line.position = {r * std::cos(angle), 1.5 * std::sin(1.7 * i), r * std::sin(angle)};
    if (i % 2 == 0)
      o.shape = Sphere{1};
    else
      o.shape = Box{{1.6, 1.2, 1.4}};
    o.material.pattern = Checker{0.4, {{0.9f, 0.8f, 0.6f}, {0.3f, 0.4f, 0.7f}}};
    o.material.unlit = false;
    s.objects.push_back(o);
  }
  Light lamp;
  lamp.name = "lamp";
  lamp.kind = PointLight{};
  lamp.world_line.position = {-14, 10, 6};
  lamp.intensity = 300;
  lamp.spectrum.emission = Rgb{1, 0.9f, 0.8f};
  s.lights.push_back(lamp);
  Light sun;
  sun.name = "sun";
  DirectionalLight d;
  d.direction = normalize(Vec3{-1, -0.3, -0.2});
  d.irradiance = 2;
  sun.kind = d;
  sun.spectrum.emission = Rgb{1, 1, 1};
  s.lights.push_back(sun);
  return s;
}

void BM_LitBodies(benchmark::State& state) {
  const Scene scene = lit_bodies(state.range(0) != 0);
  RenderOptions options;
  options.threads = 1;
  for (auto _ : state) {
    Image image = render_image(scene, options);
    benchmark::DoNotOptimize(image.rgb.data());
  }
}
BENCHMARK(BM_LitBodies)
    ->ArgName("hole")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

// The CPU's share of a raster frame near the hole: the tables (lights shadowed by `shadows`, if
// any), then the images of the bodies.
void hole_frame(
    benchmark::State& state, const Scene& scene,
    const std::function<std::unique_ptr<CurvedShadowQuery>(const ResolvedScene&)>& shadows) {
  const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  double tables_s = 0, images_s = 0;
  std::size_t floats = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const ResolvedScene resolved = resolve_scene(scene);
    const EmissionTable emission(resolved);
    const auto query = shadows ? shadows(resolved) : nullptr;
    const Lighting lighting(resolved, nullptr, query.get());
    const auto t1 = std::chrono::steady_clock::now();
    std::vector<RestMesh> meshes;
    meshes.reserve(resolved.bodies.size());
    std::vector<HoleBodiesPass::Body> bodies;
    for (std::size_t i = 0; i < resolved.bodies.size(); ++i) {
      const Object& object = *resolved.bodies[i].object;
      meshes.push_back(rest_mesh(object.shape));
      bodies.push_back({i, &meshes.back(), 0, 0, !object.material.unlit});
    }
    const auto parts = hole_body_vertices(resolved, bodies, emission, lighting, {});
    const auto t2 = std::chrono::steady_clock::now();
    tables_s += std::chrono::duration<double>(t1 - t0).count();
    images_s += std::chrono::duration<double>(t2 - t1).count();
    floats = 0;
    for (const auto& part : parts) floats += part.size();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["tables_ms"] = 1e3 * tables_s / n;
  state.counters["images_ms"] = 1e3 * images_s / n;
  state.counters["triangles"] = static_cast<double>(floats / kHoleVertexFloats / 3);
}

void HoleBodyFrame(benchmark::State& state, const char* name) {
  SceneLoadReport report;
  const Scene scene = load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/" + name,
                                      {"camera.width=640", "camera.height=360"}, report);
  hole_frame(state, scene, nullptr);
}
BENCHMARK_CAPTURE(HoleBodyFrame, infall, "infall.json")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);
BENCHMARK_CAPTURE(HoleBodyFrame, lensed_clock, "lensed-clock.json")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);
BENCHMARK_CAPTURE(HoleBodyFrame, orbit, "orbit.json")->Unit(benchmark::kMillisecond)->Iterations(3);

void HoleShadowFrame(benchmark::State& state, bool direct) {
  Scene scene = lit_bodies(true);
  SceneLoadReport report;
  const Scene wheel =
      load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/wheel.json", {}, report);
  for (const int i : {1, 5}) scene.objects[i].shape = wheel.objects[0].shape;
  hole_frame(state, scene, [direct](const ResolvedScene& resolved) {
    return direct ? curved_body_shadows_met_by(resolved,
                                               std::make_unique<DirectBodySegments>(resolved))
                  : curved_body_shadows(resolved);
  });
}
BENCHMARK_CAPTURE(HoleShadowFrame, embree, false)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(HoleShadowFrame, direct, true)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
