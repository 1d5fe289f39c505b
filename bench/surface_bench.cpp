// Virtual gonioreflectometer speed: paths per second on ONE thread (= per core), on a generated
// road sample (ellipsoidal grains in a matrix, 30 mm x 30 mm, 0.1 mm cells) and on a flat sample,
// with 1 and 20 wavelengths. items_per_second = paths/s/core.
// BM_GlossySampling: a generated road sample whose materials are glossy (oren-nayar+torrance-sparrow,
// Torrance-Sparrow roughness 0.05 rad), forward specular geometry 60/60 deg, 20 wavelengths, cosine
// (arg 0) vs BRDF (arg 1) sampling; counter rel_se = median over iterations of the relative standard
// error (550 nm band) of one 4096-path estimate, so that rel_se^2 x time compares the efficiency.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/render.h"

namespace rs = roadbrdf::surface;

namespace {

rs::MaterialSpec material(const std::string& name, double albedo, double roughness = 0.0) {
  rs::MaterialSpec m;
  m.name = name;
  m.model = "oren-nayar+torrance-sparrow";
  m.parameters = {{"oren-nayar.albedo", albedo}};
  if (roughness > 0.0) m.parameters["torrance-sparrow.roughness"] = roughness;
  return m;
}

rs::HeightField make_road_sample(double roughness) {
  {
    rs::SampleRecipe recipe;
    recipe.name = "bench";
    recipe.matrix = material("mastic", 0.08, roughness);
    rs::GrainClass a;
    a.material = material("2/6", 0.3, roughness);
    a.d_min_mm = 2;
    a.d_max_mm = 6;
    a.volume_fraction = 0.18;
    rs::GrainClass b;
    b.material = material("6/10", 0.35, roughness);
    b.d_min_mm = 6;
    b.d_max_mm = 10;
    b.volume_fraction = 0.3;
    recipe.classes = {a, b};
    rs::GeneratorSettings s;
    s.size_mm = 30.0;
    s.cell_size_mm = 0.1;
    s.target_mpd_mm = 0.8;
    return rs::generate_sample(recipe, s).field;
  }
}

const rs::HeightField& road_sample() {
  static const rs::HeightField field = make_road_sample(0.0);
  return field;
}

void run(benchmark::State& state, const rs::HeightField& field) {
  const int n_wavelengths = static_cast<int>(state.range(0));
  std::vector<double> wl;
  for (int k = 0; k < n_wavelengths; ++k) wl.push_back(400.0 + 10.0 * k);
  const rs::Renderer renderer(field, rs::load_materials(field, wl), wl.size());
  rs::RenderSettings s;
  s.samples = 4096;
  s.threads = 1;
  s.acceptance_half_angle_deg = 1.0;
  const roadbrdf::Geometry g = roadbrdf::geometry_from_degrees(60, 0, 60, 180);
  std::uint64_t stream = 0;
  for (auto _ : state) {
    const rs::Estimate e = renderer.brdf(g, s, stream++);
    benchmark::DoNotOptimize(e.mean.data());
  }
  state.SetItemsProcessed(state.iterations() * s.samples);
}

void BM_GlossySampling(benchmark::State& state) {
  static const rs::HeightField field = make_road_sample(0.05);
  std::vector<double> wl;
  for (int k = 0; k < 20; ++k) wl.push_back(400.0 + 20.0 * k);
  const rs::Renderer renderer(field, rs::load_materials(field, wl), wl.size());
  rs::RenderSettings s;
  s.samples = 4096;
  s.threads = 1;
  s.acceptance_half_angle_deg = 1.0;
  s.sampling = state.range(0) == 0 ? rs::Sampling::cosine : rs::Sampling::brdf;
  const roadbrdf::Geometry g = roadbrdf::geometry_from_degrees(60, 0, 60, 180);
  std::uint64_t stream = 0;
  std::vector<double> rel;
  for (auto _ : state) {
    const rs::Estimate e = renderer.brdf(g, s, stream++);
    rel.push_back(e.standard_error[7] / e.mean[7]);
  }
  std::sort(rel.begin(), rel.end());
  state.counters["rel_se"] = rel[rel.size() / 2];
  state.SetItemsProcessed(state.iterations() * s.samples);
}

void BM_PathsRoadSample(benchmark::State& state) { run(state, road_sample()); }
void BM_PathsFlatSample(benchmark::State& state) {
  static const rs::HeightField flat = rs::make_flat(material("flat", 0.3), 16, 0.1);
  run(state, flat);
}

}  // namespace

BENCHMARK(BM_PathsRoadSample)->Arg(1)->Arg(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PathsFlatSample)->Arg(1)->Arg(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GlossySampling)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(3.0);
