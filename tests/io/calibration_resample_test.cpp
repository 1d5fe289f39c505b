// Calibration against a reference panel and spectral band averaging.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/io/calibration.h"
#include "roadbrdf/io/resample.h"
#include "roadbrdf/spectra/spectrum_file.h"

namespace roadbrdf {
namespace {

const std::string kSpectralon = roadbrdf::data_directory() + "/third-party/spectralon/Spectralon_Num4.txt";

// The calibration file parsed here, independently of spectra::read_spectrum.
std::map<int, std::pair<double, double>> spectralon_table() {
  std::ifstream in(kSpectralon);
  std::map<int, std::pair<double, double>> t;
  double wl, rho, s;
  while (in >> wl >> rho >> s) t[static_cast<int>(wl)] = {rho, s};
  return t;
}

SpectralDataset radiances(const std::vector<double>& wavelengths, double scale, int geometries) {
  SpectralDataset d;
  d.wavelengths = wavelengths;
  for (int g = 0; g < geometries; ++g) {
    d.geometries.push_back(geometry_from_degrees(10.0 * g, 0.0, 30.0, 180.0));
    for (std::size_t j = 0; j < wavelengths.size(); ++j)
      d.brdf.push_back(scale * (1.0 + 0.001 * wavelengths[j]) * (g + 1));
  }
  return d;
}

TEST(Calibration, LambertianPanelAgainstItselfGivesRhoOverPi) {
  const auto table = spectralon_table();
  ASSERT_EQ(table.size(), 2151u);
  const std::vector<double> wl = {350, 351, 500, 1000, 1400, 2000, 2500};
  CalibrationInput in;
  // A Lambertian panel: its radiance is E rho/pi at every geometry; the same panel is the reference.
  in.sample = radiances(wl, 1000.0, 4);
  in.reference = in.sample;
  SpectralDataset dark = radiances(wl, 0.0, 1);  // one dark row for every geometry
  for (auto& v : dark.brdf) v = 3.0;
  in.dark = dark;
  in.panel_reflectance = spectra::read_spectrum(kSpectralon);
  const SpectralDataset f = calibrate(in);
  ASSERT_EQ(f.geometry_count(), 4u);
  ASSERT_TRUE(f.has_sigma());  // the panel's calibration uncertainty propagates
  for (std::size_t g = 0; g < 4; ++g) {
    for (std::size_t j = 0; j < wl.size(); ++j) {
      const auto [rho, s] = table.at(static_cast<int>(wl[j]));
      EXPECT_NEAR(f.value(g, j), rho / std::numbers::pi, 1e-15);
      EXPECT_NEAR(f.sigma[g * wl.size() + j], s / std::numbers::pi, 1e-15);
    }
  }
}

TEST(Calibration, InterpolatesTheReferenceAndPropagatesRadianceUncertainty) {
  const auto table = spectralon_table();
  const std::vector<double> wl = {500.5};
  CalibrationInput in;
  in.sample = radiances(wl, 0.0, 1);
  in.sample.brdf = {50.0};
  in.sample.sigma = {2.0};
  in.reference = radiances(wl, 0.0, 1);
  in.reference.brdf = {200.0};
  in.reference.sigma = {4.0};
  const spectra::Spectrum panel = spectra::read_spectrum(kSpectralon);
  in.panel_reflectance = spectra::Spectrum(panel.name(), panel.wavelengths(), panel.values());  // without sigma
  const double rho = 0.5 * (table.at(500).first + table.at(501).first);  // linear interpolation at 500.5 nm
  const double c = rho / std::numbers::pi;
  const SpectralDataset f = calibrate(in);
  EXPECT_NEAR(f.value(0, 0), 0.25 * c, 1e-15);
  // sigma_f^2 = (c/D)^2 s_s^2 + (c N/D^2)^2 s_r^2 with N = 50, D = 200.
  const double expected = std::sqrt(std::pow(c / 200.0 * 2.0, 2) + std::pow(c * 50.0 / 40000.0 * 4.0, 2));
  EXPECT_NEAR(f.sigma[0], expected, 1e-15);
}

TEST(Calibration, RefusesExtrapolationAndBadReference) {
  CalibrationInput in;
  in.sample = radiances({340.0, 400.0}, 1.0, 1);
  in.reference = in.sample;
  in.panel_reflectance = spectra::read_spectrum(kSpectralon);
  try {
    calibrate(in);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no extrapolation"), std::string::npos) << e.what();
  }
  in.sample = radiances({400.0}, 1.0, 1);
  in.reference = radiances({400.0}, 1.0, 1);
  SpectralDataset dark = radiances({400.0}, 1.0, 1);
  in.dark = dark;  // reference equal to dark
  EXPECT_THROW(calibrate(in), InputError);
  in.dark.reset();
  in.reference = radiances({410.0}, 1.0, 1);
  EXPECT_THROW(calibrate(in), InputError);  // wavelengths differ
}

TEST(Calibration, OneColumnPanelBrf) {
  const std::string path = roadbrdf::data_directory() + "/third-party/spectralon/BRF_i10_e0.txt";
  spectra::SpectrumReadOptions o;
  o.first_wavelength = 350;
  o.step = 1;
  const spectra::Spectrum brf = spectra::read_spectrum(path, o);
  ASSERT_EQ(brf.values().size(), 2151u);
  EXPECT_EQ(brf.wavelengths().back(), 2500.0);
  EXPECT_THROW(spectra::read_spectrum(path), FileError);  // the grid must be stated
}

TEST(Resample, BandAveragesMatchHandComputedIntegrals) {
  // Samples 1, 3, 2, 2, 6 at 400..420 nm. Integrals of the linear interpolant by hand:
  //   [400, 410]: 5 (1+3)/2 + 5 (3+2)/2 = 22.5        -> 2.25
  //   [410, 420]: 5 (2+2)/2 + 5 (2+6)/2 = 30          -> 3.0
  //   [402, 412]: f(402) = 1.8, f(412) = 2: 3 (1.8+3)/2 + 12.5 + 2 (2+2)/2 = 23.7 -> 2.37
  SpectralDataset d;
  d.wavelengths = {400, 405, 410, 415, 420};
  d.geometries = {geometry_from_degrees(0, 0, 30, 180)};
  d.brdf = {1, 3, 2, 2, 6};
  d.sigma = {0.1, 0.1, 0.1, 0.1, 0.1};
  const SpectralDataset r =
      resample_dataset(d, bands_from_edges(parse_range_list("400:420:10", "edges", wavelength_rules())));
  ASSERT_EQ(r.wavelengths, (std::vector<double>{405, 415}));
  EXPECT_NEAR(r.value(0, 0), 2.25, 1e-14);
  EXPECT_NEAR(r.value(0, 1), 3.0, 1e-14);
  // Weights of [400, 410]: 0.25, 0.5, 0.25 -> sigma = 0.1 sqrt(0.0625 + 0.25 + 0.0625).
  EXPECT_NEAR(r.sigma[0], 0.1 * std::sqrt(0.375), 1e-15);
  WavelengthBands shifted;
  shifted.lower = {402};
  shifted.upper = {412};
  EXPECT_NEAR(resample_dataset(d, shifted).value(0, 0), 2.37, 1e-14);
  // Not a point pick: the value at the centre 405 nm is 3, the band average 2.25.
  EXPECT_THROW(resample_dataset(d, bands_from_edges({395, 405})), InputError);  // outside: no extrapolation
  const SpectralDataset dropped =
      resample_dataset(d, bands_from_edges(parse_range_list("400:420:5", "edges", wavelength_rules())), {{411, 413}});
  EXPECT_EQ(dropped.wavelengths, (std::vector<double>{402.5, 407.5, 417.5}));
  EXPECT_EQ(dropped.metadata.at("dropped_bands"), "410-415");
}

TEST(MissingValues, CalibrationKeepsAMissingRadianceMissing) {
  const std::vector<double> wl = {500, 600, 700};
  CalibrationInput in;
  in.sample = radiances(wl, 1000.0, 2);
  in.reference = radiances(wl, 2000.0, 1);
  in.sample.value(1, 2) = std::numeric_limits<double>::quiet_NaN();     // sample not measured
  in.reference.value(0, 0) = std::numeric_limits<double>::quiet_NaN();  // reference not measured at 500 nm
  in.panel_reflectance = spectra::read_spectrum(kSpectralon);
  const SpectralDataset out = calibrate(in);
  const auto table = spectralon_table();
  EXPECT_TRUE(std::isnan(out.value(0, 0)));
  EXPECT_TRUE(std::isnan(out.value(1, 0)));
  EXPECT_TRUE(std::isnan(out.value(1, 2)));
  // The measured cells: (1000 (g+1) / 2000) rho / pi.
  EXPECT_NEAR(out.value(0, 1), 0.5 * table.at(600).first / std::numbers::pi, 1e-12);
  EXPECT_NEAR(out.value(1, 1), 1.0 * table.at(600).first / std::numbers::pi, 1e-12);
  EXPECT_NEAR(out.value(0, 2), 0.5 * table.at(700).first / std::numbers::pi, 1e-12);
}

TEST(MissingValues, ResampledBandTouchingAMissingSampleIsMissing) {
  SpectralDataset d;
  d.wavelengths = {400, 405, 410, 415, 420};
  d.geometries = {geometry_from_degrees(0, 0, 30, 180)};
  d.brdf = {1, std::numeric_limits<double>::quiet_NaN(), 2, 2, 6};
  const SpectralDataset r =
      resample_dataset(d, bands_from_edges(parse_range_list("400:420:10", "edges", wavelength_rules())));
  EXPECT_TRUE(std::isnan(r.value(0, 0)));  // [400, 410] needs 405 nm: not invented
  EXPECT_NEAR(r.value(0, 1), 3.0, 1e-14);  // [410, 420] does not (see the hand integrals above)
}

}  // namespace
}  // namespace roadbrdf
