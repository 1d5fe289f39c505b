// Solar spectra and SPECTRL2 against independent references: the published ASTM G173-03 integrals and
// the output of NREL's original spectrl2_2.c (data/third-party/solar/spectrl2-reference-output.csv).
#include "roadbrdf/albedo/solar.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"

namespace roadbrdf::albedo {
namespace {

TEST(AstmG173, PublishedIntegrals) {
  // ASTM G173-03: global tilt 1000.4 W/m2, direct + circumsolar 900.1 W/m2 (trapezoid on the native grid).
  EXPECT_NEAR(integrate_spectrum(astm_g173("global")), 1000.4, 0.2);
  EXPECT_NEAR(integrate_spectrum(astm_g173("direct")), 900.1, 0.2);
}

TEST(Spectrl2, ReproducesNrelReferenceOutput) {
  Spectrl2Input in;
  in.zenith_deg = 47.912086486816406;
  in.relative_airmass = 1.4899535986910446;
  in.pressure_pa = 101300.0;
  in.ozone_atm_cm = 0.344;
  in.water_cm = 1.42;
  in.aod500 = 0.1;
  in.ground_albedo = 0.2;
  in.day_of_year = 75;
  const Spectrl2Output out = spectrl2(in);
  std::ifstream file(data_file("third-party/solar/spectrl2-reference-output.csv"));
  ASSERT_TRUE(file.good());
  std::string line;
  std::getline(file, line);  // header: ,wavelength,specdif,specdir,specetr,specglo (um, W m^-2 um^-1)
  std::size_t i = 0;
  double worst_dif = 0.0, worst_dir = 0.0, worst_glo = 0.0;
  while (std::getline(file, line)) {
    if (line.empty()) continue;
    std::stringstream ss(line);
    std::vector<double> v;
    std::string cell;
    while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 6u);
    ASSERT_LT(i, out.wavelengths.size());
    EXPECT_NEAR(out.wavelengths[i], v[1] * 1000.0, 1e-3);
    // um -> nm: W m^-2 um^-1 / 1000 = W m^-2 nm^-1.
    worst_dif = std::max(worst_dif, std::fabs(out.diffuse[i] - v[2] / 1000.0));
    worst_dir = std::max(worst_dir, std::fabs(out.direct_normal[i] - v[3] / 1000.0));
    worst_glo = std::max(worst_glo, std::fabs(out.global[i] - v[5] / 1000.0));
    ++i;
  }
  EXPECT_EQ(i, 122u);
  EXPECT_LT(worst_dif, 1e-4);
  EXPECT_LT(worst_dir, 1e-4);
  EXPECT_LT(worst_glo, 1e-4);
  RecordProperty("worst_diffuse", std::to_string(worst_dif));
  std::printf("SPECTRL2 max |diff| W m^-2 nm^-1: diffuse %.3g direct %.3g global %.3g\n", worst_dif, worst_dir,
              worst_glo);
}

TEST(Spectrl2, KastenYoungAirmassOfTheReferenceCase) {
  // The reference case's air mass (pvlib test input, computed by NREL solpos with Kasten & Young 1989).
  EXPECT_NEAR(kasten_young_airmass(47.912086486816406), 1.4899536, 2e-6);
}

TEST(Spectrl2, ParsesSettingsAndRejectsUnknown) {
  const Spectrl2Input in = parse_spectrl2_spec("spectrl2:aod=0.3,water=2,ozone=0.3,pressure=90000");
  EXPECT_DOUBLE_EQ(in.aod500, 0.3);
  EXPECT_DOUBLE_EQ(in.water_cm, 2.0);
  EXPECT_DOUBLE_EQ(in.pressure_pa, 90000.0);
  EXPECT_THROW(parse_spectrl2_spec("spectrl2:foo=1"), InputError);
  EXPECT_THROW(parse_spectrl2_spec("smarts"), InputError);
}

TEST(SpectralWeighting, ConstantAlbedoAndOutsideFraction) {
  const spectra::Spectrum g = astm_g173("global");
  const WeightedValue w = spectral_weighted_mean({280.0, 4000.0}, {0.3, 0.3}, {}, g);
  EXPECT_NEAR(w.value, 0.3, 1e-12);
  EXPECT_NEAR(w.fraction_outside, 0.0, 1e-12);
  // Half the range: the outside fraction is the energy above 1000 nm, computed independently here.
  const WeightedValue h = spectral_weighted_mean({280.0, 1000.0}, {0.2, 0.2}, {}, g);
  double inside = 0.0, total = 0.0;
  const std::vector<double>& wl = g.wavelengths();
  const std::vector<double>& e = g.values();
  for (std::size_t k = 1; k < wl.size(); ++k) {
    const double seg = 0.5 * (e[k] + e[k - 1]) * (wl[k] - wl[k - 1]);
    total += seg;
    if (wl[k] <= 1000.0) inside += seg;
  }
  EXPECT_NEAR(h.fraction_outside, 1.0 - inside / total, 1e-9);
  EXPECT_NEAR(h.value, 0.2, 1e-12);
}

}  // namespace
}  // namespace roadbrdf::albedo
