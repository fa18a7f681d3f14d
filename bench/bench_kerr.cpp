// Exact Kerr rays (physics/kerr_geodesic.hpp, issue 56: "at least 0.9 M rays per CPU-second"), on
// one thread: a distant observer's grid of rays at spin 0.94 and inclination 17 degrees (the
// example of AART, Cardenas-Avendano, Lupsasca & Zhu 2023), each from its screen point (alpha,
// beta) to its first crossing of the equatorial plane.
//   KerrFirstCrossing/<half-width>  a 256 x 256 grid over alpha, beta in [-w, w] M, the observer
//                                   at r = 1000 M: the constants (screen_constants), the ray
//                                   (kerr_ray), the Mino time of the crossing and r, phi, t there
//                                   (point_at_equator) where the ray crosses before leaving.
//                                   rays_per_s counts every ray of the grid per CPU-second;
//                                   crossing the share that crosses, none_real the share of those
//                                   with no real radial root.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "lightcone/physics/kerr.hpp"
#include "lightcone/physics/kerr_geodesic.hpp"

using namespace lightcone::kerr;

namespace {

constexpr double kSpin = 0.94, kObserver = 1000;
const double kInclination = 17 * std::numbers::pi / 180;

void KerrFirstCrossing(benchmark::State& state) {
  const double half_width = static_cast<double>(state.range(0));
  constexpr int kSide = 256;
  std::vector<PhotonConstants> constants;
  std::vector<int> sign_theta;
  for (int j = 0; j < kSide; ++j) {
    for (int i = 0; i < kSide; ++i) {
      const double alpha = half_width * (2 * (i + 0.5) / kSide - 1);
      const double beta = half_width * (2 * (j + 0.5) / kSide - 1);
      constants.push_back(screen_constants(kSpin, alpha, beta, kInclination));
      // beta > 0 is the photon's arriving from smaller theta: traced back, theta decreases.
      sign_theta.push_back(beta > 0 ? -1 : 1);
    }
  }
  const double cos_theta = std::cos(kInclination);
  double checksum = 0;
  long crossing = 0, none_real = 0;
  for (auto _ : state) {
    crossing = none_real = 0;
    for (size_t k = 0; k < constants.size(); ++k) {
      const KerrRay ray = kerr_ray(kSpin, constants[k], kObserver, cos_theta, -1, sign_theta[k]);
      const double tau = mino_time_to_equator(ray, 1);
      if (!(tau < ray.mino_time_limit)) continue;
      const KerrPoint p = point_at_equator(ray, 1);
      ++crossing;
      none_real += ray.radial.roots.kind == RadialCase::NoneReal;
      checksum += p.r + p.phi + 1e-3 * p.t;
    }
    benchmark::DoNotOptimize(checksum);
  }
  const double rays = static_cast<double>(constants.size());
  state.counters["rays_per_s"] = benchmark::Counter(rays * static_cast<double>(state.iterations()),
                                                    benchmark::Counter::kIsRate);
  state.counters["crossing"] = static_cast<double>(crossing) / rays;
  state.counters["none_real"] = static_cast<double>(none_real) / std::max(1.0, double(crossing));
}
BENCHMARK(KerrFirstCrossing)->Arg(8)->Arg(16)->Unit(benchmark::kMillisecond);

}  // namespace
