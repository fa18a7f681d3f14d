// The kernels of a curved ray near the hole (issue 55: "rays that meet no body cost what they cost
// today"), on one thread, in ns per call:
//   Jacobi/<kernel>_<moduli>  sn, cn, dn of one modulus at 4096 arguments over two periods, for 64
//                          moduli: `boost` is Boost's jacobi_elliptic after three Landen steps,
//                          as radius_after_angle took them before the modulus was prepared once
//                          per orbit, `landen` jacobi_functions. Moduli `far` have k'^2 in
//                          [0.5, 1] (b beyond some 10 M, where both give the same values to the
//                          bit), `near` in [1e-17, 0.5] (toward b_c).
//   CurvedPath             curved_path (photon_orbit, prepare_sweep) for every pixel centre of
//                          scenes/black-hole.json at 480x270.
//   RadiusAfterAngle       radius_after_angle on those paths, at 8 angles spread over each.
//   RayTime                the light's coordinate time from the camera to those points, as a
//                          body's chord end takes it (coordinate_time on each monotonic stretch).
#include <benchmark/benchmark.h>

#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/physics/math_policy.hpp"
#include "lightcone/physics/schwarzschild.hpp"

using namespace lightcone;

namespace {

struct JacobiCase {
  JacobiModulus modulus;
  std::vector<double> y;  // the last modulus's arguments
};

std::vector<JacobiCase> jacobi_cases(bool near) {
  std::mt19937_64 rng(near ? 2 : 1);
  std::uniform_real_distribution<double> log_kc2(near ? -17 : std::log10(0.5), near ? -0.3 : 0);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<JacobiCase> cases(64);
  for (JacobiCase& c : cases) {
    const double kc2 = std::pow(10.0, log_kc2(rng));
    c.modulus = jacobi_modulus(1 - kc2, kc2);
    // K = pi / (2 AGM(1, k')); two periods of sn either side of 0.
    double a = 1, g = std::sqrt(kc2);
    for (int i = 0; i < 40; ++i) {
      const double next = (a + g) / 2;
      g = std::sqrt(a * g), a = next;
    }
    const double quarter = std::acos(-1.0) / (2 * a);
    c.y.resize(4096);
    for (double& y : c.y) y = 4 * quarter * unit(rng) * c.modulus.rate;
  }
  return cases;
}

// radius_after_angle's evaluation before: Boost at the third modulus, three Landen steps up.
JacobiValues boost_after_three_steps(const JacobiModulus& m, double y) {
  JacobiValues j{};
  j.sn = boost::math::jacobi_elliptic(m.k[2], y, &j.cn, &j.dn, MathPolicy());
  for (int i = 2; i >= 0; --i) {
    const double s2 = j.sn * j.sn, n = 1 + m.k[i] * s2;
    j = {(1 + m.k[i]) * j.sn / n, j.cn * j.dn / n, (j.cn * j.cn + m.c[i] * s2) / n};
  }
  return j;
}

void Jacobi(benchmark::State& state, bool landen, bool near) {
  const std::vector<JacobiCase> cases = jacobi_cases(near);
  std::size_t calls = 0;
  for (auto _ : state) {
    double sum = 0;
    for (const JacobiCase& c : cases) {
      if (!landen) {  // beyond three steps the argument is the third modulus's
        double y3 = 1;
        for (int k = 3; k < c.modulus.steps; ++k) y3 *= 1 + c.modulus.k[k];
        for (double y : c.y) sum += boost_after_three_steps(c.modulus, y * y3).cn;
      } else {
        for (double y : c.y) sum += jacobi_functions(c.modulus, y).cn;
      }
      calls += c.y.size();
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["ns_per_call"] = benchmark::Counter(
      static_cast<double>(calls), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK_CAPTURE(Jacobi, boost_far, false, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Jacobi, landen_far, true, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Jacobi, boost_near, false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Jacobi, landen_near, true, true)->Unit(benchmark::kMillisecond);

// black-hole.json's camera rays at 480x270.
struct HoleRays {
  Scene scene;
  ResolvedScene resolved;
  std::vector<Vec3> looks;
  HoleRays() {
    SceneLoadReport report;
    scene = load_scene_file(std::string(LIGHTCONE_SOURCE_DIR) + "/scenes/black-hole.json",
                            {"camera.width=480", "camera.height=270", "camera.samples=1"}, report);
    resolved = resolve_scene(scene);
    for (int j = 0; j < scene.camera.height; ++j)
      for (int i = 0; i < scene.camera.width; ++i)
        looks.push_back(look_direction(resolved.camera, i + 0.5, j + 0.5));
  }
};

void per_call(benchmark::State& state, std::size_t calls) {
  state.counters["ns_per_call"] =
      benchmark::Counter(static_cast<double>(calls) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void CurvedPathPerPixel(benchmark::State& state) {
  const HoleRays rays;
  for (auto _ : state) {
    double sum = 0;
    for (const Vec3& u : rays.looks) sum += curved_path(*rays.resolved.hole, u).sweep.phase;
    benchmark::DoNotOptimize(sum);
  }
  per_call(state, rays.looks.size());
}
BENCHMARK(CurvedPathPerPixel)->Name("CurvedPath")->Unit(benchmark::kMillisecond);

// The same paths eight at a time (curved_paths), as the renderer's packets of a tile's 4x2 pixels
// take them.
void CurvedPathsPerPacket(benchmark::State& state) {
  HoleRays rays;
  const int width = rays.scene.camera.width, height = rays.scene.camera.height;
  std::vector<Vec3> packets;  // the looks of each 4x2 block of pixels, block after block
  for (int by = 0; by < height; by += 2)
    for (int bx = 0; bx < width; bx += 4)
      for (int j = by; j < std::min(by + 2, height); ++j)
        for (int i = bx; i < std::min(bx + 4, width); ++i)
          packets.push_back(rays.looks[static_cast<std::size_t>(j) * width + i]);
  CurvedPath paths[kMaxSweeps];
  for (auto _ : state) {
    double sum = 0;
    for (std::size_t first = 0; first < packets.size(); first += kMaxSweeps) {
      const std::size_t n = std::min<std::size_t>(kMaxSweeps, packets.size() - first);
      curved_paths(*rays.resolved.hole, std::span(packets).subspan(first, n), std::span(paths, n));
      for (std::size_t i = 0; i < n; ++i) sum += paths[i].sweep.phase;
    }
    benchmark::DoNotOptimize(sum);
  }
  per_call(state, packets.size());
}
BENCHMARK(CurvedPathsPerPacket)->Name("CurvedPaths")->Unit(benchmark::kMillisecond);

// Each path's angles: 8 spread over the path up to its end, or over two turns where it winds
// onto the photon sphere.
struct PathPoints {
  std::vector<CurvedPath> paths;
  std::vector<std::vector<double>> phis;
  explicit PathPoints(const HoleRays& rays) {
    for (const Vec3& u : rays.looks) {
      const CurvedPath p = curved_path(*rays.resolved.hole, u);
      if (p.dark || p.sweep.angle_total == 0) continue;
      const double span = std::min(p.sweep.angle_total, 4 * std::acos(-1.0));
      std::vector<double> phi;
      for (int i = 1; i <= 8; ++i) phi.push_back(span * (i - 0.5) / 8.25);
      paths.push_back(p);
      phis.push_back(phi);
    }
  }
  std::size_t points() const { return paths.size() * 8; }
};

void RadiusAfterAngle(benchmark::State& state) {
  const PathPoints points{HoleRays()};
  for (auto _ : state) {
    double sum = 0;
    for (std::size_t i = 0; i < points.paths.size(); ++i)
      for (double phi : points.phis[i]) sum += radius_after_angle(points.paths[i].sweep, phi);
    benchmark::DoNotOptimize(sum);
  }
  per_call(state, points.points());
}
BENCHMARK(RadiusAfterAngle)->Unit(benchmark::kMillisecond);

void RayTime(benchmark::State& state) {
  const HoleRays rays;
  const PathPoints points(rays);
  const double r0 = rays.resolved.hole->camera_radius;
  std::vector<double> radii;
  for (std::size_t i = 0; i < points.paths.size(); ++i)
    for (double phi : points.phis[i])
      radii.push_back(radius_after_angle(points.paths[i].sweep, phi));
  for (auto _ : state) {
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < points.paths.size(); ++i) {
      const CurvedPath& p = points.paths[i];
      const double turn = p.sweep.turning_radius;
      for (double phi : points.phis[i]) {
        const double r = radii[n++];
        sum += turn > 0 && phi > p.sweep.angle_to_turn
                   ? coordinate_time(p.orbit, r0, turn) + coordinate_time(p.orbit, turn, r)
                   : coordinate_time(p.orbit, r0, r);
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  per_call(state, points.points());
}
BENCHMARK(RayTime)->Unit(benchmark::kMillisecond);

}  // namespace
