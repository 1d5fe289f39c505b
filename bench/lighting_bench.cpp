// Speed of the road-lighting calculation (docs/lighting.md, "Speed"): one installation of the
// standard (2 lanes with an observer each, the standard grid, every contributing luminaire)
// from a spectral BRDF as a fit gives it (41 wavelengths, 380-780 nm), r-table included; the lighting
// part alone on a prepared surface; and the upward and alpha-variation parts.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "roadbrdf/lighting/lighting_request.h"
#include "roadbrdf/models/registry.h"

namespace {

using namespace roadbrdf;
using namespace roadbrdf::lighting;

Luminaire road_luminaire() {
  Luminaire l;
  l.name = "synthetic road luminaire";
  for (int c = 0; c < 360; c += 5) l.distribution.c_deg.push_back(c);
  for (int g = 0; g <= 180; ++g) l.distribution.gamma_deg.push_back(g);
  for (double c : l.distribution.c_deg) {
    for (double g : l.distribution.gamma_deg) {
      const double rad = 3.141592653589793 / 180.0;
      const double along = std::pow(std::cos(c * rad), 2.0);
      const double beam = std::cos(g * rad) + 2.5 * along * std::exp(-std::pow((g - 65.0) / 12.0, 2));
      l.distribution.candela.push_back(g < 90.0 ? 400.0 * (1.0 + 0.6 * std::sin(c * rad)) * beam : 0.0);
    }
  }
  l.flux_lm = 12000.0;
  l.power_w = 90.0;
  return l;
}

SpectralModel fitted_like_model() {
  const std::shared_ptr<const Model> model(make_model("oren-nayar"));
  std::vector<double> wavelengths, table;
  for (int k = 0; k <= 40; ++k) {
    wavelengths.push_back(380.0 + 10.0 * k);
    std::vector<double> p = model->description().default_parameters();
    p[0] = 0.08 + 0.002 * k;  // a grey, slightly reddish pavement
    table.insert(table.end(), p.begin(), p.end());
  }
  return SpectralModel(model, wavelengths, table);
}

Installation standard_installation() {
  Installation inst;
  inst.road.lanes = 2;
  inst.road.lane_width_m = 3.5;
  inst.luminaires.spacing_m = 30.0;
  inst.luminaires.height_m = 10.0;
  inst.luminaires.maintenance_factor = 0.8;
  return inst;
}

void BM_LightingFromSpectralBrdf(benchmark::State& state) {
  const Luminaire luminaire = road_luminaire();
  const SpectralModel model = fitted_like_model();
  const Installation inst = standard_installation();
  for (auto _ : state) {
    Diagnostics d;
    const RoadSurface surface = surface_from_model(model, "bench", d);
    const LightingResult r = evaluate_installation(inst, luminaire, surface, {"M4", 4000.0});
    benchmark::DoNotOptimize(r.figures.L_av);
  }
}
BENCHMARK(BM_LightingFromSpectralBrdf)->Unit(benchmark::kMillisecond);

void BM_SurfaceFromSpectralBrdf(benchmark::State& state) {
  const SpectralModel model = fitted_like_model();
  for (auto _ : state) {
    Diagnostics d;
    const RoadSurface surface = surface_from_model(model, "bench", d);
    benchmark::DoNotOptimize(surface.q0);
  }
}
BENCHMARK(BM_SurfaceFromSpectralBrdf)->Unit(benchmark::kMillisecond);

void BM_LightingPartAlone(benchmark::State& state) {
  const Luminaire luminaire = road_luminaire();
  Diagnostics d;
  RoadSurface surface = surface_from_model(fitted_like_model(), "bench", d);
  surface.model.reset();  // the r-table method only: grid, E, L, TI, R_EI
  const Installation inst = standard_installation();
  for (auto _ : state) {
    Diagnostics dd;
    const LightingFigures f = compute_lighting(inst, luminaire, surface, dd);
    benchmark::DoNotOptimize(f.L_av);
  }
}
BENCHMARK(BM_LightingPartAlone)->Unit(benchmark::kMillisecond);

void BM_UpwardLight(benchmark::State& state) {
  const Luminaire luminaire = road_luminaire();
  Diagnostics d;
  const RoadSurface surface = surface_from_model(fitted_like_model(), "bench", d);
  const Installation inst = standard_installation();
  for (auto _ : state) {
    Diagnostics dd;
    const UpwardLight u = upward_light(inst, luminaire, surface, dd);
    benchmark::DoNotOptimize(u.ULOR);
  }
}
BENCHMARK(BM_UpwardLight)->Unit(benchmark::kMillisecond);

}  // namespace

namespace {

void BM_HemisphericalReflectance(benchmark::State& state) {
  Diagnostics d;
  const RoadSurface surface = surface_from_model(fitted_like_model(), "bench", d);
  for (auto _ : state) {
    const ReflectanceTable t = hemispherical_reflectance(surface);
    benchmark::DoNotOptimize(t.reflectance.data());
  }
}
BENCHMARK(BM_HemisphericalReflectance)->Unit(benchmark::kMillisecond);

void BM_DirectUpwardFlux(benchmark::State& state) {
  const Luminaire luminaire = road_luminaire();
  const InstalledPhotometry p = installed_photometry(luminaire, standard_installation().luminaires);
  for (auto _ : state) {
    benchmark::DoNotOptimize(hemisphere_flux(p, PlacedLuminaire{0, 0, 10, 0, true}, true));
  }
}
BENCHMARK(BM_DirectUpwardFlux)->Unit(benchmark::kMillisecond);

}  // namespace
