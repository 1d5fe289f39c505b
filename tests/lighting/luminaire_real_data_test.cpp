// Real luminaire files (../shared/real-data/luminaires, PROVENANCE.md there; never copied into the
// repository): skipped with a message when that folder is absent.
// - The ten EULUMDAT files of eulumdat-luminance against the luminance tables Relux computed from
//   them (relux_reference.json): L(C, gamma) = I(C, gamma) / projected luminous area, C 0-345 by 15,
//   gamma 65-85 by 5, within the stated 3 % (values above 10 cd/m^2; below, 10 cd/m^2 absolute).
// - The flux integrated from the intensities against each file's header.
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/lighting/luminaire_file.h"
#include "roadbrdf/lighting/luminaire_flux.h"
#include "roadbrdf/lighting/luminaire_request.h"
#include "support/paths.h"

namespace roadbrdf::lighting {
namespace {

std::string luminaires_dir() {
  const std::string shared = test::shared_real_data_dir();
  return shared.empty() ? std::string() : shared + "/luminaires";
}

#define REQUIRE_REAL_DATA(folder)                                                                                 \
  if (luminaires_dir().empty()) GTEST_SKIP() << "../shared/real-data/luminaires is absent: real luminaire files"; \
  const std::string folder = luminaires_dir()

TEST(LuminaireRealData, ReluxLuminanceTablesOfTheTenEulumdatFiles) {
  REQUIRE_REAL_DATA(dir);
  const std::string reference_path = dir + "/eulumdat-luminance-MIT/relux_reference.json";
  const Json reference = parse_json_file(reference_path);
  const JsonNode root(reference, reference_path);
  const double relative = root.at("tolerance").at("relative_percent").number() / 100.0;
  const double absolute = root.at("tolerance").at("absolute_cd_m2").number();
  const JsonNode c_planes = root.at("grid").at("c_planes_deg");
  const JsonNode gammas = root.at("grid").at("g_angles_deg");
  int compared = 0;
  for (const auto& [sample, entry] : root.at("samples").members()) {
    Diagnostics diag;
    const Luminaire lum = read_luminaire(dir + "/eulumdat-luminance-MIT/" + sample + ".ldt", diag);
    EXPECT_EQ(lum.metadata["symmetry_indicator"].get<double>(), entry.at("isym").number()) << sample;
    double worst = 0.0;
    for (std::size_t j = 0; j < gammas.size(); ++j) {
      const double gamma = gammas[j].number();
      const JsonNode row = entry.at("table").at(fmt::format("{:g}", gamma));
      for (std::size_t i = 0; i < c_planes.size(); ++i) {
        const double c = c_planes[i].number();
        const double expected = row[i].number();
        const double luminance = lum.distribution.intensity(c, gamma) / lum.luminous_area.projected_m2(c, gamma);
        const double tolerance = expected > absolute ? relative * expected : absolute;
        EXPECT_NEAR(luminance, expected, tolerance) << sample << " C " << c << " gamma " << gamma;
        if (expected > absolute) worst = std::max(worst, std::abs(luminance / expected - 1.0));
        ++compared;
      }
    }
    std::printf("%s: largest relative difference to Relux %.3f %%\n", sample.c_str(), 100.0 * worst);
  }
  EXPECT_EQ(compared, 10 * 24 * 5);
}

TEST(LuminaireRealData, IntegratedFluxAgainstEachHeader) {
  REQUIRE_REAL_DATA(dir);
  // EULUMDAT: lamp flux x LORL; every file of the folder within 2 %, so without a flux_mismatch warning.
  for (const std::string name : {"eulumdat-luminance-MIT/sample_01.ldt", "eulumdat-luminance-MIT/sample_02.ldt",
                                 "eulumdat-luminance-MIT/sample_03.ldt", "eulumdat-luminance-MIT/sample_04.ldt",
                                 "eulumdat-luminance-MIT/sample_05.ldt", "eulumdat-luminance-MIT/sample_06.ldt",
                                 "eulumdat-luminance-MIT/sample_07.ldt", "eulumdat-luminance-MIT/sample_08.ldt",
                                 "eulumdat-luminance-MIT/sample_09.ldt", "eulumdat-luminance-MIT/sample_10.ldt",
                                 "eulumdat-rs-AGPL3/road_luminaire.ldt"}) {
    LuminaireRequest request;
    request.file = dir + "/" + name;
    const LuminaireSummary s = luminaire_summary(request);
    const double header =
        s.luminaire.lamp_flux_lm * s.luminaire.metadata["light_output_ratio_percent"].get<double>() / 100.0;
    EXPECT_NEAR(s.flux.total_lm(), header, 0.02 * header) << name;
    EXPECT_FALSE(s.diagnostics.has_warning("flux_mismatch")) << name;
    std::printf("%s: integrated %.1f lm, header %.1f lm (%+.2f %%)\n", name.c_str(), s.flux.total_lm(), header,
                100.0 * (s.flux.total_lm() / header - 1.0));
  }
  // The 60 W roadway luminaire (LM-63-1995): 1 lamp of 9155.7 lm, LED, so the luminaire's own flux.
  {
    LuminaireRequest request;
    request.file = dir + "/eulumdat-rs-AGPL3/outdoor-roadway-60W-4000K.ies";
    const LuminaireSummary s = luminaire_summary(request);
    EXPECT_NEAR(s.flux.total_lm(), 9155.7, 0.02 * 9155.7);
    EXPECT_FALSE(s.diagnostics.has_warning("flux_mismatch"));
    std::printf("outdoor roadway: integrated %.1f lm, header 9155.7 lm\n", s.flux.total_lm());
  }
  // The Hella luminaire (IESNA91): the header says 1000 lm lamps, but the intensities are those of
  // its 2070 lm lamp ([LAMP] "Testlampe 2070 lm"): the integral finds 2070 lm and the reader warns.
  {
    LuminaireRequest request;
    request.file = dir + "/tuberlin-roadrad/HellaEcoLight_2070lm_LDT.ies";
    const LuminaireSummary s = luminaire_summary(request);
    EXPECT_NEAR(s.flux.total_lm(), 2070.0, 0.02 * 2070.0);
    EXPECT_TRUE(s.diagnostics.has_warning("flux_mismatch"));
    EXPECT_EQ(s.luminaire.distribution.c_deg.size(), 360u);
    EXPECT_EQ(s.luminaire.distribution.gamma_deg.size(), 131u);
    std::printf("Hella: integrated %.1f lm, lamp 2070 lm by its name\n", s.flux.total_lm());
  }
  // The headlamp: relative, 1000 lm: a light output ratio below 1, no warning.
  {
    LuminaireRequest request;
    request.file = dir + "/tuberlin-roadrad/HeadLight.ies";
    const LuminaireSummary s = luminaire_summary(request);
    EXPECT_LT(s.flux.total_lm(), 1000.0);
    EXPECT_GT(s.dlor, 0.0);
    EXPECT_TRUE(s.diagnostics.warnings.empty());
  }
}

}  // namespace
}  // namespace roadbrdf::lighting
