// The `roadbrdf mix` command: formulation + fit files + measured mixture -> comparison table and
// MIX.json, read back as a spectral model.
#include "support/cli.h"
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/mixing/mix_file.h"

namespace {

namespace fs = std::filesystem;
using namespace roadbrdf;

using Result = roadbrdf::test::CliResult;
Result run(const std::string& arguments) { return roadbrdf::test::run_cli(arguments); }

const std::vector<double> kWavelengths = {400, 500, 600, 700};
// Albedo spectra of the three end-members (linearly independent over the four wavelengths, so that
// Lambertian end-members are identifiable from the spectra alone).
const std::vector<double> kBitumen = {0.05, 0.06, 0.05, 0.07};
const std::vector<double> kMastic = {0.10, 0.15, 0.12, 0.11};
const std::vector<double> kGravel = {0.40, 0.35, 0.50, 0.45};

// Lambertian fit file with the given albedo at each of kWavelengths.
void write_lambert_fit(const fs::path& path, const std::vector<double>& albedo) {
  nlohmann::json j;
  j["format"] = "roadbrdf-fit";
  j["version"] = 1;
  j["best"] = "lambert";
  j["fits"] = {{{"model", "lambert"}, {"options", nlohmann::json::object()}, {"wavelengths", kWavelengths},
                {"parameters", {{"albedo", albedo}}}}};
  std::ofstream(path) << j.dump(1);
}

class CliMix : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("roadbrdf_cli_mix_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "fits");
    write_lambert_fit(dir_ / "fits" / "bitumen.fit.json", kBitumen);
    write_lambert_fit(dir_ / "fits" / "mastic.fit.json", kMastic);
    write_lambert_fit(dir_ / "fits" / "gravel.fit.json", kGravel);
    std::ofstream(dir_ / "F.json") << R"({ "format": "roadbrdf-formulation", "version": 1, "name": "T",
      "mastic": { "fit": "fits/mastic.fit.json" },
      "components": [
        { "name": "Bitumen", "kind": "binder", "mass_percent": 5, "density_g_cm3": 1.03, "fit": "fits/bitumen.fit.json" },
        { "name": "Sand 0/2", "kind": "aggregate", "mass_percent": 40, "density_g_cm3": 2.65, "d_min_mm": 0,
          "d_max_mm": 2, "fit": "fits/mastic.fit.json" },
        { "name": "Gravel 6/10", "kind": "aggregate", "mass_percent": 55, "density_g_cm3": 2.7, "d_min_mm": 6,
          "d_max_mm": 10, "fit": "fits/gravel.fit.json" } ] })";
    // Measured mixture: 0.1 bitumen + 0.3 mastic + 0.6 gravel, all Lambertian.
    std::ofstream csv(dir_ / "mixed.csv");
    csv.precision(17);
    csv << "# sample: test mixture\ntheta_i,phi_i,theta_r,phi_r";
    for (double w : kWavelengths) csv << ',' << w;
    csv << '\n';
    for (double ti : {0.0, 30.0, 60.0}) {
      for (double tr : {10.0, 40.0, 70.0}) {
        for (double pr : {0.0, 90.0, 180.0}) {
          csv << ti << ",0," << tr << ',' << pr;
          for (std::size_t m = 0; m < kWavelengths.size(); ++m) {
            const double rho = 0.1 * kBitumen[m] + 0.3 * kMastic[m] + 0.6 * kGravel[m];
            csv << ',' << rho / kPi;
          }
          csv << '\n';
        }
      }
    }
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(CliMix, PredictionWithoutData) {
  const std::string out = (dir_ / "mix.json").string();
  const Result r = run("mix " + (dir_ / "F.json").string() + " -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("areal"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("skipped"), std::string::npos) << r.output;  // fitted/shadowed need --data
  const SpectralModel m = mixing::read_mix_file(out, "areal");
  // Lambertian end-members: the areal mixture is Lambertian with the mixed albedo.
  const std::vector<double> p = m.parameters_at(550.0);
  const Geometry g = geometry_from_degrees(20, 0, 50, 120);
  double expected = 0.0;
  // 550 nm: halfway between the tabulated 500 and 600 nm values.
  const double rho[3] = {0.5 * (kBitumen[1] + kBitumen[2]), 0.5 * (kMastic[1] + kMastic[2]),
                         0.5 * (kGravel[1] + kGravel[2])};
  for (int k = 0; k < 3; ++k) expected += p[k] * rho[k] / kPi;
  EXPECT_NEAR(m.model().evaluate(p.data(), g), expected, 1e-12);
  EXPECT_NEAR(p[0] + p[1] + p[2], 1.0, 1e-12);
}

TEST_F(CliMix, ComparisonWithData) {
  const std::string out = (dir_ / "mix.json").string();
  const Result r =
      run("mix " + (dir_ / "F.json").string() + " --data " + (dir_ / "mixed.csv").string() + " --folds 3 -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  // The data are an exact linear mixture: "fitted" reproduces it, and so does "shadowed" (with s = 0).
  EXPECT_NE(r.output.find("best method for T: "), std::string::npos) << r.output;
  std::ifstream in(out);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("format"), "roadbrdf-mix");
  EXPECT_TRUE(j.at("best") == "fitted" || j.at("best") == "shadowed") << j.at("best");
  bool found = false;
  for (const auto& m : j.at("methods")) {
    if (m.at("method") != "fitted") continue;
    found = true;
    EXPECT_NEAR(m.at("weights").at("bitumen").get<double>(), 0.1, 1e-8);
    EXPECT_NEAR(m.at("weights").at("mastic").get<double>(), 0.3, 1e-8);
    EXPECT_NEAR(m.at("weights").at("gravel").get<double>(), 0.6, 1e-8);
    EXPECT_LT(m.at("comparison").at("relative_rmse").get<double>(), 1e-8);
  }
  EXPECT_TRUE(found);
  const SpectralModel fitted = mixing::read_mix_file(out, "fitted");
  EXPECT_EQ(fitted.model().name(), "mixture-linear");
  const SpectralModel best = mixing::read_mix_file(out);  // the file's "best"
  const std::vector<double> p = best.parameters_at(600.0);
  const double expected = (0.1 * kBitumen[2] + 0.3 * kMastic[2] + 0.6 * kGravel[2]) / kPi;
  EXPECT_NEAR(best.model().evaluate(p.data(), geometry_from_degrees(35, 0, 25, 60)), expected, 1e-6 * expected);
}

TEST_F(CliMix, FormulationErrorsAreReported) {
  std::ofstream(dir_ / "bad.json") << R"({ "format": "roadbrdf-formulation", "version": 1, "name": "B",
      "components": [ { "name": "Bitumen", "kind": "binder", "mass_percent": 90, "density_g_cm3": 1.03,
                        "fit": "fits/bitumen.fit.json" } ] })";
  const Result r = run("mix " + (dir_ / "bad.json").string() + " -o " + (dir_ / "o.json").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("bad.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("100 %"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "o.json"));
}

}  // namespace
