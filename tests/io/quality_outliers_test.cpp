// The outlier check of `check` on a dense monotone incidence series: theta_i from 0 to 89 deg in 1 deg
// steps at seven views, a smooth BRDF rising steeply towards grazing incidence (Minnaert-like,
// 1/(cos theta_i + 0.001)^2: 30 x its nadir value at 88 deg and 60 x at 89 deg). No geometry of the
// smooth series is an outlier (with the quadratic fit alone, the last incidence of every view was
// flagged at 2-3 x its neighbours: fitted over neighbours on one side, it extrapolates short of the
// ramp); values planted 2.5 x too bright inside the series and near its grazing end are found.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/io/quality.h"

namespace roadbrdf {
namespace {

struct Planted {
  double theta_i, theta_r, phi_r;
};

SpectralDataset ramp(const std::vector<Planted>& planted, std::set<std::size_t>* planted_indices) {
  SpectralDataset d;
  d.wavelengths = {450.0, 550.0, 650.0, 750.0};
  for (double tr : {0.0, 20.0, 40.0, 60.0}) {
    for (double pr : {0.0, 180.0}) {
      if (tr == 0.0 && pr == 180.0) continue;
      for (double ti = 0.0; ti <= 89.0; ti += 1.0) {
        const double ci = std::cos(ti * kDegree), cr = std::cos(tr * kDegree);
        double f = 0.05 * (1.0 + (pr == 180.0 ? 0.5 : 0.2) / sqr(ci + 0.001)) / (0.5 + cr);
        for (const Planted& p : planted) {
          if (p.theta_i == ti && p.theta_r == tr && p.phi_r == pr) {
            f *= 2.5;
            planted_indices->insert(d.geometries.size());
          }
        }
        d.geometries.push_back(geometry_from_degrees(ti, 0.0, tr, pr));
        for (double w : d.wavelengths) d.brdf.push_back(f * (1.0 + 0.3 * (w - 450.0) / 300.0));
      }
    }
  }
  return d;
}

TEST(QualityOutliersOnARamp, SmoothSeriesRisingTowardsGrazingHasNoOutliers) {
  std::set<std::size_t> none;
  const SpectralDataset d = ramp({}, &none);
  ASSERT_EQ(d.geometry_count(), 7u * 90u);
  const QualityReport r = check_dataset(d);
  EXPECT_TRUE(r.outliers.empty()) << quality_report_text(d, r);
}

TEST(QualityOutliersOnARamp, PlantedValuesInsideAndNearTheGrazingEndAreFound) {
  std::set<std::size_t> planted;
  const SpectralDataset d = ramp({{50.0, 40.0, 180.0}, {85.0, 20.0, 0.0}, {10.0, 60.0, 0.0}}, &planted);
  ASSERT_EQ(planted.size(), 3u);
  const QualityReport r = check_dataset(d);
  std::set<std::size_t> found;
  for (const auto& o : r.outliers) found.insert(o.index);
  EXPECT_EQ(found, planted) << quality_report_text(d, r);
}

}  // namespace
}  // namespace roadbrdf
