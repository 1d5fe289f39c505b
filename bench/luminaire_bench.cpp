// Luminaire photometry speed: IntensityDistribution::intensity() (called 10^4-10^5 times per road
// installation by the lighting calculation) and the flux integral, on synthetic distributions of the
// sizes of real files: 360 C-planes x 131 gamma angles (a 1 deg road luminaire) and 72 x 361 (5 deg by
// 0.5 deg), and one plane (rotational symmetry). Directions sweep C and gamma over the lower hemisphere.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>

#include "roadbrdf/lighting/luminaire.h"
#include "roadbrdf/lighting/luminaire_flux.h"

namespace {

using roadbrdf::lighting::IntensityDistribution;

IntensityDistribution grid(std::size_t planes, std::size_t angles, double gamma_max) {
  IntensityDistribution d;
  for (std::size_t i = 0; i < planes; ++i)
    d.c_deg.push_back(360.0 * static_cast<double>(i) / static_cast<double>(planes));
  for (std::size_t j = 0; j < angles; ++j) {
    d.gamma_deg.push_back(gamma_max * static_cast<double>(j) / static_cast<double>(angles - 1));
  }
  for (const double c : d.c_deg) {
    for (const double g : d.gamma_deg)
      d.candela.push_back(500.0 + 300.0 * std::cos(g * 0.0174533) * (1.0 + 0.3 * std::sin(c * 0.0174533)));
  }
  return d;
}

IntensityDistribution for_range(const benchmark::State& state) {
  switch (state.range(0)) {
    case 0:
      return grid(360, 131, 130.0);
    case 1:
      return grid(72, 361, 180.0);
    default:
      return grid(1, 37, 180.0);
  }
}

void BM_Intensity(benchmark::State& state) {
  const IntensityDistribution d = for_range(state);
  constexpr int kCalls = 10000;
  for (auto _ : state) {
    double sum = 0.0;
    for (int k = 0; k < kCalls; ++k) sum += d.intensity(k * 0.0361, (k % 900) * 0.1);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * kCalls);
}
BENCHMARK(BM_Intensity)->Arg(0)->Arg(1)->Arg(2);

void BM_FluxIntegral(benchmark::State& state) {
  const IntensityDistribution d = for_range(state);
  for (auto _ : state) benchmark::DoNotOptimize(roadbrdf::lighting::luminous_flux(d).total_lm());
}
BENCHMARK(BM_FluxIntegral)->Arg(0)->Arg(1)->Arg(2);

}  // namespace
