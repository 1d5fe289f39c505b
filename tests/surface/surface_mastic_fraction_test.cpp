// Exposed mastic fraction of a virtual sample (generate.h `mastic_fraction`, `roadbrdf surface
// --mastic-fraction`): the mastic level is chosen so that the projected area fraction of the mastic equals
// the request within max(0.001, 1 / cells). Every expected value here is counted from the generated
// material map (cells of material 0: each cell has the same projected area), never read from the
// generator's report; unreachable requests are errors naming the reachable range.
#include <gtest/gtest.h>
#include "support/cli.h"
#include "support/materials.h"
#include "support/scratch.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <utility>

#include "roadbrdf/core/error.h"
#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/height_field.h"

namespace rs = roadbrdf::surface;

namespace {

using roadbrdf::test::lambert;

// Two classes; `scale` multiplies the volume fractions (1: dense, deposition; small: loose, random
// sequential addition leaves much of the plan without any grain).
rs::SampleRecipe recipe(double scale) {
  rs::SampleRecipe r;
  r.name = "two classes";
  r.matrix = lambert(0.05, "mastic");
  rs::GrainClass fine, coarse;
  fine.material = lambert(0.3, "2/4");
  fine.d_min_mm = 2;
  fine.d_max_mm = 4;
  fine.volume_fraction = 0.2 * scale;
  coarse.material = lambert(0.4, "4/6");
  coarse.d_min_mm = 4;
  coarse.d_max_mm = 6;
  coarse.volume_fraction = 0.35 * scale;
  r.classes = {fine, coarse};
  return r;
}

rs::GeneratorSettings settings() {
  rs::GeneratorSettings s;
  s.size_mm = 16.0;
  s.cell_size_mm = 0.2;  // 80 x 80 cells: tolerance max(0.001, 1/6400) = 0.001
  s.seed = 7;
  return s;
}

double counted_mastic_fraction(const rs::HeightField& f) {
  const long mastic = std::count(f.material.begin(), f.material.end(), std::uint16_t{0});
  return static_cast<double>(mastic) / static_cast<double>(f.material.size());
}

double with_level(const rs::SampleRecipe& r, double matrix_level) {
  rs::GeneratorSettings s = settings();
  s.matrix_level = matrix_level;
  return counted_mastic_fraction(rs::generate_sample(r, s).field);
}

std::string error_of(const rs::SampleRecipe& r, const rs::GeneratorSettings& s) {
  try {
    rs::generate_sample(r, s);
  } catch (const roadbrdf::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// The number that follows `key` in `text`.
double number_after(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key);
  if (at == std::string::npos) return std::numeric_limits<double>::quiet_NaN();
  return std::stod(text.substr(at + key.size()));
}

}  // namespace

TEST(SurfaceMasticFraction, FractionCountedOnTheMapIsNonDecreasingInTheLevel) {
  // The monotonicity the bisection relies on (proof in generate.h), checked on the maps themselves.
  const rs::SampleRecipe r = recipe(1.0);
  double previous = -1.0;
  for (double level : {0.0, 0.3, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0}) {
    const double fr = with_level(r, level);
    EXPECT_GE(fr, previous) << "level " << level;
    previous = fr;
  }
}

TEST(SurfaceMasticFraction, AchievedFractionCountedOnTheMapMatchesTheRequest) {
  const rs::SampleRecipe r = recipe(1.0);
  const double tolerance = std::max(0.001, 1.0 / (80.0 * 80.0));
  for (const auto& [target, text] : {std::pair{0.25, "0.25"}, std::pair{0.6, "0.6"}}) {
    rs::GeneratorSettings s = settings();
    s.mastic_fraction = target;
    const rs::GeneratedSample g = rs::generate_sample(r, s);
    ASSERT_EQ(g.field.nx, 80);
    const double counted = counted_mastic_fraction(g.field);
    EXPECT_NEAR(counted, target, tolerance) << "target " << target;
    // The same map as the plain generator at the chosen level (nothing else changes).
    rs::GeneratorSettings plain = settings();
    plain.matrix_level = g.matrix_level_mm / g.slab_thickness_mm;
    const rs::GeneratedSample h = rs::generate_sample(r, plain);
    EXPECT_EQ(h.field.material, g.field.material);
    EXPECT_NEAR(counted_mastic_fraction(h.field), target, tolerance);
    // Recorded in the SURFACE description.
    const std::string& d = g.field.description;
    EXPECT_NE(d.find(std::string("exposed mastic fraction of ") + text + ":"), std::string::npos) << d;
    EXPECT_NEAR(number_after(d, "achieved "), counted, 1e-5) << d;
  }
}

TEST(SurfaceMasticFraction, UnreachableFractionIsAnErrorNamingTheReachableRange) {
  // Loose packing: at the bottom of the slab (level 0) the mastic already shows wherever no grain rises
  // above z = 0, so a smaller fraction cannot be reached.
  const rs::SampleRecipe r = recipe(0.3);
  const double lowest = with_level(r, 0.0), highest = with_level(r, 1.0);
  ASSERT_GT(lowest, 0.1);  // the premise of this test
  rs::GeneratorSettings s = settings();
  s.mastic_fraction = 0.5 * lowest;
  const std::string e = error_of(r, s);
  EXPECT_NE(e.find("not reachable"), std::string::npos) << e;
  EXPECT_NEAR(number_after(e, "reachable with this packing: "), lowest, 1e-5) << e;
  EXPECT_NEAR(number_after(e, "slab) to "), highest, 1e-5) << e;
  // Just inside the range is reachable.
  s.mastic_fraction = std::min(0.99, lowest + 0.05);
  EXPECT_NEAR(counted_mastic_fraction(rs::generate_sample(r, s).field), *s.mastic_fraction, 0.001);
}

TEST(SurfaceMasticFraction, InvalidRequestsAreErrors) {
  const rs::SampleRecipe r = recipe(1.0);
  for (double bad : {0.0, 1.0, -0.2, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
    rs::GeneratorSettings s = settings();
    s.mastic_fraction = bad;
    EXPECT_NE(error_of(r, s).find("must be in (0, 1)"), std::string::npos) << bad;
  }
  rs::GeneratorSettings s = settings();
  s.mastic_fraction = 0.3;
  s.target_mpd_mm = 0.5;
  EXPECT_NE(error_of(r, s).find("exclude each other"), std::string::npos);
}

TEST(SurfaceMasticFraction, CommandLineOptionAndExclusivity) {
  const std::string folder = roadbrdf::test::scratch_path("mastic_fraction_cli");
  std::filesystem::create_directories(folder);
  {
    std::ofstream out(folder + "/mix.json");
    out << R"({
    "format": "roadbrdf-formulation", "version": 1, "name": "M",
    "mastic": {"name": "mastic", "fit": "mastic.fit.json"},
    "components": [
      {"name": "Bitumen", "kind": "binder", "mass_percent": 6, "density_g_cm3": 1.03, "fit": "mastic.fit.json"},
      {"name": "Sand 0/2", "kind": "aggregate", "mass_percent": 34, "density_g_cm3": 2.65, "d_min_mm": 0,
       "d_max_mm": 2, "fit": "mastic.fit.json"},
      {"name": "Gravel 2/4", "kind": "aggregate", "mass_percent": 60, "density_g_cm3": 2.65, "d_min_mm": 2,
       "d_max_mm": 4, "fit": "gravel.fit.json"}
    ]})";
  }
  const std::string base = "surface " + folder + "/mix.json --size 12mm --cell 0.1 --seed 4 ";
  const std::string surface = folder + "/s.json";
  roadbrdf::test::CliResult r = roadbrdf::test::run_cli(base + "--mastic-fraction 0.3 -o " + surface);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("(requested 0.3, tolerance 0.001)"), std::string::npos) << r.output;
  const rs::HeightField f = rs::read_surface(surface);
  EXPECT_NEAR(counted_mastic_fraction(f), 0.3, std::max(0.001, 1.0 / (120.0 * 120.0)));
  EXPECT_NE(f.description.find("chosen for an exposed mastic fraction of 0.3"), std::string::npos) << f.description;
  for (const std::string other : {"--matrix-level 0.5", "--target-mpd 0.5"}) {
    r = roadbrdf::test::run_cli(base + "--mastic-fraction 0.3 " + other + " -o " + surface);
    EXPECT_NE(r.status, 0) << other;
    EXPECT_NE(r.output.find("exclude each other"), std::string::npos) << r.output;
  }
  r = roadbrdf::test::run_cli(base + "--mastic-fraction 1 -o " + surface);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("must be in (0, 1)"), std::string::npos) << r.output;
  std::filesystem::remove_all(folder);
}
