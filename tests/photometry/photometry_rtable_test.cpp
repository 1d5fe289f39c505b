// Tests of r-tables, Q0/S1/S2/Qd, classes, r-table files (photometry/rtable.h, rtable_io.h).
// References (independent of the code under test):
//  - closed forms: Lambertian surface of albedo rho has q = rho/pi everywhere, r = (rho/pi) cos^3(gamma),
//    S1 = cos^3(atan 2) = 5^-1.5, Q0 = Qd = rho/pi, S2 = 1; solid-angle averages of cos(gamma),
//    cos^2(gamma) and 1/cos(gamma) over gamma <= atan 12 in closed form;
//  - published S1 of the CIE standard tables (R1 0.25, R2 0.58, R3 1.11, R4 1.55, C1 0.24, C2 0.97) and
//    the nominal Q0 of their classes (0.10, 0.07, 0.07, 0.08, 0.10, 0.07), van Bommel Table 12.2;
//  - road-angle definitions (theta_r = 90 - alpha, dphi = 180 - beta).
#include <gtest/gtest.h>
#include "support/scratch.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/models/spectral_model.h"
#include "roadbrdf/photometry/rtable.h"
#include "roadbrdf/photometry/rtable_io.h"
#include "support/paths.h"

namespace roadbrdf::photometry {
namespace {

std::filesystem::path temp_path(const std::string& name) {
  return std::filesystem::path(roadbrdf::test::scratch_path("photometry_rtable_" + name));
}

std::string temp_file(const std::string& name, const std::string& content) {
  const auto path = temp_path(name);
  std::ofstream(path) << content;
  return path.string();
}

RTable lambert_table(double rho) {
  auto model = make_model("lambert");
  return compute_rtable(*model, {rho});
}

RTable table_of(double (*q)(double gamma, double beta)) {
  RTable t;
  for (std::size_t i = 0; i < kRows; ++i) {
    const double g = std::atan(standard_tan_gamma()[i]);
    for (std::size_t j = 0; j < kColumns; ++j) {
      t.at(i, j) = 1e4 * q(g, deg_to_rad(standard_beta_deg()[j])) * std::pow(std::cos(g), 3);
    }
  }
  return t;
}

TEST(RTableGrid, StandardGrid) {
  EXPECT_EQ(standard_beta_deg().front(), 0.0);
  EXPECT_EQ(standard_beta_deg()[10], 45.0);
  EXPECT_EQ(standard_beta_deg().back(), 180.0);
  EXPECT_EQ(standard_tan_gamma()[8], 2.0);
  EXPECT_EQ(standard_tan_gamma()[9], 2.5);
  EXPECT_EQ(standard_tan_gamma().back(), 12.0);
  std::size_t cells = 0;
  for (std::size_t n : standard_region_columns()) cells += n;
  EXPECT_EQ(cells, 396u);
}

TEST(RTableGrid, GeometriesFollowTheRoadAngles) {
  const auto g = rtable_geometries(1.0);
  ASSERT_EQ(g.size(), 580u);
  // row tan(gamma) = 1 (index 4), beta = 0 (forward side)
  const Geometry& a = g[4 * kColumns + 0];
  EXPECT_NEAR(rad_to_deg(a.theta_i), 45.0, 1e-12);
  EXPECT_NEAR(rad_to_deg(a.theta_r), 89.0, 1e-12);
  EXPECT_NEAR(a.cos_delta_phi, -1.0, 1e-12);  // dphi = 180 deg: forward
  // beta = 180: source behind the observer, retro side (dphi = 0)
  const Geometry& b = g[4 * kColumns + 19];
  EXPECT_NEAR(b.cos_delta_phi, 1.0, 1e-12);
  // beta = 90
  EXPECT_NEAR(g[4 * kColumns + 13].cos_delta_phi, 0.0, 1e-12);
  const auto g5 = rtable_geometries(5.0);
  EXPECT_NEAR(rad_to_deg(g5[0].theta_r), 85.0, 1e-12);
  EXPECT_THROW(rtable_geometries(0.0), InputError);
  EXPECT_THROW(rtable_geometries(90.0), InputError);
}

TEST(RTableLambert, ClosedForms) {
  const double rho = 0.3;
  const RTable t = lambert_table(rho);
  EXPECT_EQ(t.defined_count(), 580u);
  for (std::size_t i = 0; i < kRows; ++i) {
    const double cos3 = std::pow(std::cos(std::atan(standard_tan_gamma()[i])), 3);
    for (std::size_t j = 0; j < kColumns; ++j) {
      EXPECT_NEAR(t.r(i, j), rho / kPi * cos3, 1e-15) << i << "," << j;
      EXPECT_NEAR(t.q(i, j), rho / kPi, 1e-15);
    }
  }
  // The Q0 rule uses the same weights above and below the fraction: exact for constant q.
  EXPECT_NEAR(q0(t), rho / kPi, 1e-15);
  EXPECT_NEAR(q0(t, Q0Region::table), rho / kPi, 1e-15);
  EXPECT_NEAR(qd(t), rho / kPi, 1e-15);
  EXPECT_NEAR(s1(t), std::pow(std::cos(std::atan(2.0)), 3), 1e-14);
  EXPECT_NEAR(s1(t), std::pow(5.0, -1.5), 1e-14);
  EXPECT_NEAR(s2(t), 1.0, 1e-13);
  const RTableSummary s = summarize(t);
  EXPECT_EQ(s.r_class.name, "R1");  // S1 = 0.089 < 0.42
  EXPECT_EQ(s.defined_cells, 580u);
}

TEST(RTableQ0, IntegrationAccuracyAgainstClosedForms) {
  // Full table (every cell), Q0 over all of it = solid-angle average over gamma <= atan 12, beta in [0, pi].
  const double gm = std::atan(12.0);
  const double omega = 1.0 - std::cos(gm);  // per unit beta
  // q = cos(gamma): int cos sin / int sin
  const double ref_cos = 0.5 * std::pow(std::sin(gm), 2) / omega;
  // q = cos^2(gamma)
  const double ref_cos2 = (1.0 - std::pow(std::cos(gm), 3)) / 3.0 / omega;
  // q = 1 / cos(gamma)
  const double ref_sec = -std::log(std::cos(gm)) / omega;
  // q = 1 + cos(beta): average 1
  const double tol = 0.012;  // stated accuracy of the trapezoid rule on the standard grid (docs/photometry.md)
  EXPECT_NEAR(q0(table_of([](double g, double) { return std::cos(g); }), Q0Region::table) / ref_cos, 1.0, tol);
  EXPECT_NEAR(q0(table_of([](double g, double) { return std::pow(std::cos(g), 2); }), Q0Region::table) / ref_cos2, 1.0,
              tol);
  EXPECT_NEAR(q0(table_of([](double g, double) { return 1.0 / std::cos(g); }), Q0Region::table) / ref_sec, 1.0, tol);
  EXPECT_NEAR(q0(table_of([](double, double b) { return 1.0 + std::cos(b); }), Q0Region::table), 1.0, 0.005);
  // Qd of q = cos(gamma): int cos^2 sin / int cos sin over the hemisphere = 2/3.
  EXPECT_NEAR(qd(table_of([](double g, double) { return std::cos(g); })) / (2.0 / 3.0), 1.0, 0.005);
}

// ---- the CIE standard tables ----------------------------------------------------------------

struct Standard {
  const char* file;
  double s1;
  double q0;
  const char* name;
  ClassSystem system;
};
const Standard kStandards[] = {
    {"r1-table.dat", 0.25, 0.10, "R1", ClassSystem::R}, {"r2-table.dat", 0.58, 0.07, "R2", ClassSystem::R},
    {"r3-table.dat", 1.11, 0.07, "R3", ClassSystem::R}, {"r4-table.dat", 1.55, 0.08, "R4", ClassSystem::R},
    {"c1-table.dat", 0.24, 0.10, "C1", ClassSystem::C}, {"c2-table.dat", 0.97, 0.07, "C2", ClassSystem::C},
};

RTable standard(const std::string& file) { return read_rtable(data_file("third-party/rtables/" + file)).table; }

TEST(RTableStandard, PublishedS1ClassAndQ0) {
  for (const Standard& s : kStandards) {
    SCOPED_TRACE(s.file);
    const RTable t = standard(s.file);
    EXPECT_NEAR(t.alpha_deg, 1.0, 1e-12);
    const double v = s1(t);
    EXPECT_NEAR(std::round(v * 100.0) / 100.0, s.s1, 1e-9) << v;
    const RoadClass c = classify(v, s.system);
    EXPECT_EQ(c.name, s.name);
    EXPECT_DOUBLE_EQ(c.standard_q0, s.q0);
    // Q0 over the standard region reproduces the nominal Q0 of the class to its 2 published decimals.
    const double q = q0(t);
    EXPECT_NEAR(std::round(q * 100.0) / 100.0, s.q0, 1e-9) << q;
  }
}

TEST(RTableStandard, ZeroCellsAreMissing) {
  const RTable t = standard("r3-table.dat");
  EXPECT_EQ(t.defined_count(), 396u);
  for (std::size_t i = 0; i < kRows; ++i) {
    for (std::size_t j = 0; j < kColumns; ++j) EXPECT_EQ(t.defined(i, j), in_standard_region(i, j)) << i << "," << j;
  }
  EXPECT_FALSE(t.defined(28, 19));
  EXPECT_TRUE(std::isnan(t.r(28, 19)));
  EXPECT_DOUBLE_EQ(t.at(0, 0), 294.0);
  EXPECT_DOUBLE_EQ(t.r(0, 0), 0.0294);
  // Reading the zeros as zero reflectance would give R3 a Q0 of 0.064 (not 0.07): they must be skipped.
  RTable zeros = t;
  for (double& x : zeros.scaled) {
    if (std::isnan(x)) x = 0.0;
  }
  EXPECT_LT(q0(zeros, Q0Region::table), 0.065);
  EXPECT_NEAR(q0(t, Q0Region::table), q0(t), 1e-15);  // only standard-region cells are defined
}

TEST(RTableStandard, CsvZerosAndEmptyCellsAreMissing) {
  std::ostringstream csv;
  csv << "# test\n";
  for (std::size_t i = 0; i < kRows; ++i) {
    for (std::size_t j = 0; j < kColumns; ++j) {
      if (j) csv << ',';
      if (i == 3 && j == 4) continue;  // empty cell
      csv << ((i == 5 && j == 7) ? 0.0 : 100.0 + static_cast<double>(i));
    }
    csv << '\n';
  }
  const std::string path = temp_file("bare.csv", csv.str());
  const RTable t = read_rtable(path).table;
  EXPECT_EQ(t.defined_count(), 578u);
  EXPECT_FALSE(t.defined(3, 4));
  EXPECT_FALSE(t.defined(5, 7));
  EXPECT_DOUBLE_EQ(t.at(2, 2), 102.0);
  std::filesystem::remove(path);
}

// ---- round trips -----------------------------------------------------------------------------

void expect_identical(const RTable& a, const RTable& b) {
  EXPECT_EQ(a.alpha_deg, b.alpha_deg);
  for (std::size_t k = 0; k < a.scaled.size(); ++k) {
    if (std::isnan(a.scaled[k])) {
      EXPECT_TRUE(std::isnan(b.scaled[k])) << k;
    } else {
      EXPECT_EQ(a.scaled[k], b.scaled[k]) << k;  // bit for bit
    }
  }
}

TEST(RTableFiles, RoundTripInEveryFormat) {
  auto model = make_model("oren-nayar");
  const std::vector<double> p = parameters_from_assignments(model->description(), {{"albedo", 0.37}, {"sigma", 0.41}});
  RTable computed = compute_rtable(*model, p, 1.0);
  computed.name = "oren-nayar test";
  const RTable r3 = standard("r3-table.dat");
  for (RTableFormat f : {RTableFormat::csv, RTableFormat::rtb, RTableFormat::radiance}) {
    SCOPED_TRACE(name_of(f));
    for (const RTable* t : {static_cast<const RTable*>(&computed), &r3}) {
      const std::string ext = f == RTableFormat::csv ? ".csv" : f == RTableFormat::rtb ? ".rtb" : ".dat";
      const std::string path = temp_path(std::string("roundtrip") + ext).string();
      write_rtable_file(path, *t, f);
      const RTableFile back = read_rtable(path);
      EXPECT_EQ(back.format, f);
      expect_identical(*t, back.table);
      EXPECT_EQ(q0(back.table), q0(*t));
      EXPECT_EQ(s1(back.table), s1(*t));
      if (f == RTableFormat::rtb) {
        ASSERT_TRUE(back.declared_q0.has_value());
        EXPECT_EQ(*back.declared_q0, q0(*t));
      }
      if (f != RTableFormat::radiance) {
        EXPECT_EQ(back.table.name, t->name);
      }
      std::filesystem::remove(path);
    }
  }
}

TEST(RTableFiles, OtherAlphaRoundTripsThroughRadiance) {
  const RTable t = compute_rtable(*make_model("oren-nayar"), {0.2, 0.5}, 3.0);
  const std::string path = temp_path("alpha3.dat").string();
  write_rtable_file(path, t, RTableFormat::radiance);
  EXPECT_THROW(read_rtable(path), FileError);  // no 1 deg slice
  expect_identical(t, read_rtable(path, std::nullopt, 3.0).table);
  std::filesystem::remove(path);
}

TEST(RTableFiles, ScaleOption) {
  // A table of plain r values read with scale 1.
  std::ostringstream csv;
  for (std::size_t i = 0; i < kRows; ++i) {
    for (std::size_t j = 0; j < kColumns; ++j) csv << (j ? "," : "") << 0.05;
    csv << '\n';
  }
  const std::string path = temp_file("plain.csv", csv.str());
  const RTable t = read_rtable(path, std::nullopt, 1.0, 1.0).table;
  EXPECT_DOUBLE_EQ(t.r(7, 7), 0.05);
  std::filesystem::remove(path);
}

TEST(RTableFiles, ErrorsNameLineAndColumn) {
  // Wrong beta in the CSV header.
  std::ostringstream header;
  header << "# c\ntan_gamma";
  for (std::size_t j = 0; j < kColumns; ++j) header << ',' << (j == 3 ? 11.0 : standard_beta_deg()[j]);
  header << '\n';
  const std::string path = temp_file("badheader.csv", header.str());
  try {
    read_rtable(path);
    FAIL();
  } catch (const FileError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_GT(e.column(), 10);
  }
  // Radiance: a non-number among the values.
  std::ostringstream out;
  write_rtable(out, lambert_table(0.2), RTableFormat::radiance);
  std::string text = out.str();
  const auto pos = text.rfind(' ');
  ASSERT_NE(pos, std::string::npos);
  text[pos + 1] = 'x';  // the value after the last space: a single-character "0"
  const std::string bad = temp_file("bad.dat", text);
  try {
    read_rtable(bad);
    FAIL();
  } catch (const FileError& e) {
    EXPECT_GT(e.line(), 60);
    EXPECT_GT(e.column(), 1);
  }
  // RTB: wrong magic, truncated.
  const std::string rtb = temp_file("bad.rtb", "RTable.v2\nx\n");
  EXPECT_THROW(read_rtable(rtb), FileError);
  const std::string rtb2 = temp_file("short.rtb", "RTable.v1\nname with spaces\n29\n0\n0.25\n");
  EXPECT_THROW(read_rtable(rtb2), FileError);
  EXPECT_THROW(read_rtable(temp_file("x.txt", "1")), InputError);  // unknown extension
  for (const auto& p : {path, bad, rtb, rtb2}) std::filesystem::remove(p);
}

// ---- spectral weighting ------------------------------------------------------------------------

std::shared_ptr<const Model> shared(const std::string& name) { return std::shared_ptr<const Model>(make_model(name)); }

TEST(RTableSpectral, FlatSpectrumEqualsTheBrdf) {
  auto model = shared("oren-nayar");
  const std::vector<double> p = {0.4, 0.3};
  const RTable plain = compute_rtable(*model, p);
  std::vector<double> wl, table;
  for (double l = 360.0; l <= 830.0; l += 10.0) {
    wl.push_back(l);
    table.insert(table.end(), p.begin(), p.end());
  }
  const SpectralModel flat(model, wl, table);
  for (const char* ill : {"A", "D65"}) {
    SpectralWeighting w;
    w.illuminant = illuminant_from_name(ill);
    const RTable weighted = compute_rtable(flat, w);
    for (std::size_t k = 0; k < plain.scaled.size(); ++k) {
      EXPECT_NEAR(weighted.scaled[k] / plain.scaled[k], 1.0, 1e-12) << ill << " " << k;
    }
  }
}

TEST(RTableSpectral, WavelengthAndBand) {
  // Lambertian albedo linear in wavelength between tabulated points (SpectralModel interpolates linearly):
  // rho(l) = 0.1 + 0.001 (l - 400) on 400..700 nm.
  auto model = shared("lambert");
  const SpectralModel m(model, {400.0, 700.0}, {0.1, 0.4});
  SpectralWeighting w;
  w.kind = SpectralWeighting::Kind::wavelength;
  w.wavelength_nm = 550.0;
  EXPECT_NEAR(q0(compute_rtable(m, w)), 0.25 / kPi, 1e-14);
  w.kind = SpectralWeighting::Kind::band;
  w.band_lo_nm = 450.5;
  w.band_hi_nm = 620.0;  // mean of a linear function = value at the centre, 535.25 nm
  EXPECT_NEAR(q0(compute_rtable(m, w)), (0.1 + 0.001 * (535.25 - 400.0)) / kPi, 1e-13);
  w.band_hi_nm = 720.0;  // outside the model's range
  EXPECT_THROW(compute_rtable(m, w), InputError);
  // Photometric weighting of a 400-700 nm fit covers > 99% of the luminous integral: accepted; the
  // result lies between the albedos at the ends and, V peaking at 555 nm, near rho(555).
  SpectralWeighting ph;
  const double q = q0(compute_rtable(m, ph)) * kPi;
  EXPECT_GT(q, 0.2);
  EXPECT_LT(q, 0.35);
  // A fit on 500-600 nm does not: refused.
  const SpectralModel narrow(model, {500.0, 600.0}, {0.1, 0.4});
  EXPECT_THROW(compute_rtable(narrow, ph), InputError);
}

// ---- classes and comparison -----------------------------------------------------------------------

TEST(RTableClasses, Boundaries) {
  EXPECT_EQ(classify(0.4199).name, "R1");
  EXPECT_EQ(classify(0.42).name, "R2");
  EXPECT_EQ(classify(0.85).name, "R3");
  EXPECT_EQ(classify(1.35).name, "R4");
  EXPECT_EQ(classify(5.0).name, "R4");
  EXPECT_EQ(classify(0.27, ClassSystem::N).name, "N1");
  EXPECT_EQ(classify(0.28, ClassSystem::N).name, "N2");
  EXPECT_EQ(classify(0.6, ClassSystem::N).name, "N3");
  EXPECT_EQ(classify(1.3, ClassSystem::N).name, "N4");
  EXPECT_EQ(classify(0.39, ClassSystem::C).name, "C1");
  EXPECT_EQ(classify(0.40, ClassSystem::C).name, "C2");
  EXPECT_DOUBLE_EQ(classify(1.0).standard_q0, 0.07);
  EXPECT_DOUBLE_EQ(classify(0.1, ClassSystem::N).standard_q0, 0.10);
  EXPECT_EQ(class_system_from_name("c"), ClassSystem::C);
  EXPECT_THROW(class_system_from_name("W"), InputError);
}

TEST(RTableCompare, ScaledTable) {
  const RTable b = standard("r2-table.dat");
  RTable a = b;
  for (double& x : a.scaled) x *= 1.1;
  a.at(0, 0) = b.at(0, 0) * 1.3;
  const RTableComparison c = compare(a, b);
  EXPECT_EQ(c.compared_cells, 396u);
  EXPECT_EQ(c.only_in_a, 0u);
  EXPECT_NEAR(c.max_relative, 0.3, 1e-12);
  EXPECT_EQ(c.max_row, 0u);
  EXPECT_EQ(c.max_column, 0u);
  EXPECT_NEAR(c.mean_relative, (395 * 0.1 + 0.3) / 396, 1e-12);
  EXPECT_NEAR(c.s1_difference, s1(b) * (1.1 / 1.3 - 1.0), 1e-12);
  EXPECT_NEAR(c.q0_difference, q0(a) - q0(b), 1e-15);
  const RTableComparison self = compare(b, b);
  EXPECT_EQ(self.max_relative, 0.0);
  EXPECT_EQ(self.q0_difference, 0.0);
  // A full table against a standard one: cells outside the standard region are only in the first.
  const RTableComparison full = compare(lambert_table(0.2), b);
  EXPECT_EQ(full.only_in_a, 580u - 396u);
}

// ---- command line ---------------------------------------------------------------------------------

std::string run(const std::string& arguments, int* status = nullptr) {
  const std::string command = roadbrdf::test::cli_program() + " " + arguments + " 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (std::size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int rc = pclose(pipe);
  if (status) *status = rc;
  return out;
}

TEST(RTableCli, JsonOfALambertianSurface) {
  if (!std::filesystem::exists(roadbrdf::test::cli_program())) GTEST_SKIP() << "roadbrdf program not built";
  const auto j = nlohmann::json::parse(run("rtable lambert -p albedo=0.3 --json"));
  EXPECT_NEAR(j["Q0"].get<double>(), 0.3 / kPi, 1e-14);
  EXPECT_NEAR(j["S1"].get<double>(), std::pow(5.0, -1.5), 1e-14);
  EXPECT_NEAR(j["Qd"].get<double>(), 0.3 / kPi, 1e-14);
  EXPECT_NEAR(j["S2"].get<double>(), 1.0, 1e-13);
  EXPECT_EQ(j["class"], "R1");
  ASSERT_EQ(j["r"].size(), 29u);
  ASSERT_EQ(j["r"][0].size(), 20u);
  EXPECT_NEAR(j["r"][0][0].get<double>(), 0.3 / kPi, 1e-15);  // plain r, not x1e4
  EXPECT_EQ(j["beta_deg"][19].get<double>(), 180.0);
  EXPECT_EQ(j["tan_gamma"][28].get<double>(), 12.0);
}

TEST(RTableCli, ExportImportAndCompare) {
  if (!std::filesystem::exists(roadbrdf::test::cli_program())) GTEST_SKIP() << "roadbrdf program not built";
  const std::string rtb = temp_path("cli.rtb").string();
  int status = 0;
  run("rtable oren-nayar -p albedo=0.3 -p sigma=0.4 -o " + rtb, &status);
  EXPECT_EQ(status, 0);
  const std::string r3 = data_file("third-party/rtables/r3-table.dat");
  const auto j = nlohmann::json::parse(run("rtable --import " + r3 + " --json --compare " + r3));
  EXPECT_EQ(j["class"], "R3");
  EXPECT_TRUE(j["r"][28][19].is_null());  // missing cell
  EXPECT_EQ(j["comparison"]["max_relative_difference"].get<double>(), 0.0);
  const auto k = nlohmann::json::parse(run("rtable --import " + rtb + " --json --compare " + rtb));
  EXPECT_EQ(k["defined_cells"].get<int>(), 580);
  EXPECT_EQ(k["comparison"]["max_relative_difference"].get<double>(), 0.0);
  run("rtable lambert --import " + r3, &status);
  EXPECT_NE(status, 0);
  std::filesystem::remove(rtb);
}

TEST(RTableCli, FitFileWithAFlatSpectrumEqualsThePlainModel) {
  if (!std::filesystem::exists(roadbrdf::test::cli_program())) GTEST_SKIP() << "roadbrdf program not built";
  const std::string fit =
      temp_file("flat_fit.json",
                R"({"format": "roadbrdf-fit", "version": 1, "best": "oren-nayar", "fits": [{"model": "oren-nayar",
          "options": {}, "wavelengths": [360, 500, 600, 830],
          "parameters": {"albedo": [0.35, 0.35, 0.35, 0.35], "sigma": [0.45, 0.45, 0.45, 0.45]}}]})");
  const auto plain = nlohmann::json::parse(run("rtable oren-nayar -p albedo=0.35 -p sigma=0.45 --json"));
  for (const char* ill : {"A", "D65"}) {
    const auto weighted = nlohmann::json::parse(run("rtable " + fit + " --illuminant " + ill + " --json"));
    EXPECT_NEAR(weighted["Q0"].get<double>() / plain["Q0"].get<double>(), 1.0, 1e-12) << ill;
    EXPECT_NEAR(weighted["r"][8][0].get<double>() / plain["r"][8][0].get<double>(), 1.0, 1e-12) << ill;
  }
  std::filesystem::remove(fit);
}

}  // namespace
}  // namespace roadbrdf::photometry
