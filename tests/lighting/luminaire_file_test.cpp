// The EULUMDAT and IES LM-63 readers (lighting/luminaire_file.h) on the synthetic files of
// tests/data/lighting (make_synthetic.py): every intensity follows the closed form written there,
//   I(C, gamma) = (200 + 40 g(C)) (1 + gamma / 90) [cd/klm], g by symmetry,
// evaluated here at every C-plane of the expanded circle. And bad files: errors naming file and line.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/lighting/luminaire_file.h"
#include "roadbrdf/lighting/luminaire_flux.h"
#include "support/paths.h"

namespace roadbrdf::lighting {
namespace {

constexpr double kPi = 3.14159265358979323846;

double cosd(double x) { return std::cos(x * kPi / 180.0); }
double sind(double x) { return std::sin(x * kPi / 180.0); }

double closed_form(const std::function<double(double)>& g, double c, double gamma) {
  return (200.0 + 40.0 * g(c)) * (1.0 + gamma / 90.0);
}

std::string data(const std::string& name) { return test::test_data_dir() + "/lighting/" + name; }

// Every expanded plane and gamma angle of `lum` against the closed form times `candela_per_cdklm`,
// and the plane count.
void expect_closed_form(const Luminaire& lum, const std::function<double(double)>& g, double candela_per_cdklm,
                        std::size_t planes) {
  const IntensityDistribution& d = lum.distribution;
  ASSERT_EQ(d.c_deg.size(), planes);
  ASSERT_EQ(d.gamma_deg.size(), 5u);
  for (std::size_t i = 0; i < d.c_deg.size(); ++i) {
    for (std::size_t j = 0; j < d.gamma_deg.size(); ++j) {
      const double expected = closed_form(g, d.c_deg[i], d.gamma_deg[j]) * candela_per_cdklm;
      EXPECT_NEAR(d.at(i, j), expected, 1e-6 * expected) << "C " << d.c_deg[i] << " gamma " << d.gamma_deg[j];
    }
  }
}

Luminaire read(const std::string& name, Diagnostics& diagnostics) { return read_luminaire(data(name), diagnostics); }

TEST(Eulumdat, EverySymmetryCodeExpandsToTheFullCircle) {
  Diagnostics diag;
  const double scale = 2000.0 / 1000.0;  // cd/klm x lamp flux 2000 lm / 1000 lm
  const Luminaire isym0 = read("isym0.ldt", diag);
  expect_closed_form(
      isym0, [](double c) { return cosd(c) + 0.5 * sind(c); }, scale, 8);
  EXPECT_EQ(isym0.symmetry, PhotometricSymmetry::none);
  const Luminaire isym1 = read("isym1.ldt", diag);
  expect_closed_form(
      isym1, [](double) { return 0.0; }, scale, 1);
  EXPECT_EQ(isym1.symmetry, PhotometricSymmetry::rotational);
  const Luminaire isym2 = read("isym2.ldt", diag);
  expect_closed_form(
      isym2, [](double c) { return cosd(c); }, scale, 8);
  EXPECT_EQ(isym2.symmetry, PhotometricSymmetry::c0_c180);
  const Luminaire isym3 = read("isym3.ldt", diag);  // planes stored from C270 through C0 to C90
  expect_closed_form(
      isym3, [](double c) { return sind(c); }, scale, 8);
  EXPECT_EQ(isym3.symmetry, PhotometricSymmetry::c90_c270);
  const Luminaire isym4 = read("isym4.ldt", diag);
  expect_closed_form(
      isym4, [](double c) { return cosd(2.0 * c); }, scale, 8);
  EXPECT_EQ(isym4.symmetry, PhotometricSymmetry::quadrants);
  EXPECT_TRUE(diag.warnings.empty());
}

TEST(Eulumdat, HeaderFieldsFluxesAndLuminousArea) {
  Diagnostics diag;
  const Luminaire lum = read("isym2.ldt", diag);
  EXPECT_EQ(lum.format, "eulumdat");
  EXPECT_EQ(lum.name, "isym2");
  EXPECT_EQ(lum.manufacturer, "Synthetic Lighting Co.");
  EXPECT_FALSE(lum.absolute_photometry);
  EXPECT_DOUBLE_EQ(lum.lamp_flux_lm, 2000.0);
  EXPECT_DOUBLE_EQ(lum.flux_lm, 2000.0 * 0.80);  // lamp flux x LORL 80 %
  EXPECT_DOUBLE_EQ(lum.power_w, 25.0);
  EXPECT_DOUBLE_EQ(lum.luminous_area.along_c90_m, 0.5);  // the EULUMDAT length
  EXPECT_DOUBLE_EQ(lum.luminous_area.along_c0_m, 0.15);
  EXPECT_FALSE(lum.luminous_area.circular);
  EXPECT_DOUBLE_EQ(lum.luminous_area.heights_m[1], 0.03);
  EXPECT_EQ(lum.metadata["lamp_sets"].size(), 1u);
  EXPECT_EQ(lum.metadata["lamp_sets"][0]["colour_temperature"], "4000K");
  EXPECT_EQ(lum.metadata["direct_ratios"].size(), 10u);
  // Absolute photometry (negative number of lamps): the flux is the luminaire's, no lamp flux.
  const Luminaire absolute = read("absolute.ldt", diag);
  EXPECT_TRUE(absolute.absolute_photometry);
  EXPECT_EQ(absolute.lamp_flux_lm, 0.0);
  EXPECT_DOUBLE_EQ(absolute.flux_lm, 1500.0);
  expect_closed_form(
      absolute, [](double c) { return cosd(2.0 * c); }, 1.5, 8);
}

TEST(Ies, EveryEditionAndLateralSymmetry) {
  Diagnostics diag;
  // LM-63-2002, 0-90: candela x multiplier 2 x ballast factor 0.9; 2 lamps of 1000 lm.
  const Luminaire quadrants = read("quadrants_2002.ies", diag);
  expect_closed_form(
      quadrants, [](double c) { return cosd(2.0 * c); }, 2.0 * 0.9, 8);
  EXPECT_EQ(quadrants.symmetry, PhotometricSymmetry::quadrants);
  EXPECT_EQ(quadrants.name, "quadrant test luminaire second line of the name");
  EXPECT_EQ(quadrants.manufacturer, "Synthetic Lighting Co.");
  EXPECT_DOUBLE_EQ(quadrants.lamp_flux_lm, 2.0 * 1000.0 * 0.9);
  EXPECT_EQ(quadrants.metadata["lm63_edition"], 2002);
  EXPECT_DOUBLE_EQ(quadrants.luminous_area.along_c0_m, 0.6);  // the LM-63 length
  // LM-63-1995 with TILT=INCLUDE (kept in the metadata), 0-180, feet.
  const Luminaire tilt = read("tilt_1995.ies", diag);
  expect_closed_form(
      tilt, [](double c) { return cosd(c); }, 1.0, 8);
  EXPECT_EQ(tilt.metadata["tilt"]["factors"].size(), 3u);
  EXPECT_NEAR(tilt.luminous_area.along_c90_m, 1.5 * 0.3048, 1e-12);
  EXPECT_EQ(tilt.name, "TILT-1");  // no [LUMINAIRE]: the catalogue number
  // LM-63-2019, 0-360 (the 360 plane is the 0 plane), absolute photometry.
  const Luminaire full = read("full_2019.ies", diag);
  expect_closed_form(
      full, [](double c) { return cosd(c) + 0.5 * sind(c); }, 1.0, 8);
  EXPECT_TRUE(full.absolute_photometry);
  EXPECT_EQ(full.lamp_flux_lm, 0.0);
  EXPECT_NEAR(full.flux_lm, luminous_flux(full.distribution).total_lm(), 1e-9);
  // IESNA91, one horizontal angle: the ballast-lamp photometric factor 0.95 applies.
  const Luminaire round = read("rotational_1991.ies", diag);
  expect_closed_form(
      round, [](double) { return 0.0; }, 0.95, 1);
  EXPECT_TRUE(round.luminous_area.circular);
  EXPECT_NEAR(round.luminous_area.along_c0_m, 0.4, 1e-12);
  // 1986 (no format line), 90-270: symmetric about the C90-C270 plane.
  const Luminaire c90 = read("c90_c270_1986.ies", diag);
  expect_closed_form(
      c90, [](double c) { return sind(c); }, 1.0, 8);
  EXPECT_EQ(c90.metadata["lm63_edition"], 1986);
  EXPECT_TRUE(diag.warnings.empty());
}

// The FileError of `content` read as `name`: its line and a piece of its message.
void expect_error(const std::string& name, const std::string& content, long line, const std::string& what) {
  Diagnostics diag;
  try {
    parse_luminaire(content, name, diag);
    ADD_FAILURE() << "no error for " << name << " (" << what << ")";
  } catch (const FileError& e) {
    EXPECT_EQ(e.file(), name);
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

std::string lines(const std::vector<std::string>& l) {
  std::string out;
  for (const std::string& s : l) out += s + "\n";
  return out;
}

// A valid IES file with its fields replaced: header line, angles, candela rows.
std::string ies(const std::string& counts, const std::string& vertical, const std::string& horizontal,
                const std::vector<std::string>& rows, const std::string& tilt = "TILT=NONE") {
  std::vector<std::string> l = {"IESNA:LM-63-2002", "[LUMINAIRE] x", tilt, counts, "1 1 10", vertical, horizontal};
  l.insert(l.end(), rows.begin(), rows.end());
  return lines(l);
}

TEST(Ies, BadFilesNameFileAndLine) {
  const std::string good_counts = "1 1000 1 3 2 1 2 0 0 0";
  expect_error("a.ies", ies(good_counts, "0 45 90", "0 180", {"1 2 3", "4 5"}), 9, "truncated");
  expect_error("b.ies", ies(good_counts, "0 45 90", "0 180", {"1 2 3", "4 5 6 7"}), 9, "more values");
  expect_error("c.ies", ies(good_counts, "0 45 90", "0 180", {"1 x 3", "4 5 6"}), 8, "'x' is not a number");
  expect_error("d.ies", ies(good_counts, "0 45 90", "0 180", {"1 2 3", "4 -5 6"}), 9, "negative");
  expect_error("e.ies", ies(good_counts, "0 90 45", "0 180", {"1 2 3", "4 5 6"}), 6, "must increase");
  expect_error("f.ies", ies("1 1000 1 3 2 2 2 0 0 0", "0 45 90", "0 180", {"1 2 3", "4 5 6"}), 4, "photometric type B");
  expect_error("g.ies", ies("1 1000 1 3 2 3 2 0 0 0", "0 45 90", "0 180", {"1 2 3", "4 5 6"}), 4, "photometric type A");
  expect_error("h.ies", ies(good_counts, "0 45 90", "0 120", {"1 2 3", "4 5 6"}), 7, "horizontal angles from");
  expect_error("i.ies", ies(good_counts, "0 45 90", "0 180", {"1 2 3", "4 5 6"}, "TILT=lamp.tlt"), 3,
               "separate tilt file");
  expect_error("j.ies", lines({"IESNA:LM-63-2002", "[LUMINAIRE] x"}), 2, "TILT=");
  expect_error("k.ies", ies("1 0 1 3 2 1 2 0 0 0", "0 45 90", "0 180", {"1 2 3", "4 5 6"}), 4, "lumens per lamp");
  expect_error("l.ies", ies("1 1000 1 3.5 2 1 2 0 0 0", "0 45 90", "0 180", {"1 2 3", "4 5 6"}), 4, "integer");
}

// The synthetic isym2.ldt with line k (1-based) replaced, or cut after line k.
std::string ldt_with(long k, const std::string& replacement, bool cut = false) {
  const std::string content = test::test_data_dir() + "/lighting/isym2.ldt";
  Diagnostics diag;
  std::string text;
  {
    std::FILE* f = std::fopen(content.c_str(), "rb");
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
    std::fclose(f);
  }
  std::vector<std::string> l;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find("\r\n", start);
    l.push_back(text.substr(start, end - start));
    start = end + 2;
  }
  if (cut) {
    l.resize(static_cast<std::size_t>(k));
  } else {
    l[static_cast<std::size_t>(k - 1)] = replacement;
  }
  return lines(l);
}

TEST(Eulumdat, BadFilesNameFileAndLine) {
  // Header: 26 + 6 lamp-set lines + 10 direct ratios; C angles from line 43, gamma from 51,
  // intensities from 56 (5 planes of 5).
  expect_error("a.ldt", ldt_with(60, "", true), 60, "truncated");
  expect_error("b.ldt", ldt_with(58, "abc"), 58, "'abc' is not a number");
  expect_error("c.ldt", ldt_with(58, "-3"), 58, "negative");
  expect_error("d.ldt", ldt_with(45, "30"), 45, "must increase");  // C 0 45 30 ...
  expect_error("e.ldt", ldt_with(3, "7"), 3, "symmetry indicator");
  // 6 C-planes: the count does not match, the gamma list starts at the seventh C angle, 270.
  expect_error("f.ldt", ldt_with(4, "6"), 49, "gamma angle 1 of 5 is 270");
  expect_error("g.ldt", ldt_with(80, "1\n2"), 81, "more values");
  expect_error("h.ldt", ldt_with(29, "0"), 29, "flux must be positive");
  expect_error("i.ldt", ldt_with(20, "x"), 20, "luminous area height");
  expect_error("j.ldt", ldt_with(53, "30"), 53, "must increase");  // gamma 0 45 30
}

TEST(LuminaireFile, UnreadableInputs) {
  Diagnostics diag;
  EXPECT_THROW(read_luminaire(test::test_data_dir() + "/lighting/no such file.ldt", diag), FileError);
  EXPECT_THROW(read_luminaire(test::test_data_dir() + "/lighting", diag), FileError);
  expect_error("empty.ldt", "", 1, "truncated");
}

}  // namespace
}  // namespace roadbrdf::lighting
