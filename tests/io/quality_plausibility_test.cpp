// Implausible input caught with the right advice, on small synthetic files in the shapes real data
// came in: a BRDF three orders of magnitude too dark (check, albedo, rtable), values stored as
// BRDF x cos theta_i, a smooth ramp falling into the noise that must not produce a list of outliers,
// the specular window as an angle, a bounded outlier list, and the repeatability of duplicate scans.
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "roadbrdf/albedo/report.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/quality.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/photometry/rtable_request.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

bool any_contains(const std::vector<std::string>& lines, const std::string& text) {
  for (const auto& l : lines) {
    if (l.find(text) != std::string::npos) return true;
  }
  return false;
}

// A zenith-convention dataset of a BRDF f(g) at two wavelengths, on a grid with reciprocity pairs:
// theta_i, theta_r in {0, 20, 40, 60, 75}, dphi in {0, 90, 180}.
template <class F>
SpectralDataset grid_dataset(F f) {
  SpectralDataset d;
  d.wavelengths = {500.0, 600.0};
  for (double ti : {0.0, 20.0, 40.0, 60.0, 75.0}) {
    for (double tr : {0.0, 20.0, 40.0, 60.0, 75.0}) {
      for (double dphi : {0.0, 90.0, 180.0}) {
        if ((ti == 0.0 || tr == 0.0) && dphi != 0.0) continue;
        const Geometry g = geometry_from_degrees(ti, 0.0, tr, dphi);
        d.geometries.push_back(g);
        for (std::size_t j = 0; j < 2; ++j) d.brdf.push_back(f(g));
      }
    }
  }
  return d;
}

// The measured asphalt table's shape: a Lambertian-like BRDF of 2e-5 sr^-1 (pi f = 6.3e-5, below 0.005).
TEST(Plausibility, BrdfThreeOrdersOfMagnitudeTooDarkIsWarnedAbout) {
  const QualityReport dark = check_dataset(grid_dataset([](const Geometry&) { return 2e-5; }));
  ASSERT_EQ(dark.scale.equivalent_albedo.size(), 2u);
  EXPECT_NEAR(dark.scale.equivalent_albedo[0], std::numbers::pi * 2e-5, 1e-15);
  EXPECT_EQ(dark.scale.below, 2u);
  EXPECT_TRUE(any_contains(dark.warnings, "Lambertian-equivalent albedo (pi x median BRDF) is below 0.005"));
  const QualityReport asphalt = check_dataset(grid_dataset([](const Geometry&) { return 0.05 / std::numbers::pi; }));
  EXPECT_EQ(asphalt.scale.below + asphalt.scale.above, 0u);
  EXPECT_TRUE(asphalt.warnings.empty());
  // A reflectance factor (pi BRDF) of 1.2 read as a BRDF: pi x 1.2 = 3.8 > 1.
  const QualityReport brf = check_dataset(grid_dataset([](const Geometry&) { return 1.2; }));
  EXPECT_EQ(brf.scale.above, 2u);
}

// Stored g = f cos theta_i with f reciprocal (Lambert): pairs disagree by cos ratio, agree once divided.
TEST(Plausibility, BrdfTimesCosThetaIIsRecognised) {
  const QualityReport times_cos =
      check_dataset(grid_dataset([](const Geometry& g) { return 0.1 / std::numbers::pi * g.cos_theta_i(); }));
  EXPECT_GT(times_cos.cosine_factor.pairs, 2u);
  EXPECT_TRUE(times_cos.cosine_factor.likely);
  EXPECT_NEAR(times_cos.cosine_factor.divided_disagreement, 0.0, 1e-12);
  EXPECT_GT(times_cos.cosine_factor.disagreement, 0.05);
  EXPECT_TRUE(any_contains(times_cos.warnings, "the values look like BRDF x cos theta_i"));
  // A reciprocal BRDF as stored: not flagged.
  const QualityReport brdf = check_dataset(grid_dataset([](const Geometry&) { return 0.1 / std::numbers::pi; }));
  EXPECT_FALSE(brdf.cosine_factor.likely);
  EXPECT_NEAR(brdf.cosine_factor.disagreement, 0.0, 1e-12);
}

// A monotone theta_i series (theta_r = 30 deg in the retro plane, theta_i = 0-89.5 deg by 0.5 deg)
// whose signal 0.1 cos(theta_i) falls into additive noise of 1e-3 towards grazing incidence: the
// relative noise grows from 1 % to over 100 %. Judged against the quiet start of the series, the end
// was a long list of "outliers"; judged against its own neighbours, at most a few.
SpectralDataset noisy_ramp() {
  SpectralDataset d;
  for (double wl = 500.0; wl <= 600.0; wl += 10.0) d.wavelengths.push_back(wl);
  NormalStream normal(17);
  for (double ti = 0.0; ti <= 89.5; ti += 0.5) {
    d.geometries.push_back(geometry_from_degrees(ti, 0.0, 30.0, 0.0));
    for (std::size_t j = 0; j < d.wavelengths.size(); ++j) {
      d.brdf.push_back(0.1 * std::cos(ti * kDegree) + 1e-3 * normal.next());
    }
  }
  return d;
}

TEST(QualityOutliers, SmoothRampFallingIntoTheNoiseIsNotAListOfOutliers) {
  const SpectralDataset d = noisy_ramp();
  const QualityReport r = check_dataset(d);
  EXPECT_LE(r.outliers.size(), 2u) << quality_report_text(d, r);
  // A real defect in the quiet part of the same ramp is still found: 2.5 x at theta_i = 20 deg.
  SpectralDataset planted = d;
  const std::size_t g = 40;  // theta_i = 20 deg
  ASSERT_NEAR(rad_to_deg(planted.geometries[g].theta_i), 20.0, 1e-9);
  for (std::size_t j = 0; j < planted.wavelengths.size(); ++j) planted.brdf[g * planted.wavelengths.size() + j] *= 2.5;
  const QualityReport p = check_dataset(planted);
  bool found = false;
  for (const auto& o : p.outliers) found = found || o.index == g;
  EXPECT_TRUE(found) << quality_report_text(planted, p);
}

// Forward plane at theta_i = 89 deg: the mirror direction is theta_r = 89 deg; theta_r = 64 deg is
// 25 deg from it (in-plane angles subtract), outside the default window of 10 deg, so a bright value
// there is an outlier, not "near the specular direction"; at theta_r = 85 deg (4 deg) it is a peak.
TEST(QualityOutliers, SpecularWindowIsAnAngleFromTheMirrorDirection) {
  SpectralDataset d;
  d.wavelengths = {500.0, 600.0};
  std::vector<double> views;
  for (double tr = 0.0; tr <= 88.0; tr += 2.0) views.push_back(tr);
  views.push_back(85.0);
  for (double ti : {85.0, 87.0, 89.0}) {
    for (double tr : views) {
      if (ti != 89.0 && tr == 85.0) continue;
      d.geometries.push_back(geometry_from_degrees(ti, 0.0, tr, 180.0));
      const bool bright = ti == 89.0 && (tr == 64.0 || tr == 85.0);
      d.brdf.push_back(bright ? 0.3 : 0.03);
      d.brdf.push_back(bright ? 0.3 : 0.03);
    }
  }
  const QualityReport r = check_dataset(d);
  auto index_of = [&](double ti, double tr) {
    for (std::size_t g = 0; g < d.geometries.size(); ++g) {
      if (std::fabs(rad_to_deg(d.geometries[g].theta_i) - ti) < 1e-9 &&
          std::fabs(rad_to_deg(d.geometries[g].theta_r) - tr) < 1e-9)
        return g;
    }
    return d.geometries.size();
  };
  bool outlier_64 = false, peak_85 = false;
  for (const auto& o : r.outliers) {
    if (o.index == index_of(89.0, 64.0)) {
      outlier_64 = true;
      EXPECT_NEAR(o.from_mirror_deg, 25.0, 1e-6);
    }
  }
  for (const auto& o : r.specular_peaks) {
    EXPECT_NE(o.index, index_of(89.0, 64.0));
    if (o.index == index_of(89.0, 85.0)) {
      peak_85 = true;
      EXPECT_NEAR(o.from_mirror_deg, 4.0, 1e-6);
    }
  }
  EXPECT_TRUE(outlier_64) << quality_report_text(d, r);
  EXPECT_TRUE(peak_85) << quality_report_text(d, r);
  EXPECT_NE(quality_report_text(d, r).find("within 10 deg of the mirror direction"), std::string::npos);
}

// Twelve planted outliers: the text lists five and says how many more; the JSON lists all.
TEST(QualityOutliers, TextListsTheFirstFewAndJsonAll) {
  SpectralDataset d;
  d.wavelengths = {500.0, 600.0};
  NormalStream normal(3);
  for (double ti = 0.0; ti <= 80.0; ti += 10.0) {
    for (double tr = 0.0; tr <= 80.0; tr += 10.0) {
      for (double dphi : {0.0, 45.0, 90.0, 135.0, 180.0}) {
        if ((ti == 0.0 || tr == 0.0) && dphi != 0.0) continue;
        d.geometries.push_back(geometry_from_degrees(ti, 0.0, tr, dphi));
        const double f = 0.1 * (1.0 + 0.005 * normal.next());
        d.brdf.push_back(f);
        d.brdf.push_back(f);
      }
    }
  }
  std::size_t planted = 0;
  for (std::size_t g = 5; g < d.geometries.size() && planted < 12; g += 20) {
    const Geometry& x = d.geometries[g];
    if (rad_to_deg(std::acos(std::clamp(dot(x.wr, mirror_direction(x.wi)), -1.0, 1.0))) < 20.0) continue;
    d.brdf[2 * g] *= 3.0;
    d.brdf[2 * g + 1] *= 3.0;
    ++planted;
  }
  ASSERT_EQ(planted, 12u);
  const QualityReport r = check_dataset(d);
  const std::size_t found = r.outliers.size();
  ASSERT_GE(found, 10u) << quality_report_text(d, r);  // of the 12 planted
  ASSERT_LE(found, 12u) << quality_report_text(d, r);
  const std::string text = quality_report_text(d, r);
  EXPECT_NE(text.find(fmt::format("outlier geometries: {}\n", found)), std::string::npos) << text;
  EXPECT_NE(text.find(fmt::format("... and {} more (every one in the JSON report)", found - 5)), std::string::npos)
      << text;
  std::size_t listed = 0;
  for (std::size_t pos = text.find("x its neighbours (score"); pos != std::string::npos;
       pos = text.find("x its neighbours (score", pos + 1))
    ++listed;
  EXPECT_EQ(listed, 5u) << text;
  EXPECT_EQ(quality_report_json(d, r).at("outliers").size(), found);
}

// Duplicate scans, averaged: the relative spread (max - min) / mean of each duplicated cell. Geometry A
// twice: 0.10, 0.12 at 500 nm (0.02 / 0.11) and 0.2, 0.2 at 600 nm (0); geometry B three times: 0.1, 0.1,
// 0.13 at 500 nm (0.03 / 0.11) and 0.3, 0.33, 0.3 at 600 nm (0.03 / 0.31).
TEST(Repeatability, SpreadOfDuplicateScansPerWavelength) {
  const std::string rows =
      "0,0,30,180,0.10,0.2\n"
      "20,0,30,180,0.1,0.3\n"
      "0,0,30,180,0.12,0.2\n"
      "40,0,30,180,0.05,0.05\n"
      "20,0,30,180,0.1,0.33\n"
      "20,0,30,180,0.13,0.3\n";
  const std::string wide = test::scratch_path("dup_wide.csv");
  std::ofstream(wide) << "theta_i,phi_i,theta_r,phi_r,500,600\n" << rows;
  DatasetReadOptions o;
  o.average_duplicates = true;
  o.warn = [](const std::string&) {};
  DatasetReadStats stats;
  const SpectralDataset d = read_dataset(wide, o, stats);
  const Repeatability& rep = stats.repeatability;
  EXPECT_EQ(rep.geometries, 2u);
  ASSERT_EQ(rep.median_relative_spread.size(), 2u);
  EXPECT_NEAR(rep.median_relative_spread[0], 0.5 * (0.02 / 0.11 + 0.03 / 0.11), 1e-12);
  EXPECT_NEAR(rep.max_relative_spread[0], 0.03 / 0.11, 1e-12);
  EXPECT_NEAR(rep.median_relative_spread[1], 0.5 * (0.0 + 0.03 / 0.31), 1e-12);
  EXPECT_NEAR(rep.max_relative_spread[1], 0.03 / 0.31, 1e-12);
  // The same file in the long format gives the same figures.
  std::string long_text = "theta_i,phi_i,theta_r,phi_r,wavelength,brdf\n";
  std::size_t start = 0;
  while (start < rows.size()) {
    const std::size_t end = rows.find('\n', start);
    const std::string line = rows.substr(start, end - start);
    const std::size_t c4 = line.find(',', line.find(',', line.find(',', line.find(',') + 1) + 1) + 1);
    const std::string angles = line.substr(0, c4);
    const std::size_t c5 = line.find(',', c4 + 1);
    long_text += angles + ",500," + line.substr(c4 + 1, c5 - c4 - 1) + "\n";
    long_text += angles + ",600," + line.substr(c5 + 1) + "\n";
    start = end + 1;
  }
  const std::string long_path = test::scratch_path("dup_long.csv");
  std::ofstream(long_path) << long_text;
  DatasetReadStats long_stats;
  (void)read_dataset(long_path, o, long_stats);
  EXPECT_EQ(long_stats.repeatability.geometries, 2u);
  ASSERT_EQ(long_stats.repeatability.max_relative_spread.size(), 2u);
  EXPECT_NEAR(long_stats.repeatability.median_relative_spread[0], rep.median_relative_spread[0], 1e-12);
  EXPECT_NEAR(long_stats.repeatability.max_relative_spread[1], rep.max_relative_spread[1], 1e-12);
  // In the check report: text and JSON.
  const QualityReport r = check_dataset(d, QualityOptions{}, stats);
  EXPECT_NE(quality_report_text(d, r).find("repeatability of 2 duplicated geometries"), std::string::npos);
  EXPECT_EQ(quality_report_json(d, r).at("repeatability").at("duplicated_geometries"), 2u);
}

// The same too-dark surface through albedo and rtable: a white-sky albedo of 1e-4 and Q0 = 1e-4 / pi.
TEST(Plausibility, AlbedoAndRTableWarnAboutATooDarkSurface) {
  const SpectralModel dark(std::shared_ptr<const Model>(make_model("lambert")), std::vector<double>{1e-4});
  const nlohmann::json report = albedo::compute_albedo(dark, albedo::AlbedoRequest{});
  bool warned = false;
  for (const auto& w : report.at("warnings")) warned = warned || w.at("kind") == "implausibly_dark";
  EXPECT_TRUE(warned) << report.at("warnings").dump();
  const photometry::RTableReport rt = photometry::rtable_report(dark, photometry::RTableRequest{});
  EXPECT_NEAR(rt.summary.q0, 1e-4 / std::numbers::pi, 0.02e-4 / std::numbers::pi);
  EXPECT_TRUE(any_contains(rt.warnings, "is far below any road surface")) << rt.warnings.size();
  // An asphalt-like albedo of 0.05: neither warns.
  const SpectralModel asphalt(std::shared_ptr<const Model>(make_model("lambert")), std::vector<double>{0.05});
  const nlohmann::json ok = albedo::compute_albedo(asphalt, albedo::AlbedoRequest{});
  for (const auto& w : ok.at("warnings")) EXPECT_NE(w.at("kind"), "implausibly_dark");
  EXPECT_FALSE(any_contains(photometry::rtable_report(asphalt, photometry::RTableRequest{}).warnings, "far below"));
}

}  // namespace
}  // namespace roadbrdf
