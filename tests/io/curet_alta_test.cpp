// CUReT and ALTA readers on the bundled third-party files. The expected counts and values are
// taken from the files' structure and text, parsed here independently of the readers.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/io/alta.h"
#include "roadbrdf/io/curet.h"

namespace roadbrdf {
namespace {

const std::string kThird = roadbrdf::data_directory() + "/third-party/";

std::vector<std::vector<double>> numeric_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::vector<double> row;
    double v;
    while (s >> v) row.push_back(v);
    if (!row.empty()) rows.push_back(row);
  }
  return rows;
}

TEST(Curet, GeometryCountAndValuesFromTheFiles) {
  const auto table = numeric_lines(kThird + "curet/table.txt");
  const auto samples = numeric_lines(kThird + "curet/abrdf.dat");
  ASSERT_EQ(table.size(), 205u);  // the published CUReT measurement set
  std::vector<std::string> warnings;
  CuretReadOptions o;
  o.warn = [&](const std::string& w) { warnings.push_back(w); };
  for (int sample : {1, 45, 61}) {
    const SpectralDataset d = read_curet(kThird + "curet/abrdf.dat", kThird + "curet/table.txt", sample, o);
    ASSERT_EQ(d.geometry_count(), table.size());
    ASSERT_EQ(d.wavelength_count(), 1u);
    EXPECT_EQ(d.wavelengths[0], 550.0);
    EXPECT_EQ(d.metadata.at("units"), "sr^-1");
    const auto& row = samples[static_cast<std::size_t>(sample - 1)];
    ASSERT_EQ(row[0], sample);
    for (std::size_t g = 0; g < table.size(); ++g) {
      EXPECT_EQ(d.value(g, 0), row[g + 1]);
      // table.txt: index, theta_v, phi_v, theta_i, phi_i (radians) -> w_r from the view angles.
      const double tv = table[g][1], pv = table[g][2], ti = table[g][3], pi = table[g][4];
      EXPECT_NEAR(d.geometries[g].theta_i, ti, 1e-12);
      EXPECT_NEAR(d.geometries[g].theta_r, tv, 1e-12);
      EXPECT_NEAR(d.geometries[g].wr.x, std::sin(tv) * std::cos(pv), 1e-12);
      EXPECT_NEAR(d.geometries[g].wi.y, std::sin(ti) * std::sin(pi), 1e-12);
    }
  }
  // Count the negative values of every sample in the text and compare with the warnings.
  std::size_t negative_samples = 0;
  for (const auto& row : samples) {
    std::size_t neg = 0;
    for (std::size_t k = 1; k < row.size(); ++k) neg += row[k] < 0;
    if (neg == 0) continue;
    ++negative_samples;
    warnings.clear();
    const SpectralDataset d =
        read_curet(kThird + "curet/abrdf.dat", kThird + "curet/table.txt", static_cast<int>(row[0]), o);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find(std::to_string(neg) + " of 205 BRDF values are negative"), std::string::npos)
        << warnings[0];
  }
  EXPECT_GT(negative_samples, 0u);
}

TEST(Curet, UnknownSampleListsThePresentOnes) {
  try {
    read_curet(kThird + "curet/abrdf.dat", kThird + "curet/table.txt", 99);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no sample 99"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("1 2 3"), std::string::npos);
  }
  EXPECT_EQ(curet_sample_numbers(kThird + "curet/abrdf.dat").size(), 61u);
}

TEST(Alta, CosineFactorConvertedAndGrazingRowsRefusedOrExcluded) {
  const std::string path = kThird + "retroreflective/retro-3M-yellow.dat";
  const auto rows = numeric_lines(path);
  // Independent count of the grazing-view rows: theta_v = |(x, y)| = pi/2.
  std::size_t grazing = 0;
  for (const auto& r : rows) grazing += std::cos(std::hypot(r[1], r[2])) < 1e-6;
  ASSERT_EQ(rows.size(), 7397u);
  ASSERT_EQ(grazing, 86u);
  AltaReadOptions o;
  o.wavelength_nm = 633;
  o.warn = [](const std::string&) {};
  // Line of the first grazing row: 7 header lines, then one line per row.
  long first = 0;
  for (std::size_t k = 0; k < rows.size() && !first; ++k) {
    if (std::cos(std::hypot(rows[k][1], rows[k][2])) < 1e-6) first = 7 + static_cast<long>(k) + 1;
  }
  try {
    read_alta(path, o);
    FAIL();
  } catch (const FileError& e) {
    EXPECT_EQ(e.line(), first);
    EXPECT_NE(std::string(e.what()).find("grazing view"), std::string::npos);
  }
}

TEST(Alta, ReadsYellowTape) {
  const std::string path = kThird + "retroreflective/retro-3M-yellow.dat";
  const auto rows = numeric_lines(path);
  std::vector<std::string> warnings;
  AltaReadOptions o;
  o.wavelength_nm = 633;
  o.exclude_grazing = true;
  o.warn = [&](const std::string& w) { warnings.push_back(w); };
  const SpectralDataset d = read_alta(path, o);
  ASSERT_EQ(d.geometry_count(), 7397u - 86u);
  EXPECT_EQ(d.metadata.at("alta_grazing_rows_excluded"), "86");
  EXPECT_EQ(d.metadata.at("sample"), "3M Yellow");
  EXPECT_EQ(d.metadata.at("units"), "sr^-1");
  ASSERT_FALSE(warnings.empty());
  std::size_t g = 0;
  for (const auto& r : rows) {
    const double tv = std::hypot(r[1], r[2]);
    if (std::cos(tv) < 1e-6) continue;
    // BRDF = (BRDF cos theta_v) / cos theta_v; light at azimuth 0, view at atan2(y, x).
    EXPECT_NEAR(d.value(g, 0), r[3] / std::cos(tv), 1e-12 * std::fabs(r[3] / std::cos(tv)));
    EXPECT_NEAR(d.geometries[g].theta_i, r[0], 1e-12);
    EXPECT_NEAR(d.geometries[g].theta_r, tv, 1e-12);
    if (tv > 0) {
      EXPECT_NEAR(d.geometries[g].wr.x, std::sin(tv) * r[1] / tv, 1e-12);
      EXPECT_NEAR(d.geometries[g].wr.y, std::sin(tv) * r[2] / tv, 1e-12);
    }
    EXPECT_NEAR(d.geometries[g].wi.y, 0.0, 1e-15);
    ++g;
  }
  EXPECT_EQ(g, d.geometry_count());
}

TEST(Alta, MissingOutputUnitMustBeStated) {
  const std::string path = kThird + "retroreflective/retro-gray-tape.dat";
  AltaReadOptions o;
  o.wavelength_nm = 633;
  o.exclude_grazing = true;
  o.warn = [](const std::string&) {};
  try {
    read_alta(path, o);
    FAIL();
  } catch (const FileError& e) {
    EXPECT_EQ(e.line(), 7);
    EXPECT_NE(std::string(e.what()).find("no #PARAM_OUT"), std::string::npos);
  }
  o.assumed_output = "INV_STERADIAN_COSINE_FACTOR";
  const SpectralDataset d = read_alta(path, o);
  EXPECT_EQ(d.geometry_count(), numeric_lines(path).size() - 86u);
  AltaReadOptions no_wavelength;
  EXPECT_THROW(read_alta(path, no_wavelength), InputError);
}

}  // namespace
}  // namespace roadbrdf
