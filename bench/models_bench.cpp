// Batch evaluation speed of every registered model:
//   <model>/geometries:100000/wavelengths:1   and   <model>/geometries:1000/wavelengths:2151
// items_per_second = BRDF evaluations per second on one core.
// Run: build/bench/models_bench --benchmark_min_time=0.2
// Hapke with the exact H (its default) also has, below: the fitting path (prepared geometries,
// value + Jacobian, one parameter set per wavelength with w varying), and the H function alone
// (table h_tabulated used by the model vs the direct quadrature h_exact), items = H evaluations.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/models/hapke_h_function.h"
#include "roadbrdf/models/hapke_h_table.h"
#include "roadbrdf/models/registry.h"

namespace {

using namespace roadbrdf;

std::vector<Geometry> random_geometries(std::size_t n) {
  roadbrdf::Rng rng(42);
  std::vector<Geometry> g;
  g.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    g.push_back(geometry_from_radians(std::acos(rng.uniform()), 2 * kPi * rng.uniform(), std::acos(rng.uniform()),
                                      2 * kPi * rng.uniform()));
  }
  return g;
}

void bench_model(benchmark::State& state, const std::string& name, const OptionSet& options) {
  const auto model = make_model(name, options);
  const std::size_t n_geometries = static_cast<std::size_t>(state.range(0));
  const std::size_t n_wavelengths = static_cast<std::size_t>(state.range(1));
  const std::vector<Geometry> geometries = random_geometries(n_geometries);
  // Default parameters, with the linear amplitudes varied a little across wavelengths.
  const std::vector<double> defaults = model->description().default_parameters();
  std::vector<double> params;
  for (std::size_t w = 0; w < n_wavelengths; ++w) {
    for (std::size_t q = 0; q < defaults.size(); ++q) {
      const ParameterInfo& info = model->description().parameters[q];
      double v = defaults[q];
      if (info.linear) v = info.lower + (info.upper - info.lower) * (0.2 + 0.6 * double(w % 7) / 7.0);
      if (!std::isfinite(v)) v = defaults[q];
      params.push_back(v);
    }
  }
  std::vector<double> out(n_geometries * n_wavelengths);
  for (auto _ : state) {
    model->evaluate_batch(geometries.data(), n_geometries, params.data(), n_wavelengths, out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * n_geometries * n_wavelengths));
}

// What the fitter does per cost evaluation: 89 prepared geometries (as garonne.csv), value and
// Jacobian for each of 108 wavelengths, w varying over [0.05, 0.99] across wavelengths.
void bench_hapke_fit_path(benchmark::State& state) {
  const auto model = make_model("hapke");
  const std::vector<Geometry> geometries = random_geometries(89);
  const auto prepared = model->prepare(geometries.data(), geometries.size());
  const std::size_t n_sets = 108;
  std::vector<double> params;
  for (std::size_t s = 0; s < n_sets; ++s) {
    for (double v : {0.05 + 0.94 * double(s) / (n_sets - 1), 0.3, 0.06, -0.2}) params.push_back(v);
  }
  std::vector<double> values(geometries.size()), jacobian(geometries.size() * 4);
  for (auto _ : state) {
    for (std::size_t s = 0; s < n_sets; ++s) {
      model->evaluate_prepared_with_gradient(*prepared, params.data() + 4 * s, values.data(), jacobian.data());
      benchmark::DoNotOptimize(jacobian.data());
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * n_sets * geometries.size()));
}
BENCHMARK(bench_hapke_fit_path)->Name("hapke/fit_path:89x108,jacobian")->Unit(benchmark::kMillisecond);

// H(x, w) alone on 4096 random (x, w) pairs: table (as used by the model) vs direct quadrature.
template <bool kTabulated>
void bench_hapke_h(benchmark::State& state) {
  roadbrdf::Rng rng(3);
  std::vector<double> x(4096), w(4096);
  for (std::size_t k = 0; k < x.size(); ++k) {
    x[k] = rng.uniform();
    w[k] = rng.uniform();
  }
  for (auto _ : state) {
    double sum = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      sum += kTabulated ? hapke::h_tabulated(x[k], w[k]) : hapke::h_exact(x[k], w[k]);
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * x.size()));
}
BENCHMARK(bench_hapke_h<true>)->Name("hapke/H:table");
BENCHMARK(bench_hapke_h<false>)->Name("hapke/H:direct_quadrature");

struct Registration {
  Registration() {
    std::vector<std::pair<std::string, OptionSet>> variants;
    for (const std::string& name : model_names()) variants.push_back({name, {}});
    // The reference configuration for torrance-sparrow, and the report's composites.
    for (const std::string& name : model_names()) {
      if (name == "torrance-sparrow") {
        variants.push_back({name, {{"profile", "smith"}, {"distribution", "ggx"}}});
        variants.push_back({"oren-nayar+torrance-sparrow", {}});
        variants.push_back({"lambert+torrance-sparrow", {}});
      }
    }
    for (const auto& [name, options] : variants) {
      std::string label = name;
      for (const auto& [k, v] : options) label += "," + k + "=" + v;
      benchmark::RegisterBenchmark(label.c_str(), bench_model, name, options)
          ->ArgNames({"geometries", "wavelengths"})
          ->Args({100000, 1})
          ->Args({1000, 2151})
          ->Unit(benchmark::kMillisecond);
    }
  }
} registration;

}  // namespace
