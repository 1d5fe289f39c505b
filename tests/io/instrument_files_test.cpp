// Instrument-file readers and manifests on roadbrdf's own synthetic files
// (written into the build tree by tests/data/instruments/make_synthetic.py from closed forms given there).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/io/asd.h"
#include "roadbrdf/io/instrument.h"
#include "roadbrdf/io/manifest.h"
#include "roadbrdf/spectra/spectrum_file.h"
#include "support/paths.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

std::string dir() { return test::instrument_files_dir() + "/"; }

// The closed forms of make_synthetic.py.
double white(double l) { return 20000.0 + 4.0 * l; }
constexpr double kDark = 100.0;
double sample(int k, double l) { return kDark + 0.1 * (k + 1) * (white(l) - kDark) * (1.0 + l / 10000.0); }
double factor(int k, double l) { return 0.1 * (k + 1) * (1.0 + l / 10000.0); }
double rho(double l) { return 0.95 + 0.00001 * (l - 350.0); }

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string write_scratch(const std::string& name, const std::string& content) {
  const std::string path = test::scratch_path(name);
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(AsdReader, Version8RawHeaderAndSpectra) {
  const InstrumentSpectrum s = read_instrument_file(dir() + "run_001.asd");
  EXPECT_EQ(s.format, InstrumentFormat::kAsd);
  ASSERT_EQ(s.wavelengths.size(), 21u);
  EXPECT_EQ(s.wavelengths.front(), 350.0);
  EXPECT_EQ(s.wavelengths.back(), 370.0);
  EXPECT_EQ(s.metadata.at("asd.version"), "as8");
  EXPECT_EQ(s.metadata.at("asd.data_type"), "raw");
  EXPECT_EQ(s.metadata.at("asd.data_format"), "double");
  EXPECT_EQ(s.metadata.at("asd.integration_time_ms"), "68");
  EXPECT_EQ(s.metadata.at("asd.swir1_gain"), "118");
  EXPECT_EQ(s.metadata.at("asd.swir2_gain"), "616");
  EXPECT_EQ(s.metadata.at("asd.swir1_offset"), "2076");
  EXPECT_EQ(s.metadata.at("asd.swir2_offset"), "2253");
  EXPECT_EQ(s.metadata.at("asd.splice1_nm"), "1000");
  EXPECT_EQ(s.metadata.at("asd.splice2_nm"), "1830");
  EXPECT_EQ(s.metadata.at("asd.sample_count"), "25");
  EXPECT_EQ(s.metadata.at("asd.instrument_type"), "4 (FieldSpec full range)");
  EXPECT_EQ(s.metadata.at("asd.instrument_number"), "12345");
  EXPECT_EQ(s.metadata.at("asd.saved"), "2024-05-24 10:15:30");
  EXPECT_EQ(s.metadata.at("asd.reference_flag"), "true");
  EXPECT_EQ(s.metadata.at("asd.reference_time"), "2024-05-24 06:00:00");  // OLE date 45436.25
  EXPECT_EQ(s.metadata.at("asd.reference_description"), "synthetic white reference");
  EXPECT_EQ(s.metadata.at("asd.comments"), "roadbrdf synthetic file");
  EXPECT_EQ(s.quantity, "DN");
  for (std::size_t k = 0; k < 21; ++k) {
    const double l = 350.0 + static_cast<double>(k);
    EXPECT_EQ(s.target[k], sample(0, l));
    EXPECT_EQ(s.reference[k], white(l));
    EXPECT_NEAR(s.reflectance[k], sample(0, l) / white(l), 1e-15);
  }
  const InstrumentSpectrum w = read_instrument_file(dir() + "run_white.asd");
  EXPECT_EQ(w.metadata.at("asd.unread_bytes"), "36 bytes from byte 920 (audit log and signature)");
}

TEST(AsdReader, Version6FloatAndVersion7IntegerAndCalibrationBlocks) {
  const InstrumentSpectrum f = read_instrument_file(dir() + "v6_float_reflectance.asd");
  EXPECT_EQ(f.metadata.at("asd.version"), "as6");
  EXPECT_EQ(f.metadata.at("asd.data_type"), "reflectance");
  EXPECT_EQ(f.metadata.at("asd.data_format"), "float");
  EXPECT_EQ(f.metadata.count("asd.unread_bytes"), 0u);  // v6 ends after the classifier data
  for (std::size_t k = 0; k < 21; ++k) {
    const double l = 350.0 + static_cast<double>(k);
    EXPECT_EQ(f.target[k], static_cast<double>(static_cast<float>(sample(0, l))));
  }
  const InstrumentSpectrum i = read_instrument_file(dir() + "v7_integer_saturated.asd");
  EXPECT_EQ(i.metadata.at("asd.data_format"), "integer");
  EXPECT_EQ(i.metadata.at("asd.saturation"), "VNIR saturated");
  ASSERT_EQ(i.notes.size(), 1u);
  EXPECT_NE(i.notes[0].find("VNIR saturated"), std::string::npos);
  for (std::size_t k = 0; k < 21; ++k) EXPECT_EQ(i.target[k], std::round(sample(2, 350.0 + static_cast<double>(k))));
  const InstrumentSpectrum r = read_instrument_file(dir() + "v7_radiance_calibrations.asd");
  EXPECT_EQ(r.metadata.at("asd.data_type"), "radiance");
  EXPECT_EQ(r.metadata.at("asd.reference_flag"), "false");
  EXPECT_EQ(r.metadata.at("asd.calibrations"),
            "base (panel reflectance) 'bse00000.ref' (integration 0 ms, SWIR gains 0/0); lamp 'lmp00000.ill' "
            "(integration 0 ms, SWIR gains 0/0); fiber optic 'fo00000.raw' (integration 136 ms, SWIR gains 31/16)");
  EXPECT_EQ(r.metadata.count("asd.unread_bytes"), 0u);  // the calibration spectra end the file exactly
  EXPECT_EQ(r.quantity, "DN");                          // the stored spectrum stays raw counts
}

TEST(AsdReader, TruncatedFileNamesTheByteOffset) {
  const std::string bytes = slurp(dir() + "run_001.asd");
  ASSERT_EQ(bytes.size(), 920u);
  // Every truncation is an error naming the file and a byte offset, never a crash or a silent result.
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const std::string message = error_of([&] { parse_asd(std::string_view(bytes).substr(0, n), "cut.asd"); });
    EXPECT_EQ(message.rfind("cut.asd: byte ", 0), 0u) << n << ": " << message;
  }
  EXPECT_EQ(error_of([&] { parse_asd(std::string_view(bytes).substr(0, 600), "cut.asd"); }),
            "cut.asd: byte 484: file ends inside the spectrum (168 bytes needed, 116 left): truncated ASD file");
  EXPECT_EQ(error_of([&] { parse_asd(std::string_view(bytes).substr(0, 700), "cut.asd"); }),
            // 484 + 21 x 8 = 652: flag (2), two dates (16), description length (2) and 25 characters
            "cut.asd: byte 697: file ends inside the reference spectrum (168 bytes needed, 3 left): truncated ASD "
            "file");
}

TEST(AsdReader, CorruptHeaderFields) {
  std::string bytes = slurp(dir() + "run_001.asd");
  std::string v5 = bytes;
  v5[2] = '5';
  EXPECT_EQ(error_of([&] { parse_asd(v5, "x.asd"); }),
            "x.asd: byte 0: 'as5' is not an ASD file version roadbrdf reads (as6, as7, as8)");
  std::string format = bytes;
  format[199] = 7;
  EXPECT_NE(error_of([&] { parse_asd(format, "x.asd"); }).find("x.asd: byte 199: data format 7"), std::string::npos);
  std::string type = bytes;
  type[186] = 42;
  EXPECT_NE(error_of([&] { parse_asd(type, "x.asd"); }).find("byte 186: unknown data type 42"), std::string::npos);
  std::string flag = bytes;
  flag[484 + 21 * 8] = 0x12;
  EXPECT_NE(error_of([&] { parse_asd(flag, "x.asd"); }).find("byte 652: reference flag"), std::string::npos);
  std::string nan = bytes;
  for (int k = 0; k < 8; ++k) nan[484 + 8 + k] = static_cast<char>(0xff);
  EXPECT_NE(error_of([&] { parse_asd(nan, "x.asd"); }).find("byte 492: spectrum value 2 is not a finite number"),
            std::string::npos);
}

TEST(SedReader, ReflectanceFileAndFileWithoutReflectance) {
  const InstrumentSpectrum s = read_instrument_file(dir() + "sed_002.sed");
  EXPECT_EQ(s.format, InstrumentFormat::kSed);
  EXPECT_EQ(s.quantity, "normalized DN");
  ASSERT_EQ(s.wavelengths.size(), 21u);
  for (std::size_t k = 0; k < 21; ++k) {
    const double l = 350.0 + static_cast<double>(k);
    EXPECT_NEAR(s.target[k], sample(1, l) - kDark, 1e-8 * white(l));
    EXPECT_NEAR(s.reference[k], white(l) - kDark, 1e-8 * white(l));
    EXPECT_NEAR(s.reflectance[k], factor(1, l), 1e-8);
  }
  EXPECT_EQ(s.metadata.at("sed.measurement"), "REFLECTANCE");
  EXPECT_EQ(s.metadata.at("instrument"), "PSR+3500_SN0000000 [3]");
  EXPECT_EQ(s.target_settings.at("integration times [ms]"), "50,50,30");
  const InstrumentSpectrum n = read_instrument_file(dir() + "sed_no_reflectance.sed");
  EXPECT_TRUE(n.reflectance.empty());
  EXPECT_EQ(n.target.size(), 21u);
  EXPECT_EQ(error_of([&] { instrument_signal(n, InstrumentQuantity::kReflectance); }),
            dir() + "sed_no_reflectance.sed: the file has no reflectance column (nor a reference to form it)");
}

TEST(SedReader, TruncatedOrCorruptFileNamesTheLine) {
  const std::string text = slurp(dir() + "sed_001.sed");
  const std::string cut = text.substr(0, text.rfind("360.0"));  // rows 350..359 only
  const std::string p = write_scratch("cut.sed", cut);
  EXPECT_EQ(error_of([&] { read_instrument_file(p); }),
            p + ":27: 10 data rows, but line 14 says 'Channels: 21': truncated or corrupt file");
  std::string bad = text;
  bad.replace(bad.find("355.0"), 5, "35x.0");
  const std::string q = write_scratch("bad.sed", bad);
  EXPECT_EQ(error_of([&] { read_instrument_file(q); }), q + ":23:1: '35x.0' is not a finite number");
  const std::string r = write_scratch("nodata.sed", text.substr(0, text.find("Data:")));
  EXPECT_NE(error_of([&] { read_instrument_file(r); }).find("no 'Data:' line"), std::string::npos);
}

TEST(SigReader, OverlapRulesKeepOneDetectorAndReport) {
  // Lower detector 340..380 nm every 2 nm, upper 370..400 nm; reference = 1000 + l (+1000 upper).
  const InstrumentSpectrum up = read_instrument_file(dir() + "sig_overlap.sig");
  ASSERT_EQ(up.wavelengths.size(), 15u + 16u);  // lower 340..368, upper 370..400
  EXPECT_EQ(up.wavelengths[14], 368.0);
  EXPECT_EQ(up.wavelengths[15], 370.0);
  EXPECT_EQ(up.reference[15], 2000.0 + 370.0);
  EXPECT_EQ(up.reference[14], 1000.0 + 368.0);
  EXPECT_EQ(up.metadata.at("sig.overlap"),
            "rule 'upper': join at line 30: 6 channel(s) 370-380 nm of the lower "
            "detector dropped");
  ASSERT_EQ(up.notes.size(), 1u);
  EXPECT_EQ(up.quantity, "radiance");
  InstrumentReadOptions lower;
  lower.overlap = OverlapRule::kLower;
  const InstrumentSpectrum lo = read_instrument_file(dir() + "sig_overlap.sig", lower);
  ASSERT_EQ(lo.wavelengths.size(), 21u + 10u);  // lower 340..380, upper 382..400
  EXPECT_EQ(lo.reference[20], 1000.0 + 380.0);
  EXPECT_EQ(lo.wavelengths[21], 382.0);
  EXPECT_EQ(lo.reference[21], 2000.0 + 382.0);
  for (double r : lo.reflectance) EXPECT_EQ(r, 0.25);
  InstrumentReadOptions error;
  error.overlap = OverlapRule::kError;
  EXPECT_EQ(error_of([&] { read_instrument_file(dir() + "sig_overlap.sig", error); }),
            dir() +
                "sig_overlap.sig:30:1: detector overlap: wavelength 370 nm follows 380 nm (choose an overlap "
                "rule: upper or lower)");
  const InstrumentSpectrum none = read_instrument_file(dir() + "sig_no_overlap.sig", error);
  EXPECT_EQ(none.wavelengths.size(), 21u);
  EXPECT_TRUE(none.notes.empty());
}

TEST(SigReader, TruncatedRowNamesTheLine) {
  std::string text = slurp(dir() + "sig_no_overlap.sig");
  text = text.substr(0, text.size() - 9);  // "380.0  1380.00  345.00" loses its reflectance value
  const std::string p = write_scratch("cut.sig", text);
  EXPECT_EQ(error_of([&] { read_instrument_file(p); }),
            p + ":29:17: row has 3 values, line 9 had 4: truncated or corrupt file");
}

TEST(Manifest, AsdRunWithWhiteAndDarkGivesClosedForm) {
  const Manifest m = read_manifest(dir() + "run.csv");
  EXPECT_EQ(m.entries.size(), 5u);
  EXPECT_EQ(m.convention, AngleConvention::kRoad);
  spectra::Spectrum panel = spectra::read_spectrum(dir() + "rho.txt");
  const SpectralDataset f = calibrate_manifest(m, panel);
  ASSERT_EQ(f.geometry_count(), 3u);
  ASSERT_EQ(f.wavelength_count(), 21u);
  EXPECT_FALSE(f.has_sigma());
  for (int g = 0; g < 3; ++g) {
    for (std::size_t j = 0; j < 21; ++j) {
      const double l = f.wavelengths[j];
      EXPECT_NEAR(f.value(static_cast<std::size_t>(g), j), factor(g, l) * rho(l) / std::numbers::pi, 1e-15);
    }
  }
  EXPECT_EQ(f.metadata.at("sample"), "synthetic ASD run");
  EXPECT_EQ(f.metadata.at("white_reference"), "run_white.asd");
  EXPECT_EQ(f.metadata.at("dark"), "run_dark.asd");
  EXPECT_EQ(f.metadata.at("units"), "sr^-1");
  EXPECT_EQ(f.metadata.at("signal_units"), "DN");
  EXPECT_EQ(f.metadata.at("asd.integration_time_ms"), "68");
  EXPECT_EQ(f.metadata.at("asd.spectrum_time"), "2024-05-24 06:14:24");  // equal in every sample file
  // Road angles of the manifest: gamma = theta_i, alpha = 90 - theta_r.
  EXPECT_NEAR(f.geometries[1].theta_i, 30.0 * std::numbers::pi / 180.0, 1e-12);
  EXPECT_NEAR(f.geometries[1].theta_r, 45.0 * std::numbers::pi / 180.0, 1e-12);
}

TEST(Manifest, EmbeddedReferencesEqualTheTwoStepPath) {
  const Manifest m = read_manifest(dir() + "run_sed.csv");
  const spectra::Spectrum panel = spectra::read_spectrum(dir() + "rho.txt");
  const SpectralDataset f = calibrate_manifest(m, panel);
  EXPECT_EQ(f.metadata.at("white_reference"), "embedded (the reference stored in each sample file)");
  EXPECT_EQ(f.metadata.at("dark"), "none");
  for (int g = 0; g < 3; ++g) {
    for (std::size_t j = 0; j < 21; ++j) {
      const double l = f.wavelengths[j];
      EXPECT_NEAR(f.value(static_cast<std::size_t>(g), j), factor(g, l) * rho(l) / std::numbers::pi, 1e-9);
    }
  }
  // The same through the signal datasets (convert --quantity target / reference) and calibrate().
  CalibrationInput in;
  in.sample = manifest_dataset(m, InstrumentQuantity::kTarget);
  in.reference = manifest_dataset(m, InstrumentQuantity::kReference);
  in.panel_reflectance = panel;
  EXPECT_EQ(calibrate(in).brdf, f.brdf);
  const SpectralDataset r = manifest_dataset(m, InstrumentQuantity::kReflectance);
  EXPECT_EQ(r.metadata.at("units"), "1 (reflectance factor relative to the reference panel)");
  EXPECT_NEAR(r.value(2, 0), factor(2, 350.0), 1e-8);
}

std::string manifest_with(const std::string& name, const std::string& rows,
                          const std::string& header = "file,role,gamma,alpha,beta,delta") {
  std::string text = header + "\n";
  std::istringstream in(rows);
  std::string line;
  while (std::getline(in, line)) text += dir() + line + "\n";  // absolute paths
  return write_scratch(name, text);
}

TEST(Manifest, ErrorsNameTheManifestLineOrTheFile) {
  const std::string dup = manifest_with("dup.csv", "run_001.asd,sample,0,45,0,0\nrun_002.asd,sample,0,45,0,0");
  EXPECT_NE(error_of([&] { read_manifest(dup); }).find(dup + ":3:"), std::string::npos);
  const std::string role = manifest_with("role.csv", "run_001.asd,panel,0,45,0,0");
  EXPECT_NE(error_of([&] { read_manifest(role); }).find(role + ":2:"), std::string::npos);
  EXPECT_NE(error_of([&] { read_manifest(role); }).find("unknown role 'panel'"), std::string::npos);
  const std::string two = manifest_with("two.csv",
                                        "run_white.asd,white,,,,\nrun_white.asd,white,,,,\n"
                                        "run_001.asd,sample,0,45,0,0");
  const Manifest m2 = read_manifest(two);
  EXPECT_NE(error_of([&] { manifest_calibration_input(m2); }).find(two + ":3: 2 white reference rows"),
            std::string::npos);
  const std::string missing = manifest_with("missing.csv", "nothere.asd,sample,0,45,0,0");
  EXPECT_EQ(error_of([&] {
              manifest_dataset(read_manifest(missing), InstrumentQuantity::kTarget);
            }).rfind(dir() + "nothere.asd: cannot open file for reading", 0),
            0u);
  EXPECT_NE(error_of([&] { read_instrument_file(test::test_data_dir()); }).find("is a directory"), std::string::npos);
  const std::string mixed = manifest_with("mixed.csv", "run_001.asd,sample,0,45,0,0\nsed_001.sed,sample,10,45,0,0");
  EXPECT_NE(error_of([&] {
              manifest_dataset(read_manifest(mixed), InstrumentQuantity::kTarget);
            }).find("every file of a run must hold the same quantity"),
            std::string::npos);
  const std::string sample_without_angles = manifest_with("noangles.csv", "run_001.asd,sample,,,,");
  EXPECT_NE(error_of([&] { read_manifest(sample_without_angles); }).find(":2:"), std::string::npos);
  const std::string unmatched =
      manifest_with("unmatched.csv", "run_white.asd,white,10,45,0,0\nrun_001.asd,sample,0,45,0,0");
  EXPECT_NE(error_of([&] {
              manifest_calibration_input(read_manifest(unmatched));
            }).find("no white reference row at the geometry of sample"),
            std::string::npos);
}

TEST(Manifest, RawCountsWithDifferentSettingsAreRefused) {
  const Manifest m = read_manifest(dir() + "run_settings_mismatch.csv");
  EXPECT_EQ(error_of([&] { manifest_calibration_input(m); }),
            dir() +
                "run_settings_mismatch.csv:3: sample run_001.asd was measured with integration time [ms] 68, its "
                "white reference white_it34.asd with 34: raw counts taken with different settings cannot be "
                "divided (roadbrdf applies no DN normalization)");
}

}  // namespace
}  // namespace roadbrdf
