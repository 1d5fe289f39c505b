// Virtual gonioreflectometer speed: paths per second on ONE thread (= per core), on a generated
// road sample (ellipsoidal grains in a matrix, 30 mm x 30 mm, 0.1 mm cells) and on a flat sample,
// with 1 and 20 wavelengths. items_per_second = paths/s/core.
#include <benchmark/benchmark.h>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/render.h"

namespace rs = roadbrdf::surface;

namespace {

rs::MaterialSpec material(const std::string& name, double albedo) {
  rs::MaterialSpec m;
  m.name = name;
  m.model = "oren-nayar+torrance-sparrow";
  m.parameters = {{"oren-nayar.albedo", albedo}};
  return m;
}

const rs::HeightField& road_sample() {
  static const rs::HeightField field = [] {
    rs::SampleRecipe recipe;
    recipe.name = "bench";
    recipe.matrix = material("mastic", 0.08);
    rs::GrainClass a;
    a.material = material("2/6", 0.3);
    a.d_min_mm = 2;
    a.d_max_mm = 6;
    a.volume_fraction = 0.18;
    rs::GrainClass b;
    b.material = material("6/10", 0.35);
    b.d_min_mm = 6;
    b.d_max_mm = 10;
    b.volume_fraction = 0.3;
    recipe.classes = {a, b};
    rs::GeneratorSettings s;
    s.size_mm = 30.0;
    s.cell_size_mm = 0.1;
    s.target_mpd_mm = 0.8;
    return rs::generate_sample(recipe, s).field;
  }();
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

void BM_PathsRoadSample(benchmark::State& state) { run(state, road_sample()); }
void BM_PathsFlatSample(benchmark::State& state) {
  static const rs::HeightField flat = rs::make_flat(material("flat", 0.3), 16, 0.1);
  run(state, flat);
}

}  // namespace

BENCHMARK(BM_PathsRoadSample)->Arg(1)->Arg(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PathsFlatSample)->Arg(1)->Arg(20)->Unit(benchmark::kMillisecond);
