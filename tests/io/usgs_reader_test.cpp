// USGS splib07a ASCII reader (src/roadbrdf/io/usgs.h) on small synthetic files written here.
// The layout mimics the library's files (a title line " splib07a Record=N: title", then one value per
// line in %15.7e with a leading blank; wavelengths in micrometres in a separate file); every expected
// value below is typed in from the text of the file it is read from, not computed by the reader.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/io/usgs.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

// Four channels; the wavelengths are the single-precision values the real ASD wavelength file holds
// for 350, 351, 352 and 353 nm (3.4999999e-001 is 0.35 um stored as a float).
constexpr const char* kWavelengths =
    " splib07a Record=23: Wavelengths ASD 0.35-2.5 microns 2151 ch\n"
    " 3.4999999e-001\n"
    " 3.5100001e-001\n"
    " 3.5200000e-001\n"
    " 3.5299999e-001\n";

constexpr const char* kSpectrum =
    " splib07a Record=2257: Calcite GDS304 75-150um      ASDFRb AREF\n"
    " 7.9968947e-001\n"
    " 7.9973865e-001\n"
    " 7.9986185e-001\n"
    " 8.0005091e-001\n";

std::string write_scratch(const std::string& name, const std::string& content) {
  const std::string path = test::scratch_path(name);
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

// The FileError of parsing (spectrum, wavelengths), or a failure when nothing is thrown.
FileError error_of(const std::string& spectrum, const std::string& wavelengths) {
  try {
    parse_usgs_spectrum(spectrum, "s.txt", wavelengths, "w.txt");
  } catch (const FileError& e) {
    return e;
  }
  ADD_FAILURE() << "no FileError";
  return FileError("(none)", 0, 0, "(no error)");
}

TEST(UsgsReader, ValuesTitleAndRecords) {
  const UsgsSpectrum s = parse_usgs_spectrum(kSpectrum, "s.txt", kWavelengths, "w.txt");
  EXPECT_EQ(s.record, 2257);
  EXPECT_EQ(s.title, "Calcite GDS304 75-150um      ASDFRb AREF");
  EXPECT_EQ(s.wavelength_record, 23);
  EXPECT_EQ(s.wavelength_title, "Wavelengths ASD 0.35-2.5 microns 2151 ch");
  EXPECT_EQ(s.channels, 4u);
  EXPECT_EQ(s.missing, 0u);
  ASSERT_EQ(s.wavelengths.size(), 4u);
  ASSERT_EQ(s.reflectance.size(), 4u);
  // Single-precision micrometres become whole nanometres (rounded to 1e-3 nm).
  EXPECT_EQ(s.wavelengths[0], 350.0);
  EXPECT_EQ(s.wavelengths[1], 351.0);
  EXPECT_EQ(s.wavelengths[2], 352.0);
  EXPECT_EQ(s.wavelengths[3], 353.0);
  EXPECT_EQ(s.reflectance[0], 7.9968947e-001);
  EXPECT_EQ(s.reflectance[3], 8.0005091e-001);
  EXPECT_EQ(s.path, "s.txt");
  EXPECT_EQ(s.wavelength_path, "w.txt");
}

TEST(UsgsReader, JsonHoldsTheValuesOfTheFiles) {
  const nlohmann::json j = parse_usgs_spectrum(kSpectrum, "s.txt", kWavelengths, "w.txt").to_json();
  EXPECT_EQ(j.at("record"), 2257);
  EXPECT_EQ(j.at("wavelength_record"), 23);
  EXPECT_EQ(j.at("title"), "Calcite GDS304 75-150um      ASDFRb AREF");
  EXPECT_EQ(j.at("wavelengths"), nlohmann::json({350.0, 351.0, 352.0, 353.0}));
  EXPECT_EQ(j.at("reflectance").at(1), 7.9973865e-001);
  EXPECT_EQ(j.at("channels"), 4);
  EXPECT_EQ(j.at("missing"), 0);
  EXPECT_EQ(j.at("path"), "s.txt");
  EXPECT_EQ(j.at("wavelength_path"), "w.txt");
}

TEST(UsgsReader, WavelengthsAreRoundedToAThousandthOfANanometre) {
  // Beckman-like channels that are not whole nanometres: 0.21310002 um = 213.10002 nm -> 213.1,
  // 1.2345678 um = 1234.5678 nm -> 1234.568 (rounded half up at the fourth decimal).
  const std::string w = " splib07a Record=18: Wavelengths BECK\n 2.0510000e-001\n 2.1310002e-001\n 1.2345678e+000\n";
  const std::string s = " splib07a Record=1: x\n 0.1\n 0.2\n 0.3\n";
  const UsgsSpectrum u = parse_usgs_spectrum(s, "s.txt", w, "w.txt");
  ASSERT_EQ(u.wavelengths.size(), 3u);
  EXPECT_DOUBLE_EQ(u.wavelengths[0], 205.1);
  EXPECT_DOUBLE_EQ(u.wavelengths[1], 213.1);
  EXPECT_DOUBLE_EQ(u.wavelengths[2], 1234.568);
}

TEST(UsgsReader, MissingChannelsOfEitherFileAreDropped) {
  // Channel 2 deleted in the spectrum, channel 4 in the wavelength file (-1.23e+34, the library's marker).
  const std::string s = " splib07a Record=7: x\n 1.0000000e-001\n-1.2300000e+034\n 3.0000000e-001\n 4.0000000e-001\n";
  const std::string w = " splib07a Record=8: w\n 0.40\n 0.50\n 0.60\n-1.23e+34\n";
  const UsgsSpectrum u = parse_usgs_spectrum(s, "s.txt", w, "w.txt");
  EXPECT_EQ(u.channels, 4u);
  EXPECT_EQ(u.missing, 2u);
  ASSERT_EQ(u.wavelengths.size(), 2u);
  EXPECT_EQ(u.wavelengths[0], 400.0);
  EXPECT_EQ(u.wavelengths[1], 600.0);
  EXPECT_EQ(u.reflectance[0], 0.1);
  EXPECT_EQ(u.reflectance[1], 0.3);
}

TEST(UsgsReader, BlankLinesAndCarriageReturnsAreAccepted) {
  const std::string s = " splib07a Record=7: x\r\n 0.25\r\n\r\n 0.5\r\n\r\n";
  const std::string w = " splib07a Record=8: w\r\n 1.0\r\n 2.0\r\n";
  const UsgsSpectrum u = parse_usgs_spectrum(s, "s.txt", w, "w.txt");
  ASSERT_EQ(u.reflectance.size(), 2u);
  EXPECT_EQ(u.reflectance[1], 0.5);
  EXPECT_EQ(u.wavelengths[1], 2000.0);
}

TEST(UsgsReader, BadTitleNamesFileLineAndColumn) {
  const FileError e = error_of("Calcite reflectance\n 0.5\n", kWavelengths);
  EXPECT_EQ(e.file(), "s.txt");
  EXPECT_EQ(e.line(), 1);
  EXPECT_EQ(e.column(), 1);
  EXPECT_NE(std::string(e.what()).find("s.txt:1:1: not a USGS splib07a ASCII file"), std::string::npos) << e.what();

  // A record that is not a number: the column of the text after "Record=" (leading blank + 16 characters).
  const FileError r = error_of(kSpectrum, " splib07a Record=abc: w\n 0.35\n");
  EXPECT_EQ(r.file(), "w.txt");
  EXPECT_EQ(r.line(), 1);
  EXPECT_EQ(r.column(), 18);
}

TEST(UsgsReader, BadValueNamesFileLineAndColumn) {
  const std::string s = " splib07a Record=7: x\n 0.1\n   0.2x\n 0.3\n 0.4\n";
  const FileError e = error_of(s, kWavelengths);
  EXPECT_EQ(e.file(), "s.txt");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.column(), 4);
  EXPECT_NE(std::string(e.what()).find("s.txt:3:4: '0.2x' is not a number"), std::string::npos) << e.what();

  // Two values on one line are not the library's layout.
  const FileError two = error_of(" splib07a Record=7: x\n 0.1 0.2\n", " splib07a Record=8: w\n 0.4\n");
  EXPECT_EQ(two.line(), 2);
  EXPECT_EQ(two.column(), 2);
}

TEST(UsgsReader, MismatchedChannelCountsNameTheFirstExtraValue) {
  // Spectrum of 5 values against 4 wavelengths: the error is at the spectrum's fifth value (line 6).
  const std::string five = std::string(kSpectrum) + " 0.9\n";
  const FileError e = error_of(five, kWavelengths);
  EXPECT_EQ(e.file(), "s.txt");
  EXPECT_EQ(e.line(), 6);
  const std::string what = e.what();
  EXPECT_NE(what.find("5 values but the wavelength file has 4 (w.txt)"), std::string::npos) << what;

  // The other way round: the wavelength file is longer.
  const std::string w5 = std::string(kWavelengths) + "\n 3.5399999e-001\n";
  const FileError f = error_of(kSpectrum, w5);
  EXPECT_EQ(f.file(), "w.txt");
  EXPECT_EQ(f.line(), 7);  // after a blank line 6
  EXPECT_NE(std::string(f.what()).find("5 values but the spectrum has 4 (s.txt)"), std::string::npos) << f.what();
}

TEST(UsgsReader, WavelengthsMustIncreaseAndBePositive) {
  const std::string s = " splib07a Record=7: x\n 0.1\n 0.2\n 0.3\n";
  const FileError e = error_of(s, " splib07a Record=8: w\n 0.5\n 0.6\n 0.6\n");
  EXPECT_EQ(e.file(), "w.txt");
  EXPECT_EQ(e.line(), 4);
  EXPECT_NE(std::string(e.what()).find("wavelengths must increase"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("on line 3"), std::string::npos) << e.what();

  const FileError z = error_of(s, " splib07a Record=8: w\n 0.0\n 0.6\n 0.7\n");
  EXPECT_EQ(z.line(), 2);
  EXPECT_NE(std::string(z.what()).find("must be > 0"), std::string::npos) << z.what();
  // A wavelength too large to be a spectrometer channel (and infinite once in nanometres): refused.
  const FileError h = error_of(s, " splib07a Record=8: w\n 0.5\n 0.6\n 1e303\n");
  EXPECT_EQ(h.line(), 4);
  EXPECT_NE(std::string(h.what()).find("must be > 0 and < 1e6"), std::string::npos) << h.what();
}

TEST(UsgsReader, EmptyFileAndTitleOnly) {
  const FileError e = error_of("", kWavelengths);
  EXPECT_EQ(e.file(), "s.txt");
  EXPECT_NE(std::string(e.what()).find("empty file"), std::string::npos) << e.what();
  const FileError t = error_of(" splib07a Record=7: x\n\n", kWavelengths);
  EXPECT_NE(std::string(t.what()).find("no values after the title line"), std::string::npos) << t.what();
}

TEST(UsgsReader, ReadsFilesAndNamesAMissingOne) {
  const std::string s = write_scratch("usgs_spectrum.txt", kSpectrum);
  const std::string w = write_scratch("usgs_wavelengths.txt", kWavelengths);
  const UsgsSpectrum u = read_usgs_spectrum(s, w);
  EXPECT_EQ(u.path, s);
  EXPECT_EQ(u.wavelength_path, w);
  EXPECT_EQ(u.reflectance[1], 7.9973865e-001);
  try {
    read_usgs_spectrum(s, test::scratch_path("no_such_wavelengths.txt"));
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_wavelengths.txt"), std::string::npos) << e.what();
  }
}

TEST(UsgsReader, DatasetIsReflectanceOverPiAtTheStatedGeometry) {
  const UsgsSpectrum u = parse_usgs_spectrum(kSpectrum, "s.txt", kWavelengths, "w.txt");
  const Geometry g = geometry_from_degrees(30.0, 0.0, 0.0, 0.0);
  const SpectralDataset d = usgs_dataset(u, g, AngleConvention::kZenithAzimuth);
  ASSERT_EQ(d.geometries.size(), 1u);
  EXPECT_DOUBLE_EQ(d.geometries[0].theta_i, 30.0 * std::numbers::pi / 180.0);
  EXPECT_EQ(d.geometries[0].theta_r, 0.0);
  ASSERT_EQ(d.wavelengths.size(), 4u);
  ASSERT_EQ(d.brdf.size(), 4u);
  // A Lambertian surface of reflectance factor R has BRDF R / pi.
  EXPECT_DOUBLE_EQ(d.brdf[0], 7.9968947e-001 / std::numbers::pi);
  EXPECT_DOUBLE_EQ(d.brdf[3], 8.0005091e-001 / std::numbers::pi);
  EXPECT_EQ(d.metadata.at("usgs.record"), "2257");
  EXPECT_EQ(d.metadata.at("usgs.quantity"), "reflectance factor / pi");
  EXPECT_EQ(d.metadata.at("usgs.missing_channels"), "0");

  // Every channel deleted: no dataset, and the file is named.
  const UsgsSpectrum none =
      parse_usgs_spectrum(" splib07a Record=7: x\n-1.23e+34\n", "gone.txt", " splib07a Record=8: w\n 0.4\n", "w.txt");
  EXPECT_EQ(none.missing, 1u);
  try {
    usgs_dataset(none, g, AngleConvention::kZenithAzimuth);
    ADD_FAILURE() << "no error for a spectrum without channels";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("gone.txt: every channel is missing"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace roadbrdf
