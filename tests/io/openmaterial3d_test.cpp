// ASAM OpenMATERIAL 3D BRDF look-up tables (io/openmaterial3d.h): units and conventions of the
// reader, a written file read back to the same values, sorted rows, refused inputs, the measured
// asphalt LiDAR file of ../shared (skipped when absent), and `roadbrdf export` grids.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/io/alta.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/model_export.h"
#include "roadbrdf/io/openmaterial3d.h"
#include "roadbrdf/models/registry.h"
#include "support/paths.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

constexpr double kPi = std::numbers::pi;

std::string corpus(const std::string& name) { return test::source_dir() + "/tests/fuzz/corpus/openmaterial3d/" + name; }

SpectralDataset read(const std::string& path, DatasetReadOptions options = {}) {
  options.warn = [](const std::string&) {};
  return read_dataset(path, options);
}

OpenMaterialMetadata metadata() {
  OpenMaterialMetadata m;
  m.name = "test";
  m.uuid = random_uuid();
  m.copyrights = {"none"};
  m.license = "CC0-1.0";
  m.authors = {"roadbrdf tests"};
  m.sources = "simulation";
  m.creation_date = utc_timestamp();
  return m;
}

// The file of the corpus, written by hand: metres -> nm, radians kept, exit azimuth = phi_r - phi_i,
// a null BRDF missing, the solid angle and the metadata kept.
TEST(OpenMaterial3d, ReadsUnitsConventionsAndMetadata) {
  const SpectralDataset d = read(corpus("small_brdf.xompt"));
  ASSERT_EQ(d.wavelengths, (std::vector<double>{905.0, 1550.0}));
  ASSERT_EQ(d.geometry_count(), 3u);
  EXPECT_DOUBLE_EQ(d.geometries[2].theta_i, 0.5);
  EXPECT_DOUBLE_EQ(d.geometries[2].theta_r, 0.5);
  EXPECT_NEAR(d.geometries[2].phi_r - d.geometries[2].phi_i, kPi, 1e-15);
  EXPECT_DOUBLE_EQ(d.value(1, 0), 0.12);
  EXPECT_TRUE(std::isnan(d.value(1, 1)));
  EXPECT_EQ(d.metadata.at("receiver_solid_angle_sr.905"), "0.001");
  EXPECT_EQ(d.metadata.at("openmaterial3d.typicalSensorTechnology"), "lidar");
  EXPECT_EQ(d.metadata.at("openmaterial3d.authors"), "roadbrdf tests");
}

TEST(OpenMaterial3d, RefusesWhatTheSchemaRefusesWithTheKeyPath) {
  const auto message = [](const std::string& file, DatasetReadOptions o = {}) {
    try {
      read(corpus(file), o);
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("bad_rows.xompt").find("brdf.lookupTable[0][0]"), std::string::npos);
  EXPECT_NE(message("duplicate_rows.xompt").find("brdf.lookupTable[1]"), std::string::npos);
  DatasetReadOptions average;
  average.average_duplicates = true;
  EXPECT_EQ(message("duplicate_rows.xompt", average), "no error");
  DatasetReadOptions strict;
  strict.allow_missing = false;
  EXPECT_NE(message("small_brdf.xompt", strict).find("brdf.lookupTable[4][4]"), std::string::npos);
}

TEST(OpenMaterial3d, WrittenFileReadsBackTheSameValuesInSortedRows) {
  SpectralDataset d;
  d.wavelengths = {550.0, 905.0};
  // Given out of order, with an azimuth of -90 deg (270 deg relative).
  d.geometries = {geometry_from_degrees(60.0, 0.0, 30.0, 180.0), geometry_from_degrees(10.0, 90.0, 20.0, 0.0),
                  geometry_from_degrees(10.0, 0.0, 20.0, 45.0)};
  d.brdf = {0.1 / 3.0, 0.2 / 7.0, 1.0 / 3.0, 0.25, 1e-7, std::nan("")};
  const std::string path = test::scratch_path("written_brdf.xompt");
  write_openmaterial3d(d, metadata(), path);
  const SpectralDataset back = read(path);
  ASSERT_EQ(back.wavelengths, d.wavelengths);
  ASSERT_EQ(back.geometry_count(), 3u);
  // Rows are sorted: (10, 20, 45 deg), (10, 20, 270 deg), (60, 30, 180 deg).
  EXPECT_NEAR(back.geometries[0].phi_r * 180.0 / kPi, 45.0, 1e-12);
  EXPECT_NEAR(back.geometries[1].phi_r * 180.0 / kPi, 270.0, 1e-12);
  EXPECT_EQ(back.value(0, 0), d.value(2, 0));
  EXPECT_EQ(back.value(0, 0), 1e-7);
  EXPECT_TRUE(std::isnan(back.value(0, 1)));
  EXPECT_EQ(back.value(1, 1), d.value(1, 1));
  EXPECT_EQ(back.value(2, 0), d.value(0, 0));
  const Json doc = parse_json_file(path);
  const auto& rows = doc["brdf"]["lookupTable"];
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const std::vector<double> a = {rows[k - 1][0], rows[k - 1][1], rows[k - 1][2], rows[k - 1][3]};
    const std::vector<double> b = {rows[k][0], rows[k][1], rows[k][2], rows[k][3]};
    EXPECT_LT(a, b) << "row " << k;
  }
}

TEST(OpenMaterial3d, WriterRefusesWhatTheSchemaRefuses) {
  SpectralDataset d;
  d.wavelengths = {905.0};
  d.geometries = {geometry_from_degrees(90.0, 0.0, 0.0, 0.0)};
  d.brdf = {0.1};
  const std::string path = test::scratch_path("refused_brdf.xompt");
  EXPECT_THROW(write_openmaterial3d(d, metadata(), path), InputError);  // 90 deg > 1.570796 rad
  d.geometries = {geometry_from_degrees(10.0, 0.0, 0.0, 0.0)};
  d.brdf = {-0.1};
  EXPECT_THROW(write_openmaterial3d(d, metadata(), path), InputError);
  d.brdf = {0.1};
  OpenMaterialMetadata m = metadata();
  m.uuid = "not-a-uuid";
  try {
    write_openmaterial3d(d, m, path);
    FAIL();
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "uuid");
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

// A uuid of version 4 (RFC 4122 section 4.4): the version nibble 4, the variant bits 10.
TEST(OpenMaterial3d, RandomUuidIsVersion4) {
  const std::string a = random_uuid(), b = random_uuid();
  ASSERT_EQ(a.size(), 36u);
  EXPECT_EQ(a[14], '4');
  EXPECT_NE(std::string("89ab").find(a[19]), std::string::npos);
  EXPECT_NE(a, b);
}

// A Lambertian model exported on a grid: every value rho/pi, in all three formats.
TEST(ModelExport, LambertGridInEveryFormat) {
  ExportRequest r;
  r.source = "lambert";
  r.parameters = {"albedo=0.3"};
  r.preset = "lidar";
  r.theta_i = {0.0, 45.0, 89.0};
  r.theta_r = {0.0, 60.0};
  r.phi = {0.0, 90.0, 180.0};
  r.output = test::scratch_path("lambert_brdf.xompt");
  const ExportResult result = export_model(r);
  EXPECT_EQ(result.sources, "simulation");
  EXPECT_EQ(result.metadata["typicalSensorTechnology"], "lidar");
  const SpectralDataset back = read(r.output);
  ASSERT_EQ(back.wavelengths, (std::vector<double>{905.0, 1550.0}));
  ASSERT_EQ(back.geometry_count(), 12u);  // theta_r = 0: one azimuth
  for (const double f : back.brdf) EXPECT_NEAR(f, 0.3 / kPi, 1e-15);

  r.format = "csv";
  r.output = test::scratch_path("lambert_grid.csv");
  export_model(r);
  EXPECT_EQ(read(r.output).brdf, back.brdf);

  r.format = "alta";
  r.output = test::scratch_path("lambert_grid.alta");
  try {
    export_model(r);
    FAIL() << "two wavelengths in ALTA";
  } catch (const FieldError& e) {
    EXPECT_EQ(e.field(), "wavelengths");
  }
  r.preset = "none";
  r.wavelengths = {905.0};
  export_model(r);
  AltaReadOptions ao;
  ao.wavelength_nm = 905.0;
  const SpectralDataset alta = read_alta(r.output, ao);
  ASSERT_EQ(alta.geometry_count(), 12u);
  for (const double f : alta.brdf) EXPECT_NEAR(f, 0.3 / kPi, 1e-15);
}

TEST(ModelExport, CameraPresetIs380To780By10) {
  ExportRequest r;
  r.source = "lambert";
  r.preset = "camera";
  r.theta_i = {30.0};
  r.theta_r = {30.0};
  r.phi = {0.0};
  r.output = test::scratch_path("camera_brdf.xompt");
  const ExportResult result = export_model(r);
  ASSERT_EQ(result.wavelengths.size(), 41u);
  EXPECT_EQ(result.wavelengths.front(), 380.0);
  EXPECT_EQ(result.wavelengths.back(), 780.0);
  EXPECT_EQ(result.metadata["typicalSensorTechnology"], "camera");
}

// 90 deg written in radians rounded to six decimals (1.570796 below pi/2, 1.5707964 above it) is the
// grazing direction, read as exactly pi/2 and counted; 1.5707 (89.994 deg) is a measured angle, kept.
TEST(OpenMaterial3d, RadiansRoundedToSixDecimalsAtNinetyDegreesAreGrazing) {
  std::string text;
  {
    std::ifstream in(corpus("small_brdf.xompt"));
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string rows = R"("lookupTable": [
      [9.05e-07, 1.570796, 0.0, 0.0, 0.1],
      [9.05e-07, 0.5, 1.5707964, 3.141592653589793, 0.2],
      [9.05e-07, 1.5707, 0.5, 6.2831853, 0.3],
      [1.55e-06, 1.570796, 0.0, 0.0, 0.09],
      [1.55e-06, 0.5, 1.5707964, 3.141592653589793, 0.18],
      [1.55e-06, 1.5707, 0.5, 6.2831853, 0.27]
    ])";
  const auto begin = text.find("\"lookupTable\"");
  const auto end = text.find(']', text.find("3.141592653589793, 0.18]")) + 1;
  ASSERT_NE(begin, std::string::npos);
  text.replace(begin, text.find("\n  }", end) - begin, rows);
  const std::string path = test::scratch_path("rounded_radians.xompt");
  std::ofstream(path) << text;
  std::vector<std::string> warnings;
  DatasetReadOptions options;
  options.warn = [&warnings](const std::string& w) { warnings.push_back(w); };
  const SpectralDataset d = read_dataset(path, options);
  ASSERT_EQ(d.geometry_count(), 3u);
  EXPECT_EQ(d.geometries[0].theta_i, kPi / 2);
  EXPECT_TRUE(d.geometries[0].grazing_i());
  EXPECT_EQ(d.geometries[1].theta_r, kPi / 2);
  EXPECT_TRUE(d.geometries[1].grazing_r());
  EXPECT_EQ(d.geometries[2].theta_i, 1.5707);
  EXPECT_FALSE(d.geometries[2].grazing_i());
  // 6.2831853 is 2 pi - 7e-9: within the rounding of 2 pi, read as 2 pi (the same direction as 0).
  EXPECT_EQ(d.metadata.at("rounded_radian_angles"), "6");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("1.570796 is 89.99997 deg"), std::string::npos) << warnings[0];
}

// The measured asphalt of ASAM OpenMATERIAL 3D's examples (DIVP, 905 nm): 905 rows, incident zenith
// 86-90 deg, exit zenith 0-90 deg by 1 deg, exit azimuth 0 or pi.
TEST(OpenMaterial3d, MeasuredAsphaltLidarFile) {
  const std::string dir = test::shared_real_data_dir();
  if (dir.empty()) GTEST_SKIP() << "../shared/real-data is absent: the OpenMATERIAL 3D asphalt file is not read";
  const std::string path = dir + "/openmaterial3d/example_material_lidar_brdf.xompt";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
  const SpectralDataset d = read(path);
  EXPECT_EQ(d.wavelengths, std::vector<double>{905.0});
  EXPECT_EQ(d.geometry_count(), 905u);
  EXPECT_EQ(d.metadata.at("openmaterial3d.sources"), "measurement");
  EXPECT_EQ(d.metadata.at("openmaterial3d.license"), "MPL-2.0");
  double lo = 1e9, hi = 0.0;
  for (const Geometry& g : d.geometries) {
    lo = std::min(lo, g.theta_i * 180.0 / kPi);
    hi = std::max(hi, g.theta_i * 180.0 / kPi);
  }
  EXPECT_NEAR(lo, 86.0, 1e-3);
  // Its "90 deg" rows hold 1.570796 rad: read as exactly 90 deg, so the grazing rules apply to them.
  EXPECT_EQ(hi, 90.0);
  EXPECT_GT(std::stoul(d.metadata.at("rounded_radian_angles")), 0u);
}

}  // namespace
}  // namespace roadbrdf
