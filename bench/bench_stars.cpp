// The star catalogue (issue: "Loading the catalogue takes at most 20 ms"):
//   StarCatalogueLoad   read_star_catalogue of the bundled catalogue (8,789 naked-eye stars),
//                       file to memory, checked.
#include <benchmark/benchmark.h>

#include "lightcone/io/star_catalogue.hpp"

using namespace lightcone;

namespace {

void StarCatalogueLoad(benchmark::State& state) {
  const auto path = bright_star_catalogue_path();
  std::size_t stars = 0;
  for (auto _ : state) {
    const auto catalogue = read_star_catalogue(path);
    stars = catalogue.size();
    benchmark::DoNotOptimize(catalogue.data());
  }
  state.counters["stars"] = static_cast<double>(stars);
}
BENCHMARK(StarCatalogueLoad)->Unit(benchmark::kMillisecond);

}  // namespace
