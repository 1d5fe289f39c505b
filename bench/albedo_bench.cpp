// Albedo speed: black-sky at 10 sun zeniths + white-sky of a fitted-like
// oren-nayar+torrance-sparrow at 2151 wavelengths (350-2500 nm, 1 nm), default tolerance 1e-5, one core.
// The parameters are synthetic but shaped like a road fit: a spectral diffuse albedo rising from 0.05 to
// 0.25, a weak specular lobe (k_s 0.03-0.05, GGX roughness 0.3, ior 1.6 -> 1.5), sigma 0.3 (non-spectral).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/registry.h"

namespace {

using namespace roadbrdf;

struct Fixture {
  std::unique_ptr<Model> model = make_model("oren-nayar+torrance-sparrow");
  std::vector<double> params;
  std::size_t n_sets = 0;
  explicit Fixture(std::size_t n) : n_sets(n) {
    const auto& d = model->description();
    for (std::size_t s = 0; s < n; ++s) {
      const double t = n > 1 ? static_cast<double>(s) / static_cast<double>(n - 1) : 0.0;
      std::vector<double> p = parameters_from_assignments(d, {{"oren-nayar.albedo", 0.05 + 0.2 * t},
                                                              {"oren-nayar.sigma", 0.3},
                                                              {"torrance-sparrow.ks", 0.05 - 0.02 * t},
                                                              {"torrance-sparrow.roughness", 0.3},
                                                              {"torrance-sparrow.ior", 1.6 - 0.1 * t}});
      params.insert(params.end(), p.begin(), p.end());
    }
  }
};

void BM_BlackSky10PlusWhiteSky(benchmark::State& state) {
  Fixture f(static_cast<std::size_t>(state.range(0)));
  std::size_t geometries = 0;
  double worst = 0.0;
  for (auto _ : state) {
    geometries = 0;
    worst = 0.0;
    for (int k = 0; k < 10; ++k) {
      const auto r = albedo::black_sky(*f.model, f.params.data(), f.n_sets, k * 9.0 * kDegree);
      geometries += r.geometries;
      worst = std::max(worst, r.max_error());
      benchmark::DoNotOptimize(r.value.data());
    }
    const auto w = albedo::white_sky(*f.model, f.params.data(), f.n_sets);
    geometries += w.geometries;
    worst = std::max(worst, w.max_error());
    benchmark::DoNotOptimize(w.value.data());
  }
  state.counters["geometries"] = static_cast<double>(geometries);
  state.counters["max_error"] = worst;
}
BENCHMARK(BM_BlackSky10PlusWhiteSky)->Arg(1)->Arg(2151)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_WhiteSkyOnly(benchmark::State& state) {
  Fixture f(static_cast<std::size_t>(state.range(0)));
  std::size_t geometries = 0;
  for (auto _ : state) {
    const auto w = albedo::white_sky(*f.model, f.params.data(), f.n_sets);
    geometries = w.geometries;
    benchmark::DoNotOptimize(w.value.data());
  }
  state.counters["geometries"] = static_cast<double>(geometries);
}
BENCHMARK(BM_WhiteSkyOnly)->Arg(2151)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_BlackSky10Only(benchmark::State& state) {
  Fixture f(static_cast<std::size_t>(state.range(0)));
  std::size_t geometries = 0;
  for (auto _ : state) {
    geometries = 0;
    for (int k = 0; k < 10; ++k) {
      const auto r = albedo::black_sky(*f.model, f.params.data(), f.n_sets, k * 9.0 * kDegree);
      geometries += r.geometries;
      benchmark::DoNotOptimize(r.value.data());
    }
  }
  state.counters["geometries"] = static_cast<double>(geometries);
}
BENCHMARK(BM_BlackSky10Only)->Arg(2151)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
