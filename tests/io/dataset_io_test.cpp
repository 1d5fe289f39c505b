// Wide/long CSV datasets: round trips and every bad-input case with its file:line:column.
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/core/random.h"
#include "support/scratch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "support/paths.h"

namespace roadbrdf {
namespace {

const std::string kData = roadbrdf::test::test_data_dir() + "/io/";

std::string temp_file(const std::string& name, const std::string& content) {
  const std::string path = roadbrdf::test::scratch_path("io_" + name);
  std::ofstream(path) << content;
  return path;
}

struct Quiet {
  std::vector<std::string> warnings;
  DatasetReadOptions options() {
    DatasetReadOptions o;
    o.warn = [this](const std::string& w) { warnings.push_back(w); };
    return o;
  }
};

// Expect a FileError at line:column whose message contains `text`.
void expect_error(const std::string& content, long line, long column, const std::string& text,
                  DatasetReadOptions options = {}) {
  const std::string path = temp_file("bad.csv", content);
  if (!options.warn) options.warn = [](const std::string&) {};
  try {
    read_dataset(path, options);
    FAIL() << "no error for:\n" << content;
  } catch (const FileError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.column(), column) << e.what();
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    // The message starts with file:line:column (or file:line when the column is 0).
    std::string where = path;
    if (line > 0) where += ":" + std::to_string(line);
    if (column > 0) where += ":" + std::to_string(column);
    where += ": ";
    EXPECT_EQ(std::string(e.what()).rfind(where, 0), 0u) << e.what();
  }
}

SpectralDataset random_dataset(AngleConvention convention, bool sigma) {
  Rng rng(42);
  auto u = [&rng] { return -0.05 + 1.05 * rng.uniform(); };
  SpectralDataset d;
  d.convention = convention;
  d.wavelengths = {350, 351.5, 400, 1000, 2500};
  for (double ti : {0.0, 12.5, 45.0, 80.0}) {
    for (double tr : {0.0, 33.3, 70.0}) {
      for (double dphi : {0.0, 90.0, 180.0}) {
        if ((ti == 0.0 || tr == 0.0) && dphi != 0.0) continue;
        d.geometries.push_back(geometry_from_degrees(ti, 0.0, tr, dphi));
      }
    }
  }
  for (std::size_t k = 0; k < d.geometries.size() * d.wavelengths.size(); ++k) {
    d.brdf.push_back(u());
    if (sigma) d.sigma.push_back(std::fabs(u()) * 0.01);
  }
  d.metadata["sample"] = "random";
  d.metadata["instrument"] = "test";
  return d;
}

void expect_same(const SpectralDataset& a, const SpectralDataset& b) {
  ASSERT_EQ(a.geometries.size(), b.geometries.size());
  ASSERT_EQ(a.wavelengths, b.wavelengths);
  EXPECT_EQ(a.brdf, b.brdf);  // bit-identical values
  EXPECT_EQ(a.sigma, b.sigma);
  EXPECT_EQ(a.convention, b.convention);
  for (std::size_t g = 0; g < a.geometries.size(); ++g) {
    EXPECT_NEAR(a.geometries[g].theta_i, b.geometries[g].theta_i, 1e-10);
    EXPECT_NEAR(a.geometries[g].theta_r, b.geometries[g].theta_r, 1e-10);
    const Vec3 di = a.geometries[g].wi - b.geometries[g].wi, dr = a.geometries[g].wr - b.geometries[g].wr;
    EXPECT_LT(length(di), 1e-10);
    EXPECT_LT(length(dr), 1e-10);
  }
  for (const auto& [k, v] : a.metadata) EXPECT_EQ(b.metadata.at(k), v) << k;
  EXPECT_EQ(a.comments, b.comments);
}

TEST(DatasetIo, RoundTripWideAndLongBothConventions) {
  for (auto convention : {AngleConvention::kZenithAzimuth, AngleConvention::kRoad}) {
    for (bool sigma : {false, true}) {
      for (auto format : {DatasetFormat::kWide, DatasetFormat::kLong}) {
        const SpectralDataset d = random_dataset(convention, sigma);
        const std::string path = roadbrdf::test::scratch_path("io_roundtrip.csv");
        write_dataset(d, path, format);
        Quiet q;
        const SpectralDataset back = read_dataset(path, q.options());
        expect_same(d, back);
        EXPECT_EQ(q.warnings.size(), 1u);  // negative values are reported
      }
    }
  }
}

TEST(DatasetIo, WideAndLongHandWrittenFilesAgree) {
  Quiet q;
  DatasetReadStats stats;
  const SpectralDataset wide = read_dataset(kData + "wide_small.csv", q.options(), stats);
  EXPECT_EQ(stats.negative_values, 1u);
  ASSERT_EQ(q.warnings.size(), 1u);
  EXPECT_NE(q.warnings[0].find("1 of 9 BRDF values are negative"), std::string::npos) << q.warnings[0];
  EXPECT_NE(q.warnings[0].find("wide_small.csv:6:15"), std::string::npos) << q.warnings[0];
  EXPECT_EQ(wide.metadata.at("sample"), "test tile");
  EXPECT_EQ(wide.metadata.at("instrument"), "hand");
  EXPECT_EQ(wide.metadata.at("units"), "sr^-1");
  ASSERT_EQ(wide.geometry_count(), 3u);
  EXPECT_EQ(wide.wavelengths, (std::vector<double>{500, 600, 700}));
  EXPECT_EQ(wide.value(1, 1), -0.02);  // kept
  EXPECT_EQ(wide.sigma[8], 0.03);
  const SpectralDataset longf = read_dataset(kData + "long_small.csv", q.options());
  EXPECT_EQ(longf.convention, AngleConvention::kRoad);
  ASSERT_EQ(longf.geometry_count(), 3u);
  EXPECT_EQ(longf.wavelengths, wide.wavelengths);
  for (std::size_t g = 0; g < 3; ++g) {
    EXPECT_LT(length(longf.geometries[g].wi - wide.geometries[g].wi), 1e-12) << g;
    EXPECT_LT(length(longf.geometries[g].wr - wide.geometries[g].wr), 1e-12) << g;
    for (std::size_t j = 0; j < 3; ++j) {
      EXPECT_EQ(longf.value(g, j), wide.value(g, j));
      EXPECT_EQ(longf.sigma[g * 3 + j], wide.sigma[g * 3 + j]);
    }
  }
}

const std::string kHeader = "theta_i,phi_i,theta_r,phi_r,500,600\n";

TEST(DatasetIo, EmptyFile) {
  expect_error("", 0, 0, "file is empty");
  expect_error("# only a comment\n\n", 2, 0, "file is empty");
}

TEST(DatasetIo, HeaderWithoutRows) { expect_error(kHeader, 1, 0, "no data rows"); }

TEST(DatasetIo, NonNumericCell) { expect_error(kHeader + "0,0,30,180,0.1,abc\n", 2, 16, "'abc' is not a BRDF value"); }

TEST(DatasetIo, NonNumericAngle) { expect_error(kHeader + "0,x0,30,180,0.1,0.2\n", 2, 3, "'x0' is not a angle"); }

TEST(DatasetIo, InfIsAnErrorAndNanAMissingValue) {
  expect_error(kHeader + "0,0,30,180,0.1,inf\n", 2, 16, "'inf' is not a finite BRDF value");
  // Missing values are kept by default (MissingValuesKept); strict reading refuses them.
  Quiet q;
  DatasetReadOptions strict = q.options();
  strict.allow_missing = false;
  for (const char* row : {"0,0,30,180,nan,0.2\n", "0,0,30,180,0.1,\n"}) {
    const std::string path = temp_file("strict.csv", kHeader + row);
    EXPECT_THROW(read_dataset(path, strict), FileError) << row;
  }
}

TEST(DatasetIo, MissingValuesKept) {
  const std::string path = temp_file("missing.csv", kHeader + "0,0,30,180,nan,0.2\n10,0,30,180,,NA\n");
  Quiet q;
  DatasetReadOptions o = q.options();  // the default keeps them
  DatasetReadStats stats;
  const SpectralDataset d = read_dataset(path, o, stats);
  EXPECT_EQ(stats.missing_values, 3u);
  EXPECT_TRUE(std::isnan(d.value(0, 0)));
  EXPECT_EQ(d.value(0, 1), 0.2);
  ASSERT_EQ(q.warnings.size(), 1u);
  EXPECT_NE(q.warnings[0].find("3 of 4 BRDF values are missing"), std::string::npos);
}

TEST(DatasetIo, RaggedRows) {
  expect_error(kHeader + "0,0,30,180,0.1\n", 2, 15, "row has 5 cells but the header has 6 columns");
  expect_error(kHeader + "0,0,30,180,0.1,0.2,0.3\n", 2, 20, "extra cell '0.3'");
  try {
    read_dataset(kData + "ragged.csv");
    FAIL();
  } catch (const FileError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.column(), 16);
  }
}

TEST(DatasetIo, MissingAngleColumns) {
  expect_error("theta_i,phi_i,theta_r,500,600\n0,0,30,0.1,0.2\n", 1, 0, "lacks the angle columns");
}

TEST(DatasetIo, ZenithOutsideRange) {
  expect_error(kHeader + "0,0,91,180,0.1,0.2\n", 2, 5, "theta_r = '91' is outside [0, 90]");
  expect_error(kHeader + "-5,0,30,180,0.1,0.2\n", 2, 1, "theta_i = '-5' is outside [0, 90]");
  expect_error("gamma,alpha,beta,delta,500\n10,95,0,0,0.1\n", 2, 4, "alpha = '95' is outside [0, 90]");
}

TEST(DatasetIo, WavelengthsMustIncrease) {
  expect_error("theta_i,phi_i,theta_r,phi_r,600,500\n0,0,30,180,0.1,0.2\n", 1, 33, "strictly increasing");
  expect_error("theta_i,phi_i,theta_r,phi_r,500,500\n0,0,30,180,0.1,0.2\n", 1, 33, "equal to");
  expect_error("theta_i,phi_i,theta_r,phi_r,500,nm600\n0,0,30,180,0.1,0.2\n", 1, 33, "'nm600' is neither");
  expect_error("theta_i,phi_i,theta_r,phi_r,500,600,sigma_500,sigma_650\n0,0,30,180,0.1,0.2,0,0\n", 1, 47,
               "'sigma_650' does not match");
  expect_error("theta_i,phi_i,theta_r,phi_r\n0,0,30,180\n", 1, 28, "no wavelength columns");
}

TEST(DatasetIo, NegativeSigmaIsAnError) {
  expect_error("theta_i,phi_i,theta_r,phi_r,500,sigma_500\n0,0,30,180,0.1,-0.01\n", 2, 16, "cannot be negative");
}

TEST(DatasetIo, DuplicateGeometries) {
  // 0,360 is the same direction as 0,0: a duplicate, found through the directions.
  const std::string content = kHeader + "10,0,30,180,0.1,0.2\n20,0,30,180,0.1,0.2\n10,360,30,180,0.3,0.4\n";
  expect_error(content, 4, 1, "duplicate geometry: same angles as line 2");
  const std::string path = temp_file("dup.csv", content);
  Quiet q;
  DatasetReadOptions o = q.options();
  o.average_duplicates = true;
  DatasetReadStats stats;
  const SpectralDataset d = read_dataset(path, o, stats);
  EXPECT_EQ(stats.averaged_duplicate_rows, 1u);
  ASSERT_EQ(d.geometry_count(), 2u);
  EXPECT_DOUBLE_EQ(d.value(0, 0), 0.2);
  EXPECT_DOUBLE_EQ(d.value(0, 1), 0.3);
  EXPECT_EQ(d.metadata.at("averaged_duplicate_rows"), "1");
}

TEST(DatasetIo, DuplicateSigmaAveragedAsMean) {
  const std::string content = "theta_i,phi_i,theta_r,phi_r,500,sigma_500\n10,0,30,180,1.0,0.3\n10,0,30,180,2.0,0.4\n";
  const std::string path = temp_file("dupsigma.csv", content);
  DatasetReadOptions o;
  o.average_duplicates = true;
  o.warn = [](const std::string&) {};
  const SpectralDataset d = read_dataset(path, o);
  EXPECT_DOUBLE_EQ(d.value(0, 0), 1.5);
  EXPECT_DOUBLE_EQ(d.sigma[0], 0.25);  // sqrt(0.09 + 0.16) / 2
}

TEST(DatasetIo, DuplicatesAverageTheMeasuredValuesOnly) {
  // Wide and long: a cell missing in one duplicate is the other's value; missing in all, missing.
  const std::string wide =
      "theta_i,phi_i,theta_r,phi_r,500,600,sigma_500,sigma_600\n"
      "10,0,30,180,1.0,nan,0.3,nan\n10,0,30,180,3.0,nan,0.4,nan\n10,0,30,180,nan,nan,nan,nan\n";
  const std::string lng =
      "theta_i,phi_i,theta_r,phi_r,wavelength,brdf,sigma\n"
      "10,0,30,180,500,1.0,0.3\n10,0,30,180,500,3.0,0.4\n10,0,30,180,500,nan,nan\n"
      "10,0,30,180,600,nan,nan\n10,0,30,180,600,,\n";
  for (const auto& content : {wide, lng}) {
    const std::string path = temp_file("dupmissing.csv", content);
    Quiet q;
    DatasetReadOptions o = q.options();
    o.average_duplicates = true;
    const SpectralDataset d = read_dataset(path, o);
    ASSERT_EQ(d.geometry_count(), 1u);
    EXPECT_DOUBLE_EQ(d.value(0, 0), 2.0) << content;
    EXPECT_DOUBLE_EQ(d.sigma[0], 0.25) << content;  // sqrt(0.09 + 0.16) / 2: the two measured rows
    EXPECT_TRUE(std::isnan(d.value(0, 1))) << content;
    EXPECT_TRUE(std::isnan(d.sigma[1])) << content;
    EXPECT_EQ(missing_value_count(d), 1u);
  }
}

TEST(DatasetIo, MissingValuesRoundTripAsNan) {
  const std::string path = temp_file("missing_rt.csv", kHeader + "0,0,30,180,NA,0.2\n10,0,30,180,0.3,\n");
  Quiet q;
  const SpectralDataset d = read_dataset(path, q.options());
  for (auto format : {DatasetFormat::kWide, DatasetFormat::kLong}) {
    const std::string out = test::scratch_path(format == DatasetFormat::kWide ? "rt_wide.csv" : "rt_long.csv");
    write_dataset(d, out, format);
    const SpectralDataset back = read_dataset(out, q.options());
    ASSERT_EQ(back.brdf.size(), 4u);
    EXPECT_TRUE(std::isnan(back.value(0, 0)));
    EXPECT_EQ(back.value(0, 1), 0.2);
    EXPECT_EQ(back.value(1, 0), 0.3);
    EXPECT_TRUE(std::isnan(back.value(1, 1)));
  }
}

TEST(DatasetIo, LongFormatErrors) {
  const std::string h = "theta_i,phi_i,theta_r,phi_r,wavelength,brdf\n";
  expect_error(h + "0,0,30,180,500,0.1\n0,0,30,180,500,0.2\n", 3, 1, "already has wavelength 500 nm at line 2");
  // A pair without a row is a missing cell (dataset_dialect_test.cpp), an error when missing values
  // are refused, and always when the table would be more than half missing.
  DatasetReadOptions strict;
  strict.allow_missing = false;
  expect_error(h + "0,0,30,180,500,0.1\n0,0,30,180,600,0.2\n10,0,30,180,500,0.3\n", 4, 0,
               "no value at wavelength 600 nm (missing values are refused here)", strict);
  expect_error(h + "0,0,30,180,500,0.1\n10,0,30,180,600,0.2\n20,0,30,180,700,0.3\n", 2, 0,
               "has no value at wavelength 600 nm, and 6 of the 3 x 3 (geometry, wavelength) pairs have no row");
  expect_error("theta_i,phi_i,theta_r,phi_r,wavelength,brdf,colour\n0,0,30,180,500,0.1,red\n", 1, 45,
               "unexpected column 'colour'");
  expect_error(h + "0,0,30,180,-500,0.1\n", 2, 12, "not positive");
}

TEST(DatasetIo, UnitsMustBeBrdf) {
  expect_error("# units: W m^-2 sr^-1 nm^-1\n" + kHeader + "0,0,30,180,0.1,0.2\n", 1, 0, "units 'W m^-2 sr^-1 nm^-1'");
  const std::string path = temp_file("radiance.csv", "# units: counts\n" + kHeader + "0,0,30,180,10,20\n");
  DatasetReadOptions o;
  o.any_units = true;
  EXPECT_EQ(read_dataset(path, o).metadata.at("units"), "counts");
}

TEST(DatasetIo, WriteIsAtomicAndRejectsInconsistentData) {
  SpectralDataset d = random_dataset(AngleConvention::kZenithAzimuth, false);
  d.brdf.pop_back();
  const std::string path = roadbrdf::test::scratch_path("io_never.csv");
  std::filesystem::remove(path);
  EXPECT_THROW(write_dataset(d, path), InputError);
  EXPECT_FALSE(std::filesystem::exists(path));
}

// Free comment lines are data about the measurement (operator notes, instrument settings): kept in
// order through a read and a write, never dropped; "key: value" lines are metadata instead.
TEST(DatasetIo, FreeCommentsAreKeptInOrder) {
  const std::string path = temp_file("comments.csv",
                                     "# measured 2026-03-04 by J.D.\n# sample: concrete\n"
                                     "#lamp warmed up 20 min, 12:30 start\n" +
                                         kHeader + "0,0,30,180,0.1,0.2\n");
  Quiet q;
  const SpectralDataset d = read_dataset(path, q.options());
  EXPECT_EQ(d.comments,
            (std::vector<std::string>{"measured 2026-03-04 by J.D.", "lamp warmed up 20 min, 12:30 start"}));
  EXPECT_EQ(d.metadata.at("sample"), "concrete");
  for (DatasetFormat format : {DatasetFormat::kWide, DatasetFormat::kLong}) {
    const std::string out = roadbrdf::test::scratch_path("io_comments_out.csv");
    write_dataset(d, out, format);
    const SpectralDataset back = read_dataset(out, q.options());
    expect_same(d, back);  // the writer's own banner line is not read back as a comment
  }
}

// Every writer validates what it writes: nothing its own reader would refuse or read differently.
TEST(DatasetIo, WriterRefusesWhatWouldNotReadBack) {
  const std::string path = roadbrdf::test::scratch_path("io_refused.csv");
  auto refused = [&](SpectralDataset d, const std::string& fragment) {
    std::filesystem::remove(path);
    try {
      write_dataset(d, path);
      ADD_FAILURE() << "no error, expected '" << fragment << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(path));
  };
  const SpectralDataset good = random_dataset(AngleConvention::kZenithAzimuth, true);
  SpectralDataset d = good;
  d.wavelengths = {std::nan("")};
  d.brdf.resize(d.geometries.size());
  d.sigma.clear();
  refused(d, "wavelengths[0] = nan nm: must be finite and > 0");
  d = good;
  d.wavelengths.back() = std::numeric_limits<double>::infinity();
  refused(d, "must be finite and > 0");
  d = good;
  d.brdf[7] = -std::numeric_limits<double>::infinity();
  refused(d, "BRDF is infinite at geometry (row) 1");
  d = good;
  d.sigma[3] = -1e-3;
  refused(d, "sigma is -0.001");
  d = good;
  d.geometries[2].theta_r = std::nan("");
  refused(d, "geometry (row) 2");
  d = good;
  d.metadata["two words"] = "x";
  refused(d, "metadata key 'two words'");
  d = good;
  d.metadata["note"] = "line one\nline two";
  refused(d, "metadata 'note': the value must be one line");
  d = good;
  d.comments = {"ok", "line one\rline two"};
  refused(d, "must be one line");
  d = good;
  d.comments = {"operator: J.D."};
  refused(d, "would read back as metadata");
}

}  // namespace
}  // namespace roadbrdf
