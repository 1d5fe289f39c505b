// Instrument-file readers on real third-party files in ../shared/real-data/instrument-files/
// (never copied into the repository; the tests are skipped when the folder is absent).
// Reference values: the header table of PROVENANCE.md (read there with an independent parse) and
// the reflectance columns of the text files, parsed here independently of the readers.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/io/instrument.h"
#include "roadbrdf/io/manifest.h"
#include "roadbrdf/spectra/spectrum_file.h"
#include "support/paths.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

std::string folder() {
  const std::string shared = test::shared_real_data_dir();
  return shared.empty() ? "" : shared + "/instrument-files/";
}

#define REQUIRE_REAL_DATA() \
  if (folder().empty()) GTEST_SKIP() << "real third-party data not available (../shared/real-data is absent)"

std::size_t index_of(const InstrumentSpectrum& s, double wavelength) {
  for (std::size_t k = 0; k < s.wavelengths.size(); ++k) {
    if (std::fabs(s.wavelengths[k] - wavelength) < 1e-9) return k;
  }
  ADD_FAILURE() << s.path << " has no channel at " << wavelength << " nm";
  return 0;
}

struct AsdRow {
  const char* file;
  const char* version;
  const char* data_type;
  int integration_ms;
  double ratio[3];  // spectrum / reference at 500, 1000, 2000 nm
};

// PROVENANCE.md, "Header values read here with an independent quick parse" (all: 2151 channels,
// 350 nm + 1 nm, format 2 = double, instrument type 4).
const AsdRow kAsdTable[] = {
    {"asd-asdreader-GPL3/soil.asd", "as8", "raw", 9, {0.186, 0.472, 0.458}},
    {"asd-pyASD-MIT/v6sample/v6sample00000.asd", "as6", "raw", 68, {0.831, 0.879, 0.835}},
    {"asd-pyASD-MIT/v7sample/v7sample00000.asd", "as7", "radiance", 68, {0.988, 0.992, 1.001}},
    {"asd-pyASD-MIT/v7sample/v7sample00003.asd", "as7", "reflectance", 68, {0.843, 0.893, 0.824}},
    {"asd-pyASD-MIT/v7sample_field_spectroscopy/44231B009-1-FW300000.asd",
     "as7",
     "reflectance",
     17,
     {0.156, 0.384, 0.463}},
    {"asd-pyASD-MIT/v8sample/v8sample00001.asd", "as8", "raw", 68, {0.876, 0.883, 0.822}},
};

TEST(InstrumentRealData, AsdHeadersAndRatiosMatchProvenanceTable) {
  REQUIRE_REAL_DATA();
  for (const AsdRow& row : kAsdTable) {
    SCOPED_TRACE(row.file);
    const InstrumentSpectrum s = read_instrument_file(folder() + row.file);
    EXPECT_EQ(s.metadata.at("asd.version"), row.version);
    EXPECT_EQ(s.metadata.at("asd.data_type"), row.data_type);
    EXPECT_EQ(s.metadata.at("asd.data_format"), "double");
    EXPECT_EQ(s.metadata.at("asd.integration_time_ms"), std::to_string(row.integration_ms));
    EXPECT_EQ(s.metadata.at("asd.instrument_type"), "4 (FieldSpec full range)");
    ASSERT_EQ(s.wavelengths.size(), 2151u);
    EXPECT_EQ(s.wavelengths.front(), 350.0);
    EXPECT_EQ(s.wavelengths.back(), 2500.0);
    const double at[3] = {500.0, 1000.0, 2000.0};
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = index_of(s, at[k]);
      EXPECT_NEAR(s.target[i] / s.reference[i], row.ratio[k], 0.0005) << at[k] << " nm";
      EXPECT_NEAR(s.reflectance[i], row.ratio[k], 0.0005) << at[k] << " nm";
    }
  }
}

TEST(InstrumentRealData, EveryAsdFileParsesToTheEnd) {
  REQUIRE_REAL_DATA();
  const char* files[] = {"asd-pyASD-MIT/v6sample/v6sample00001.asd",
                         "asd-pyASD-MIT/v6sample/v6sample00002.asd",
                         "asd-pyASD-MIT/v7sample/v7sample00001.asd",
                         "asd-pyASD-MIT/v7sample/v7sample00002.asd",
                         "asd-pyASD-MIT/v7sample/v7sample00004.asd",
                         "asd-pyASD-MIT/v7sample/v7sample00005.asd",
                         "asd-pyASD-MIT/v7sample_field_spectroscopy/44231B009-1-FW3R00000.asd",
                         "asd-pyASD-MIT/v7sample_field_spectroscopy/44231B174-1-FF300000.asd",
                         "asd-pyASD-MIT/v8sample/v8sample00002.asd"};
  for (const char* f : files) {
    SCOPED_TRACE(f);
    const InstrumentSpectrum s = read_instrument_file(folder() + f);
    EXPECT_EQ(s.wavelengths.size(), 2151u);
    // v6 and v7 files end where the parsed blocks end (or with the 3-byte end marker); v8 files
    // carry an audit log and signature, which are not read.
    if (s.metadata.at("asd.version") != "as8") {
      EXPECT_EQ(s.metadata.count("asd.unread_bytes"), 0u);
    }
  }
  // v7sample00000 (radiance) carries three calibration spectra (86 kB: PROVENANCE.md).
  const InstrumentSpectrum r = read_instrument_file(folder() + "asd-pyASD-MIT/v7sample/v7sample00000.asd");
  EXPECT_NE(r.metadata.at("asd.calibrations").find("fiber optic"), std::string::npos);
  EXPECT_EQ(r.metadata.count("asd.unread_bytes"), 0u);
}

// The value column `column` (0-based, after the wavelength) of a text file's data rows, keyed by
// wavelength; rows start after the line that begins with `data_marker` (+ `skip` lines).
std::map<double, double> text_column(const std::string& path, const std::string& data_marker, int skip, int column) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && line.rfind(data_marker, 0) != 0) {
  }
  for (int k = 0; k < skip; ++k) std::getline(in, line);
  std::map<double, double> out;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    double wl, v = 0;
    row >> wl;
    for (int k = 0; k <= column; ++k) row >> v;
    if (row) out[wl] = v;
  }
  return out;
}

TEST(InstrumentRealData, SedReflectanceColumnsAndTheFileWithoutOne) {
  REQUIRE_REAL_DATA();
  const std::string dir = folder() + "sed-spectralevolution-spectrolab-GPL3/";
  for (const char* f : {"1566060_09506_working.sed", "data_psr_added_lines.sed", "data_psr_removed_lines.sed"}) {
    SCOPED_TRACE(f);
    const InstrumentSpectrum s = read_instrument_file(dir + f);
    ASSERT_EQ(s.wavelengths.size(), 2151u);
    const auto percent = text_column(dir + f, "Data:", 1, 2);
    ASSERT_EQ(percent.size(), 2151u);
    for (double wl : {350.0, 500.0, 1000.0, 1500.0, 2000.0, 2500.0}) {
      EXPECT_DOUBLE_EQ(s.reflectance[index_of(s, wl)], percent.at(wl) / 100.0) << wl;
    }
  }
  const InstrumentSpectrum dn = read_instrument_file(dir + "1566060_09506_working.sed");
  EXPECT_EQ(dn.quantity, "normalized DN");
  EXPECT_EQ(dn.metadata.at("sed.measurement"), "REFLECTANCE");
  const InstrumentSpectrum rad = read_instrument_file(dir + "data_psr_added_lines.sed");
  EXPECT_EQ(rad.quantity, "radiance");
  EXPECT_EQ(rad.units, "W/m^2/sr/nm");
  EXPECT_EQ(rad.metadata.at("sed.unrecognized_header_lines"), "8 (lines 2 to 10)");
  // Target / reference reproduces the radiance file's reflectance column to its printed precision.
  for (double wl : {500.0, 1000.0, 1500.0, 2000.0}) {
    const std::size_t i = index_of(rad, wl);
    EXPECT_NEAR(rad.target[i] / rad.reference[i], rad.reflectance[i], 2e-3 * rad.reflectance[i]) << wl;
  }
  const InstrumentSpectrum none = read_instrument_file(dir + "1566060_15025_not_working.sed");
  EXPECT_EQ(none.metadata.at("sed.measurement"), "DIRECT_ENERGY");
  EXPECT_TRUE(none.reflectance.empty());
  EXPECT_EQ(none.target.size(), 2151u);
  EXPECT_EQ(none.reference.size(), 2151u);
  EXPECT_THROW(instrument_signal(none, InstrumentQuantity::kReflectance), InputError);
}

TEST(InstrumentRealData, SvcOverlapRuleAndReflectanceColumns) {
  REQUIRE_REAL_DATA();
  const std::string dir = folder() + "svc-sig-spectrolab-GPL3/";
  // The overlap-matched file has increasing wavelengths: nothing to drop.
  InstrumentReadOptions strict;
  strict.overlap = OverlapRule::kError;
  const InstrumentSpectrum moc = read_instrument_file(dir + "BNL13001_000_moc.sig", strict);
  EXPECT_EQ(moc.wavelengths.size(), 982u);
  EXPECT_TRUE(moc.notes.empty());
  // The raw scan of the same target overlaps at 1016.6 -> 971.8 nm and 1911.9 -> 1898.4 nm.
  EXPECT_THROW(read_instrument_file(dir + "BNL13001_000.sig", strict), FileError);
  const InstrumentSpectrum raw = read_instrument_file(dir + "BNL13001_000.sig");
  for (std::size_t k = 1; k < raw.wavelengths.size(); ++k) ASSERT_GT(raw.wavelengths[k], raw.wavelengths[k - 1]);
  const auto refl = text_column(dir + "BNL13001_000.sig", "data=", 0, 2);
  std::size_t rows = 0;
  {
    std::ifstream in(dir + "BNL13001_000.sig");
    std::string line;
    bool data = false;
    while (std::getline(in, line)) {
      if (data && line.size() > 2) ++rows;
      if (line.rfind("data=", 0) == 0) data = true;
    }
  }
  EXPECT_EQ(rows, 1024u);
  // Rule "upper": every channel of the lower detector at or above the next detector's first
  // wavelength is dropped (971.8 and 1898.4 nm are the first wavelengths of the next detectors).
  std::size_t dropped = 0;
  double previous = 0.0, next_start = 0.0;
  std::vector<double> order;  // wavelengths in file order, for an independent count of the rule
  {
    std::ifstream in(dir + "BNL13001_000.sig");
    std::string line;
    bool data = false;
    while (std::getline(in, line)) {
      if (data && line.size() > 2) order.push_back(std::stod(line));
      if (line.rfind("data=", 0) == 0) data = true;
    }
  }
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && order[k] <= previous) {
      next_start = order[k];
      for (std::size_t j = k; j-- > 0 && order[j] >= next_start;) ++dropped;
    }
    previous = order[k];
  }
  EXPECT_EQ(dropped, 40u);
  EXPECT_EQ(raw.wavelengths.size() + dropped, rows);
  for (double wl : {400.1, 799.9, 1200.0, 2400.1}) {
    EXPECT_DOUBLE_EQ(raw.reflectance[index_of(raw, wl)], refl.at(wl) / 100.0) << wl;
  }
  EXPECT_EQ(raw.quantity, "radiance");
  // The white-reference scan (the panel against itself): reflectance 100 % within noise.
  const InstrumentSpectrum wr = read_instrument_file(dir + "ACPL_D2_P1_T_1_WR_000.sig");
  double mean = 0.0;
  for (double r : wr.reflectance) mean += r / static_cast<double>(wr.reflectance.size());
  EXPECT_NEAR(mean, 1.0, 1e-3);
  for (const char* f : {"data_svc_added_lines.sig", "data_svc_removed_lines.sig", "3_6_PANVI_2_T_1_001_BAD.sig"}) {
    SCOPED_TRACE(f);
    const InstrumentSpectrum s = read_instrument_file(dir + f);
    EXPECT_GT(s.wavelengths.size(), 900u);
  }
}

TEST(InstrumentRealData, ManifestOfRealFilesCalibrates) {
  REQUIRE_REAL_DATA();
  // An ASD reflectance file divided by its own stored white reference, with a flat panel of 0.99.
  const std::string manifest = test::scratch_path("real_run.csv");
  const std::string asd = folder() + "asd-pyASD-MIT/v7sample/v7sample00003.asd";
  std::ofstream(manifest) << "file,role,theta_i,phi_i,theta_r,phi_r\n" << asd << ",sample,0,0,45,180\n";
  const std::string panel = test::scratch_path("flat_panel.txt");
  std::ofstream(panel) << "300 0.99\n2600 0.99\n";
  const SpectralDataset f = calibrate_manifest(read_manifest(manifest), spectra::read_spectrum(panel));
  ASSERT_EQ(f.wavelength_count(), 2151u);
  EXPECT_NEAR(f.value(0, 500 - 350) * std::numbers::pi / 0.99, 0.843, 0.0005);
  EXPECT_NEAR(f.value(0, 1000 - 350) * std::numbers::pi / 0.99, 0.893, 0.0005);
  EXPECT_NEAR(f.value(0, 2000 - 350) * std::numbers::pi / 0.99, 0.824, 0.0005);
  EXPECT_EQ(f.metadata.at("asd.data_type"), "reflectance");
}

}  // namespace
}  // namespace roadbrdf
