// Laboratory tables read without a script: column mapping, fixed angles, the quantity stored, and
// several runs combined. The tables in tests/data/io/lab are synthetic, in the shape of a laboratory
// goniometer's export (commanded and measured angle columns, extra columns, a reflectance factor).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/dataset_runs.h"
#include "support/paths.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

const std::string kLab = roadbrdf::test::test_data_dir() + "/io/lab/";

struct Collected {
  std::vector<std::string> warnings;
  DatasetReadOptions options(DatasetQuantity quantity = DatasetQuantity::kBrdf) {
    DatasetReadOptions o;
    o.quantity = quantity;
    o.columns = {{"theta_r", "True_Average_View_Zenith"}, {"phi_r", "True_Average_View_Azimuth"}};
    o.fixed_angles = {{"theta_i", 30.0}, {"phi_i", 0.0}};
    o.warn = [this](const std::string& w) { warnings.push_back(w); };
    return o;
  }
};

TEST(DatasetMapping, MappedColumnsAndFixedAnglesReadTheMeasuredAngles) {
  Collected c;
  const SpectralDataset d = read_dataset(kLab + "sand_brdf.csv", c.options());
  ASSERT_EQ(d.geometries.size(), 7u);
  ASSERT_EQ(d.wavelengths, (std::vector<double>{450, 550, 650}));
  // The measured (True_Average) zeniths of the file, not the commanded ones.
  const double measured[7] = {0.4, 20.3, 39.8, 60.1, 20.25, 39.65, 60.15};
  for (std::size_t g = 0; g < 7; ++g) {
    EXPECT_NEAR(rad_to_deg(d.geometries[g].theta_r), measured[g], 1e-12);
    EXPECT_NEAR(rad_to_deg(d.geometries[g].theta_i), 30.0, 1e-12);
  }
  // The extra columns are not read, and the warning names them.
  ASSERT_EQ(c.warnings.size(), 1u);
  for (const char* name : {"Run", "Commanded_View_Zenith", "Commanded_View_Azimuth", "Temperature_C"}) {
    EXPECT_NE(c.warnings[0].find(name), std::string::npos) << c.warnings[0];
  }
  // BRDF = (0.05 + 1e-4 (lambda - 450)) (1 + 0.2 cos theta_r), the formula the file was written from.
  for (std::size_t g = 0; g < 7; ++g) {
    for (std::size_t j = 0; j < 3; ++j) {
      const double expected =
          (0.05 + 1e-4 * (d.wavelengths[j] - 450.0)) * (1.0 + 0.2 * std::cos(d.geometries[g].theta_r));
      EXPECT_NEAR(d.brdf[g * 3 + j], expected, 1e-15);
    }
  }
}

TEST(DatasetMapping, EveryQuantityReadsBackTheSameBrdf) {
  Collected c;
  const SpectralDataset reference = read_dataset(kLab + "sand_brdf.csv", c.options());
  EXPECT_EQ(reference.metadata.count("quantity_read"), 0u);
  const struct {
    const char* file;
    DatasetQuantity quantity;
  } cases[] = {{"sand_brf.csv", DatasetQuantity::kBrf},
               {"sand_brdf_cos.csv", DatasetQuantity::kBrdfCos},
               {"sand_percent_brf.csv", DatasetQuantity::kPercentBrf}};
  for (const auto& k : cases) {
    const SpectralDataset d = read_dataset(kLab + k.file, c.options(k.quantity));
    ASSERT_EQ(d.brdf.size(), reference.brdf.size()) << k.file;
    for (std::size_t i = 0; i < d.brdf.size(); ++i) {
      EXPECT_NEAR(d.brdf[i], reference.brdf[i], 1e-15 * reference.brdf[i] * 4) << k.file << " value " << i;
    }
    EXPECT_EQ(d.metadata.at("quantity_read"), name_of(k.quantity));
    EXPECT_EQ(d.metadata.at("units"), "sr^-1");
  }
  // The closed-form factors themselves.
  EXPECT_DOUBLE_EQ(quantity_factor(DatasetQuantity::kBrf, 0.3), kPi);
  EXPECT_DOUBLE_EQ(quantity_factor(DatasetQuantity::kBrdfCos, 0.3), 0.3);
  EXPECT_DOUBLE_EQ(quantity_factor(DatasetQuantity::kPercentBrf, 0.3), 100.0 * kPi);
  EXPECT_DOUBLE_EQ(quantity_factor(DatasetQuantity::kBrdf, 0.3), 1.0);
}

TEST(DatasetMapping, SigmaIsConvertedLikeTheValues) {
  const std::string path = roadbrdf::test::scratch_path("mapping_sigma.csv");
  std::ofstream(path) << "theta_i,phi_i,theta_r,phi_r,500,sigma_500\n60,0,10,0,0.5,0.02\n90,0,10,0,0,0.01\n";
  std::vector<std::string> warnings;
  DatasetReadOptions o;
  o.quantity = DatasetQuantity::kBrdfCos;
  o.warn = [&](const std::string& w) { warnings.push_back(w); };
  const SpectralDataset d = read_dataset(path, o);
  EXPECT_NEAR(d.brdf[0], 0.5 / 0.5, 1e-14);  // cos 60 deg = 1/2
  EXPECT_NEAR(d.sigma[0], 0.02 / 0.5, 1e-15);
  // No irradiance at 90 deg: no BRDF, kept as missing and said so.
  EXPECT_TRUE(std::isnan(d.brdf[1]));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("theta_i = 90 deg"), std::string::npos);
  // Converted twice is refused.
  const std::string again = roadbrdf::test::scratch_path("mapping_converted.csv");
  write_dataset(d, again);
  EXPECT_THROW(read_dataset(again, o), FieldError);
}

TEST(DatasetMapping, ErrorsNameTheFieldAndTheNearestHeaderName) {
  Collected c;
  DatasetReadOptions o = c.options();
  o.columns["theta_r"] = "True_Average_View_Zenit";
  try {
    read_dataset(kLab + "sand_brdf.csv", o);
    FAIL() << "no error";
  } catch (const FileError& e) {
    EXPECT_EQ(e.line(), 4);
    EXPECT_NE(std::string(e.what()).find("did you mean 'True_Average_View_Zenith'"), std::string::npos) << e.what();
  }
  // An angle both fixed and mapped.
  o = c.options();
  o.fixed_angles["theta_r"] = 10.0;
  EXPECT_THROW(validate_read_options(o), FieldError);
  // Unknown fields and impossible values.
  o = c.options();
  o.columns["theta_x"] = "Run";
  EXPECT_THROW(validate_read_options(o), FieldError);
  o = c.options();
  o.fixed_angles["theta_i"] = 95.0;
  EXPECT_THROW(validate_read_options(o), FieldError);
  // Without a mapping nothing is guessed: the table's angle columns are not found.
  EXPECT_THROW(read_dataset(kLab + "sand_brdf.csv"), FileError);
  // A reflectance factor file that says sr^-1 contradicts `quantity` brf.
  EXPECT_THROW(read_dataset(kLab + "sand_brdf.csv", c.options(DatasetQuantity::kBrf)), FileError);
}

TEST(DatasetMapping, TheMappedColumnWinsOverOneNamedLikeItsField) {
  const std::string path = roadbrdf::test::scratch_path("mapping_both.csv");
  std::ofstream(path) << "theta_i,phi_i,theta_r,phi_r,measured_view,500\n30,0,20,180,20.4,0.1\n";
  std::vector<std::string> warnings;
  DatasetReadOptions o;
  o.columns = {{"theta_r", "Measured_View"}};  // case differs from the header
  o.warn = [&](const std::string& w) { warnings.push_back(w); };
  const SpectralDataset d = read_dataset(path, o);
  EXPECT_NEAR(rad_to_deg(d.geometries[0].theta_r), 20.4, 1e-12);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("'theta_r'"), std::string::npos) << warnings[0];
}

TEST(DatasetMapping, PerFileItemsOverrideTheGeneralOnes) {
  DatasetReadFields f;
  f.set = {"theta_i=30", "run_theta45.csv:theta_i=45", "phi_i=0"};
  f.columns = {"theta_r=View_Zenith", "phi_r=View_Azimuth"};
  const std::vector<std::string> files = {kLab + "run_theta30.csv", kLab + "run_theta45.csv"};
  EXPECT_DOUBLE_EQ(f.options_for(files[0], files).fixed_angles.at("theta_i"), 30.0);
  EXPECT_DOUBLE_EQ(f.options_for(files[1], files).fixed_angles.at("theta_i"), 45.0);
  f.set.push_back("other.csv:theta_i=10");
  EXPECT_THROW(f.options_for(files[0], files), FieldError);
  f.set = {"theta_i"};
  EXPECT_THROW(f.options_for(files[0], files), FieldError);
  f.set = {};
  f.quantity = "brfx";
  EXPECT_THROW(f.options_for(files[0], files), FieldError);
}

void expect_same(const SpectralDataset& a, const SpectralDataset& b) {
  ASSERT_EQ(a.geometries.size(), b.geometries.size());
  ASSERT_EQ(a.wavelengths, b.wavelengths);
  for (std::size_t g = 0; g < a.geometries.size(); ++g) {
    EXPECT_NEAR(a.geometries[g].theta_i, b.geometries[g].theta_i, 1e-14);
    EXPECT_NEAR(a.geometries[g].theta_r, b.geometries[g].theta_r, 1e-14);
    EXPECT_NEAR(std::cos(a.geometries[g].phi_r - b.geometries[g].phi_r), 1.0, 1e-14);
  }
  for (std::size_t i = 0; i < a.brdf.size(); ++i) EXPECT_EQ(a.brdf[i], b.brdf[i]) << i;
}

TEST(DatasetRuns, CombiningRunsEqualsReadingTheConcatenatedFile) {
  DatasetReadFields f;
  f.set = {"run_theta30.csv:theta_i=30", "run_theta45.csv:theta_i=45", "phi_i=0"};
  f.columns = {"theta_r=View_Zenith", "phi_r=View_Azimuth"};
  const SpectralDataset combined =
      read_dataset_runs({kLab + "run_theta30.csv", kLab + "run_theta45.csv"}, f, [](const std::string&) {});
  expect_same(combined, read_dataset(kLab + "runs_concatenated.csv"));
  EXPECT_NE(combined.metadata.at("runs").find("run_theta45.csv"), std::string::npos);
}

TEST(DatasetRuns, RepeatScansFollowTheDuplicatePolicy) {
  DatasetReadFields f;
  f.set = {"theta_i=30", "phi_i=0"};
  f.columns = {"theta_r=View_Zenith", "phi_r=View_Azimuth"};
  const std::vector<std::string> files = {kLab + "run_theta30.csv", kLab + "run_theta30_repeat.csv"};
  auto quiet = [](const std::string&) {};
  try {
    read_dataset_runs(files, f, quiet);
    FAIL() << "duplicates accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("`average_duplicates`"), std::string::npos) << e.what();
  }
  f.average_duplicates = true;
  const SpectralDataset combined = read_dataset_runs(files, f, quiet);
  DatasetReadOptions o;
  o.average_duplicates = true;
  o.warn = quiet;
  const SpectralDataset concatenated = read_dataset(kLab + "repeat_concatenated.csv", o);
  expect_same(combined, concatenated);
  EXPECT_EQ(combined.metadata.at("averaged_duplicate_rows"), concatenated.metadata.at("averaged_duplicate_rows"));
  // Runs with other wavelengths do not combine.
  std::vector<DatasetRun> runs(2);
  runs[0] = {"a", concatenated};
  runs[1] = {"b", concatenated};
  runs[1].data.wavelengths[0] = 449.0;
  EXPECT_THROW(combine_runs(runs, true, quiet), InputError);
}

}  // namespace
}  // namespace roadbrdf
