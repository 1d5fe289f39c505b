// Single- and few-band fits and mixtures are first class: albedo, rtable and eval
// work on a fit or MIX.json with one wavelength (or a few), report the per-wavelength values and omit,
// with a note, the broadband / luminous values that cannot be formed.
// References: Lambert closed forms (every albedo equals rho; q = rho / pi, r = q cos^3 gamma,
// Q0 = rho / pi, S1 = cos^3(atan 2) = 5^-3/2), an areal mixture of Lambert surfaces (sum of w rho),
// and, for the real CUReT sample 45, an independent Gauss-Legendre integral of the fitted model.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/models/registry.h"
#include "support/cli.h"
#include "support/reference_quadrature.h"
#include "support/scratch.h"

namespace {

namespace fs = std::filesystem;
using roadbrdf::test::run_cli;
using roadbrdf::test::run_shell;

constexpr double kPi = 3.14159265358979323846;

const roadbrdf::test::ScratchDirectory& scratch() {
  static const roadbrdf::test::ScratchDirectory dir;
  return dir;
}

std::string path(const std::string& name) { return (scratch().path() / name).string(); }

// A Lambert fit file with albedo rho(lambda) at the given wavelengths.
std::string lambert_fit(const std::string& name, const std::vector<double>& wavelengths,
                        const std::vector<double>& rho) {
  nlohmann::json j;
  j["format"] = "roadbrdf-fit";
  j["version"] = 1;
  j["best"] = "lambert";
  j["fits"] = {{{"model", "lambert"},
                {"options", nlohmann::json::object()},
                {"wavelengths", wavelengths},
                {"parameters", {{"albedo", rho}}}}};
  const std::string p = path(name);
  std::ofstream(p) << j.dump(1);
  return p;
}

// Standard output only (notes go to standard error).
nlohmann::json json_of(const std::string& arguments) {
  const auto r = run_shell(roadbrdf::test::cli_program() + " " + arguments + " 2>/dev/null");
  EXPECT_EQ(r.status, 0) << arguments << "\n" << r.output;
  return nlohmann::json::parse(r.output);
}

// Standard r-table grid: row k has tan(gamma) = kTanGamma[k].
double s1_lambert() { return std::pow(1.0 / std::sqrt(5.0), 3); }

TEST(SingleBand, LambertAlbedoEqualsRhoAndBroadbandIsOmittedWithANote) {
  const std::string fit = lambert_fit("l1.json", {550.0}, {0.3});
  const auto j = json_of("albedo " + fit + " --sun-zenith 0,30,60 --illuminant D65 --json");
  ASSERT_EQ(j["wavelengths"].size(), 1u);
  for (int z = 0; z < 3; ++z) EXPECT_NEAR(j["black_sky"][z][0].get<double>(), 0.3, 1e-9);
  EXPECT_NEAR(j["white_sky"][0].get<double>(), 0.3, 1e-9);
  EXPECT_TRUE(j["broadband"].is_null());
  EXPECT_TRUE(j["luminous"].is_null());
  const std::string notes = j["notes"].dump();
  EXPECT_NE(notes.find("broadband (solar-weighted) values need at least two wavelengths"), std::string::npos) << notes;
  EXPECT_NE(notes.find("luminous"), std::string::npos) << notes;
  // The table says the same in one comment line and has no broadband lines.
  const auto table = run_cli("albedo " + fit);
  ASSERT_EQ(table.status, 0) << table.output;
  EXPECT_NE(table.output.find("# single-band fit (550 nm)"), std::string::npos) << table.output;
  EXPECT_EQ(table.output.find("# broadband"), std::string::npos) << table.output;
  EXPECT_NE(table.output.find("550,0.30000000"), std::string::npos) << table.output;
}

TEST(SingleBand, RTableUsesTheBandWithoutAskingAndMatchesLambertClosedForms) {
  const double rho = 0.3;
  const std::string fit = lambert_fit("l1r.json", {550.0}, {rho});
  const auto j = json_of("rtable " + fit + " --json");
  EXPECT_EQ(j["weighting"]["wavelength_nm"].get<double>(), 550.0);
  EXPECT_NE(j["weighting"]["note"].get<std::string>().find("single-band"), std::string::npos);
  EXPECT_NEAR(j["Q0"].get<double>(), rho / kPi, 1e-9);
  EXPECT_NEAR(j["S1"].get<double>(), s1_lambert(), 1e-9);
  const auto tan_gamma = j["tan_gamma"].get<std::vector<double>>();
  for (std::size_t i = 0; i < tan_gamma.size(); ++i) {
    const double cos_gamma = 1.0 / std::sqrt(1.0 + tan_gamma[i] * tan_gamma[i]);
    EXPECT_NEAR(j["r"][i][0].get<double>(), rho / kPi * std::pow(cos_gamma, 3), 1e-12) << i;
  }
  // The same table as asking for the band explicitly; the note goes to standard error.
  const auto explicit_band = json_of("rtable " + fit + " --wavelength 550 --json");
  EXPECT_EQ(explicit_band["r"], j["r"]);
  const auto text = run_cli("rtable " + fit);
  EXPECT_EQ(text.status, 0) << text.output;
  EXPECT_NE(text.output.find("roadbrdf: note: single-band model (550 nm)"), std::string::npos) << text.output;
}

TEST(SingleBand, EvalAcceptsFitFiles) {
  const std::string one = lambert_fit("l1e.json", {550.0}, {0.3});
  const auto r = run_cli("eval " + one + " --theta-i 30 --phi-i 0 --theta-r 20 --phi-r 180");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NEAR(std::stod(r.output), 0.3 / kPi, 1e-9);
  const std::string few = lambert_fit("l3e.json", {450.0, 550.0, 650.0}, {0.2, 0.3, 0.4});
  const auto ask = run_cli("eval " + few + " --theta-i 30 --phi-i 0 --theta-r 20 --phi-r 180");
  EXPECT_NE(ask.status, 0);
  EXPECT_NE(ask.output.find("choose one with --wavelength"), std::string::npos) << ask.output;
  const auto at = run_cli("eval " + few + " --wavelength 650 --theta-i 30 --phi-i 0 --theta-r 20 --phi-r 180");
  ASSERT_EQ(at.status, 0) << at.output;
  EXPECT_NEAR(std::stod(at.output), 0.4 / kPi, 1e-9);
  const auto model = run_cli("eval lambert -p albedo=0.5 --wavelength 500 --theta-i 0 --phi-i 0 --theta-r 0 --phi-r 0");
  EXPECT_NE(model.status, 0);
  EXPECT_NE(model.output.find("--wavelength: needs a fit file"), std::string::npos) << model.output;
}

TEST(FewBand, PerWavelengthValuesAndNotesForWhatCannotBeFormed) {
  const std::vector<double> rho = {0.2, 0.3, 0.4};
  const std::string fit = lambert_fit("l3.json", {450.0, 550.0, 650.0}, rho);
  const auto j = json_of("albedo " + fit + " --illuminant A --json");
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(j["white_sky"][k].get<double>(), rho[k], 1e-9);
    EXPECT_NEAR(j["black_sky"][0][k].get<double>(), rho[k], 1e-9);
  }
  // 450-650 nm hold well under half the solar energy: the broadband value is formed but flagged;
  // V(lambda) x A is not covered to 99%: the luminous value is omitted with a note.
  ASSERT_FALSE(j["broadband"].is_null());
  EXPECT_GT(j["broadband"]["solar_fraction_outside_range"].get<double>(), 0.5);
  EXPECT_TRUE(j["luminous"].is_null());
  // The partial solar spectrum is a typed warning; the omitted luminous value a note.
  const std::string warnings = j["warnings"].dump();
  EXPECT_NE(warnings.find("partial_solar_spectrum"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("of the solar energy"), std::string::npos) << warnings;
  const std::string notes = j["notes"].dump();
  EXPECT_NE(notes.find("luminous values are omitted"), std::string::npos) << notes;
  // r-table: photometric weighting is impossible; the error says which options to use.
  const auto r = run_cli("rtable " + fit);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--wavelength NM"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("450, 550, 650"), std::string::npos) << r.output;
  const auto at = json_of("rtable " + fit + " --wavelength 450 --json");
  EXPECT_NEAR(at["Q0"].get<double>(), 0.2 / kPi, 1e-9);
}

TEST(SingleBand, MixtureOfSingleBandFits) {
  // An areal mixture of three single-band Lambert end-members is Lambertian with sum(w rho).
  const std::vector<double> rho = {0.05, 0.15, 0.45};
  fs::create_directories(scratch().path() / "mixfits");
  lambert_fit("mixfits/a.json", {550.0}, {rho[0]});
  lambert_fit("mixfits/b.json", {550.0}, {rho[1]});
  lambert_fit("mixfits/c.json", {550.0}, {rho[2]});
  std::ofstream(path("F.json")) << R"({ "format": "roadbrdf-formulation", "version": 1, "name": "T",
      "mastic": { "fit": "mixfits/b.json" },
      "components": [
        { "name": "Bitumen", "kind": "binder", "mass_percent": 5, "density_g_cm3": 1.03, "fit": "mixfits/a.json" },
        { "name": "Sand 0/2", "kind": "aggregate", "mass_percent": 40, "density_g_cm3": 2.65, "d_min_mm": 0,
          "d_max_mm": 2, "fit": "mixfits/b.json" },
        { "name": "Gravel 6/10", "kind": "aggregate", "mass_percent": 55, "density_g_cm3": 2.7, "d_min_mm": 6,
          "d_max_mm": 10, "fit": "mixfits/c.json" } ] })";
  const std::string mix = path("MIX.json");
  const auto made = run_cli("mix " + path("F.json") + " --method areal -o " + mix);
  ASSERT_EQ(made.status, 0) << made.output;
  nlohmann::json file;
  std::ifstream(mix) >> file;
  const auto& weights = file["methods"][0]["weights"];
  const double expected =
      weights["a"].get<double>() * rho[0] + weights["b"].get<double>() * rho[1] + weights["c"].get<double>() * rho[2];
  const auto e = run_cli("eval " + mix + " --theta-i 30 --phi-i 0 --theta-r 20 --phi-r 180");
  ASSERT_EQ(e.status, 0) << e.output;
  EXPECT_NEAR(std::stod(e.output), expected / kPi, 1e-9);
  const auto a = json_of("albedo " + mix + " --json");
  EXPECT_NEAR(a["white_sky"][0].get<double>(), expected, 1e-9);
  EXPECT_TRUE(a["broadband"].is_null());
  const auto t = json_of("rtable " + mix + " --json");
  EXPECT_NEAR(t["Q0"].get<double>(), expected / kPi, 1e-9);
}

// The chain a new user runs on the real CUReT concrete (sample 45, one grey band at a nominal
// 550 nm): convert -> fit -> albedo -> rtable, with the white-sky albedo checked against an
// independent integral of the fitted model.
TEST(SingleBand, CuretSample45Chain) {
  const std::string curet = roadbrdf::data_directory() + "/third-party/curet/abrdf.dat";
  if (!fs::exists(curet)) GTEST_SKIP() << "CUReT data not found at " << curet;
  const std::string data = path("curet45.csv"), fit = path("curet45.fit.json");
  ASSERT_EQ(run_cli("convert " + curet + " --from curet --sample 45 -o " + data).status, 0);
  const auto fitted = run_cli("fit " + data + " -m oren-nayar -o " + fit);
  ASSERT_EQ(fitted.status, 0) << fitted.output;
  const auto albedo = json_of("albedo " + fit + " --json");
  EXPECT_TRUE(albedo["broadband"].is_null());
  const double white_sky = albedo["white_sky"][0].get<double>();

  // Independent white-sky albedo: (1/pi) int int f cos(ti) cos(tr) dw_i dw_r with the fitted
  // parameters, by a product Gauss-Legendre rule in cos(theta) and phi (isotropic: phi_i = 0, x 2 pi).
  nlohmann::json file;
  std::ifstream(fit) >> file;
  const auto& best = file["fits"][0];
  const auto model = roadbrdf::make_model(best["model"].get<std::string>(), {});
  std::vector<double> p;
  for (const auto& parameter : model->description().parameters) {
    p.push_back(best["parameters"][parameter.name][0].get<double>());
  }
  std::vector<double> x, w;
  roadbrdf::test::gauss_legendre_01(48, x, w);
  double sum = 0.0;
  for (std::size_t a = 0; a < x.size(); ++a) {
    for (std::size_t b = 0; b < x.size(); ++b) {
      for (std::size_t c = 0; c < x.size(); ++c) {
        const double mu_i = x[a], mu_r = x[b], phi = 2.0 * kPi * x[c];
        const roadbrdf::Geometry g = roadbrdf::geometry_from_degrees(std::acos(mu_i) * 180.0 / kPi, 0.0,
                                                                     std::acos(mu_r) * 180.0 / kPi, phi * 180.0 / kPi);
        // dw = d(mu) d(phi): the integral over phi_i gives 2 pi, over phi_r the rule's 2 pi.
        sum += w[a] * w[b] * w[c] * 2.0 * kPi * model->evaluate(p.data(), g) * mu_i * mu_r * 2.0 * kPi;
      }
    }
  }
  EXPECT_NEAR(white_sky, sum / kPi, 2e-4);

  const auto table = json_of("rtable " + fit + " --json");
  EXPECT_EQ(table["weighting"]["wavelength_nm"].get<double>(), 550.0);
  EXPECT_GT(table["Q0"].get<double>(), 0.0);
  // Coverage (docs/data.md): CUReT's largest viewing and incidence zeniths are 1.46402 rad =
  // 83.882 deg and 1.374447 rad = 78.750 deg (data/third-party/curet/table.txt, rows 126 and 1), so
  // every r-table cell (observer at theta_r = 89 deg, beyond 83.882 + 5) is extrapolated.
  const auto& coverage = table["coverage"];
  EXPECT_NEAR(coverage["fit"]["theta_r_deg"][1].get<double>(), 1.46402 * 180.0 / kPi, 1e-4);
  EXPECT_NEAR(coverage["fit"]["theta_i_deg"][1].get<double>(), 1.374447 * 180.0 / kPi, 1e-4);
  EXPECT_EQ(coverage["cells_outside"].get<std::size_t>(), coverage["cells"].get<std::size_t>());
}

}  // namespace
