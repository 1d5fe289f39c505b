// The `roadbrdf mix` command: formulation + fit files + measured mixture -> comparison table and
// MIX.json, read back as a spectral model.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>
#include "support/cli.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
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
  j["fits"] = {{{"model", "lambert"},
                {"options", nlohmann::json::object()},
                {"wavelengths", kWavelengths},
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
  const SpectralModel m = read_mix_file(out, "areal");
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
  const SpectralModel fitted = read_mix_file(out, "fitted");
  EXPECT_EQ(fitted.model().name(), "mixture-linear");
  const SpectralModel best = read_mix_file(out);  // the file's "best"
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

// Rows of a CSV file (comment lines skipped), split on ','.
std::vector<std::vector<std::string>> read_csv_rows(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

// The table line of a method in the command's output: its held-out RMSE (second column).
double table_rmse(const std::string& output, const std::string& method) {
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string first;
    double rmse = 0.0;
    if (words >> first && first == method && words >> rmse) return rmse;
  }
  return std::nan("");
}

TEST_F(CliMix, ResidualFileRmseEqualsTheTable) {
  // The mixture of the fixture with a deterministic +-2 % perturbation and sigma = 1 % of the value.
  std::ofstream csv(dir_ / "mixed-sigma.csv");
  csv.precision(17);
  csv << "theta_i,phi_i,theta_r,phi_r";
  for (double w : kWavelengths) csv << ',' << w;
  for (double w : kWavelengths) csv << ",sigma_" << w;
  csv << '\n';
  int index = 0;
  std::vector<std::array<double, 4>> angles;
  for (double ti : {0.0, 30.0, 60.0}) {
    for (double tr : {10.0, 40.0, 70.0}) {
      for (double pr : {0.0, 90.0, 180.0}) {
        angles.push_back({ti, 0.0, tr, pr});
        csv << ti << ",0," << tr << ',' << pr;
        std::vector<double> value;
        for (std::size_t m = 0; m < kWavelengths.size(); ++m) {
          const double rho = 0.1 * kBitumen[m] + 0.3 * kMastic[m] + 0.6 * kGravel[m];
          value.push_back(rho / kPi * (1.0 + 0.02 * std::sin(1.7 * ++index)));
          csv << ',' << value.back();
        }
        for (double v : value) csv << ',' << 0.01 * v;
        csv << '\n';
      }
    }
  }
  csv.close();
  const fs::path out = dir_ / "mix.json", residuals = dir_ / "res.csv";
  const Result r = run("mix " + (dir_ / "F.json").string() + " --data " + (dir_ / "mixed-sigma.csv").string() +
                       " --folds 3 --residuals " + residuals.string() + " -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto rows = read_csv_rows(residuals);
  ASSERT_FALSE(rows.empty());
  const std::vector<std::string> columns = {"method",
                                            "fold",
                                            "theta_i",
                                            "phi_i",
                                            "theta_r",
                                            "phi_r",
                                            "wavelength",
                                            "measured",
                                            "sigma",
                                            "predicted",
                                            "residual",
                                            "relative_residual",
                                            "normalized_residual"};
  ASSERT_EQ(rows[0], columns);
  std::map<std::string, double> sse, chi2;
  std::map<std::string, int> count;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& c = rows[i];
    ASSERT_EQ(c.size(), columns.size()) << i;
    const double measured = std::stod(c[7]), sigma = std::stod(c[8]), predicted = std::stod(c[9]),
                 residual = std::stod(c[10]);
    EXPECT_NEAR(residual, predicted - measured, 1e-15);
    EXPECT_NEAR(std::stod(c[11]), residual / measured, 1e-12);
    EXPECT_NEAR(sigma, 0.01 * measured, 1e-15);
    // Row order: geometry-major inside a method, in the data's order.
    const int row_in_method = count[c[0]]++;
    const auto& a = angles[row_in_method / kWavelengths.size()];
    for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(std::stod(c[2 + k]), a[k]) << i;
    EXPECT_DOUBLE_EQ(std::stod(c[6]), kWavelengths[row_in_method % kWavelengths.size()]);
    const int fold = std::stoi(c[1]);
    if (c[0] == "fitted" || c[0] == "shadowed") {
      EXPECT_TRUE(fold >= 1 && fold <= 3) << fold;
    } else {
      EXPECT_EQ(fold, 0);
    }
    sse[c[0]] += residual * residual;
    chi2[c[0]] += std::pow(std::stod(c[12]), 2);
  }
  std::ifstream in(out);
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(count.size(), j.at("methods").size());
  for (const auto& m : j.at("methods")) {
    const std::string method = m.at("method");
    ASSERT_EQ(count[method], 27 * 4) << method;
    const double rmse = std::sqrt(sse[method] / count[method]);
    EXPECT_NEAR(rmse, m.at("comparison").at("rmse").get<double>(), 1e-12 * rmse) << method;
    EXPECT_NEAR(chi2[method] / count[method], m.at("comparison").at("chi2_reduced").get<double>(),
                1e-9 * chi2[method] / count[method])
        << method;
    // The printed table (5 significant digits).
    EXPECT_NEAR(table_rmse(r.output, method), rmse, 1e-4 * rmse) << method << "\n" << r.output;
  }
  // Without sigma in the data: no sigma columns; --residuals needs --data.
  const Result plain = run("mix " + (dir_ / "F.json").string() + " --data " + (dir_ / "mixed.csv").string() +
                           " --method areal --folds 3 --residuals " + residuals.string() + " -o " + out.string());
  ASSERT_EQ(plain.status, 0) << plain.output;
  const auto plain_rows = read_csv_rows(residuals);
  EXPECT_EQ(plain_rows[0],
            (std::vector<std::string>{"method", "fold", "theta_i", "phi_i", "theta_r", "phi_r", "wavelength",
                                      "measured", "predicted", "residual", "relative_residual"}));
  EXPECT_EQ(plain_rows.size(), 1u + 27 * 4);
  const Result no_data =
      run("mix " + (dir_ / "F.json").string() + " --residuals " + residuals.string() + " -o " + out.string());
  EXPECT_EQ(no_data.status, 2) << no_data.output;
  EXPECT_NE(no_data.output.find("--residuals: needs data"), std::string::npos) << no_data.output;
}

TEST_F(CliMix, NoSigmaSwitchTurnsWeightingOff) {
  // sigma differs by 100x between the first and the other geometries, and the data are a perturbed
  // mixture: weighted and unweighted fitted weights must differ; --no-sigma-weights is recorded in the settings.
  std::ofstream csv(dir_ / "mixed-sigma.csv");
  csv.precision(17);
  csv << "theta_i,phi_i,theta_r,phi_r";
  for (double w : kWavelengths) csv << ',' << w;
  for (double w : kWavelengths) csv << ",sigma_" << w;
  csv << '\n';
  int index = 0;
  for (double ti : {0.0, 30.0, 60.0}) {
    for (double tr : {10.0, 40.0, 70.0}) {
      for (double pr : {0.0, 90.0, 180.0}) {
        csv << ti << ",0," << tr << ',' << pr;
        std::vector<double> value;
        for (std::size_t m = 0; m < kWavelengths.size(); ++m) {
          const double rho = 0.1 * kBitumen[m] + 0.3 * kMastic[m] + 0.6 * kGravel[m];
          value.push_back(rho / kPi * (1.0 + 0.05 * std::sin(2.3 * ++index)));
          csv << ',' << value.back();
        }
        for (double v : value) csv << ',' << (index % 3 ? 0.001 : 0.1) * v;
        csv << '\n';
      }
    }
  }
  csv.close();
  auto fitted_weights = [&](const std::string& extra) {
    const fs::path out = dir_ / "w.json";
    const Result r = run("mix " + (dir_ / "F.json").string() + " --data " + (dir_ / "mixed-sigma.csv").string() +
                         " --method fitted --folds 3 " + extra + " -o " + out.string());
    EXPECT_EQ(r.status, 0) << r.output;
    std::ifstream in(out);
    const nlohmann::json j = nlohmann::json::parse(in);
    const auto& m = j.at("methods").at(0);
    return std::make_pair(m.at("weights").at("gravel").get<double>(),
                          m.at("settings").at("sigma_weighted").get<double>());
  };
  const auto weighted = fitted_weights("");
  const auto plain = fitted_weights("--no-sigma-weights");
  EXPECT_EQ(weighted.second, 1.0);
  EXPECT_EQ(plain.second, 0.0);
  EXPECT_EQ(fitted_weights("--no-sigma"), plain);  // the hidden shorter name of the same flag
  EXPECT_GT(std::fabs(weighted.first - plain.first), 1e-6);
}

}  // namespace

namespace {

// `roadbrdf mix-calibrate` (mixing/calibration.h) and `mix --cross-sections`.
TEST_F(CliMix, CalibrateCrossSectionsAndUseThem) {
  const std::string f = (dir_ / "F.json").string(), data = (dir_ / "mixed.csv").string();
  const std::string cal = (dir_ / "cal.json").string();
  Result r = run("mix-calibrate " + f + " -o " + cal);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("give pairs of a formulation and its measured data (1 file given"), std::string::npos)
      << r.output;
  r = run("mix-calibrate " + f + " " + data + " --reference granite -o " + cal);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--reference: 'granite' is not an end-member"), std::string::npos) << r.output;
  r = run("mix-calibrate " + f + " " + data + " --reference gravel -o " + cal);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("(reference)"), std::string::npos) << r.output;
  nlohmann::json j;
  std::ifstream(cal) >> j;
  EXPECT_EQ(j.at("format"), "roadbrdf-cross-sections");
  EXPECT_EQ(j.at("reference"), "gravel");
  std::map<std::string, double> k;
  for (const auto& e : j.at("end_members")) k[e.at("name")] = e.at("cross_section_factor").get<double>();
  ASSERT_EQ(k.size(), 3u);
  EXPECT_EQ(k.at("gravel"), 1.0);
  // The fit lowers the RMS against the measured mixture (it starts from k = 1).
  EXPECT_LT(j.at("rms_calibrated").get<double>(), j.at("rms_uncalibrated").get<double>());

  const std::string out = (dir_ / "mix.json").string();
  r = run("mix " + f + " --method hapke --cross-sections " + cal + " -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  nlohmann::json m;
  std::ifstream(out) >> m;
  EXPECT_EQ(m.at("methods").at(0).at("settings").at("cross_section_factor.mastic").get<double>(), k.at("mastic"));
  r = run("mix " + f + " --method areal --cross-sections " + cal + " -o " + out);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--cross-sections: only the hapke method"), std::string::npos) << r.output;
  // A calibration without one of the formulation's end-members.
  j["end_members"].erase(1);
  std::ofstream(cal) << j.dump(1);
  r = run("mix " + f + " --method hapke --cross-sections " + cal + " -o " + out);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--cross-sections: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("has no factor for end-member"), std::string::npos) << r.output;
}

}  // namespace
