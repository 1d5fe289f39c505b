// The measurement sigma of a fit estimated from the dataset's duplicate rows (FitRequest::
// sigma_from_duplicates): a synthetic Lambertian sample scanned five times, every value drawn with a
// known relative standard deviation. The pooled estimate (ISO 5725-2 repeatability of the relative
// deviations) recovers it within its sampling error, equals the formula evaluated here on the drawn
// values, and gives a fit whose chi2 per degree of freedom is 1 within its sampling error.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/fitting/fit_request.h"
#include "roadbrdf/io/dataset_io.h"
#include "support/scratch.h"

namespace roadbrdf {
namespace {

constexpr double kRelativeSigma = 0.03;  // of one measurement
constexpr int kScans = 5;
const std::vector<double> kWavelengths = {500.0, 600.0, 700.0};
const std::vector<double> kAlbedo = {0.2, 0.3, 0.4};

struct Scans {
  std::vector<std::vector<double>> angles;  // per geometry: theta_i, phi_i, theta_r, phi_r [deg]
  // values[scan][geometry][wavelength]
  std::vector<std::vector<std::vector<double>>> values;
};

Scans draw_scans() {
  Scans s;
  for (double ti = 0.0; ti <= 70.0; ti += 10.0) {
    for (double tr : {0.0, 15.0, 30.0, 45.0, 60.0}) {
      for (double pr : {0.0, 45.0, 90.0, 180.0, 270.0}) {
        if (tr == 0.0 && pr != 0.0) continue;  // one azimuth at nadir view
        s.angles.push_back({ti, 0.0, tr, pr});
      }
    }
  }
  NormalStream normal(20261207);
  s.values.resize(kScans);
  for (auto& scan : s.values) {
    for (std::size_t g = 0; g < s.angles.size(); ++g) {
      std::vector<double> row;
      for (double a : kAlbedo) row.push_back(a / std::numbers::pi * (1.0 + kRelativeSigma * normal.next()));
      scan.push_back(row);
    }
  }
  return s;
}

// The scans one after the other (each geometry kScans times), wide or long.
std::string write_scans(const Scans& s, bool long_format, const std::string& name) {
  const std::string path = test::scratch_path(name);
  std::ofstream out(path);
  out.precision(17);
  out << "theta_i,phi_i,theta_r,phi_r";
  if (long_format) {
    out << ",wavelength,brdf\n";
  } else {
    for (double w : kWavelengths) out << ',' << w;
    out << '\n';
  }
  for (const auto& scan : s.values) {
    for (std::size_t g = 0; g < s.angles.size(); ++g) {
      const auto& a = s.angles[g];
      const std::string angles =
          std::to_string(a[0]) + ',' + std::to_string(a[1]) + ',' + std::to_string(a[2]) + ',' + std::to_string(a[3]);
      if (long_format) {
        for (std::size_t j = 0; j < kWavelengths.size(); ++j) {
          out << angles << ',' << kWavelengths[j] << ',' << scan[g][j] << '\n';
        }
      } else {
        out << angles;
        for (double v : scan[g]) out << ',' << v;
        out << '\n';
      }
    }
  }
  return path;
}

// The pooled relative standard deviation written out: sum over geometries and scans of the squared
// deviation from the geometry's mean over that mean, divided by sum (n - 1).
double pooled_relative_sd(const Scans& s, std::size_t j) {
  double squares = 0.0;
  for (std::size_t g = 0; g < s.angles.size(); ++g) {
    double mean = 0.0;
    for (const auto& scan : s.values) mean += scan[g][j];
    mean /= kScans;
    for (const auto& scan : s.values) squares += std::pow((scan[g][j] - mean) / mean, 2);
  }
  return std::sqrt(squares / static_cast<double>(s.angles.size() * (kScans - 1)));
}

TEST(FitSigmaFromDuplicates, PooledRepeatabilityRecoversTheDrawnSigmaAndChi2PerDofIsOne) {
  const Scans s = draw_scans();
  const std::size_t n = s.angles.size();
  FitRequest request;
  request.data = write_scans(s, false, "scans-wide.csv");
  request.models = {"lambert"};
  request.sigma_from_duplicates = true;
  const SpectralDataset data = read_fit_data(request);
  ASSERT_EQ(data.geometry_count(), n);
  ASSERT_TRUE(data.has_sigma());
  // Degrees of freedom of the estimate per wavelength: n (kScans - 1); its relative standard error
  // is 1 / sqrt(2 nu) for normal deviates.
  const double nu = static_cast<double>(n * (kScans - 1));
  for (std::size_t j = 0; j < kWavelengths.size(); ++j) {
    const double expected = pooled_relative_sd(s, j);
    const double y = data.value(0, j);
    const double estimate = data.sigma[j] * std::sqrt(double{kScans}) / y;  // geometry 0's sigma of the mean
    EXPECT_NEAR(estimate, expected, 1e-12 * expected) << kWavelengths[j];
    EXPECT_NEAR(estimate, kRelativeSigma, 3.0 * kRelativeSigma / std::sqrt(2.0 * nu)) << kWavelengths[j];
    // Every value's sigma: the same relative sigma over sqrt(rows averaged).
    for (std::size_t g = 0; g < n; ++g) {
      EXPECT_NEAR(data.sigma[g * kWavelengths.size() + j], expected * data.value(g, j) / std::sqrt(double{kScans}),
                  1e-12 * data.value(g, j));
    }
  }
  const FitSummary summary = run_fit(request, data);
  const FitResult& fit = summary.best();
  ASSERT_TRUE(summary.sigma_weights);
  ASSERT_EQ(summary.notes.size(), 1u);
  EXPECT_NE(summary.notes[0].find("sigma from the repeatability of duplicate rows"), std::string::npos);
  // chi2 per degree of freedom of the weighted fit: 1 up to the scatter of chi2 (variance 2/dof) and
  // of the estimated sigma entering squared (relative variance 4 / (2 nu) per wavelength).
  const double dof = static_cast<double>(fit.points_total - fit.free_parameters_total);
  const double m = static_cast<double>(kWavelengths.size());
  const double spread = std::sqrt(2.0 / dof + 4.0 / (2.0 * nu) / m);
  EXPECT_NEAR(fit.chi2_total / dof, 1.0, 3.0 * spread);
  for (std::size_t j = 0; j < kWavelengths.size(); ++j) {
    EXPECT_NEAR(fit.wavelengths[j].parameters[0], kAlbedo[j], 5.0 * kAlbedo[j] * kRelativeSigma / std::sqrt(n * 5.0));
  }
}

TEST(FitSigmaFromDuplicates, LongFileGivesTheSameSigmaAsTheWideFile) {
  const Scans s = draw_scans();
  FitRequest wide, longer;
  wide.data = write_scans(s, false, "scans-wide2.csv");
  longer.data = write_scans(s, true, "scans-long.csv");
  wide.sigma_from_duplicates = longer.sigma_from_duplicates = true;
  const SpectralDataset a = read_fit_data(wide), b = read_fit_data(longer);
  ASSERT_EQ(a.sigma.size(), b.sigma.size());
  for (std::size_t k = 0; k < a.sigma.size(); ++k) EXPECT_NEAR(a.sigma[k], b.sigma[k], 1e-12 * a.sigma[k]);
}

std::string field_of_error(const FitRequest& request) {
  try {
    (void)run_fit(request, read_fit_data(request));
  } catch (const FieldError& e) {
    return e.field() + ": " + e.what();
  }
  return "no error";
}

TEST(FitSigmaFromDuplicates, RefusedWithoutDuplicatesWithASigmaColumnOrADatasetInMemory) {
  FitRequest request;
  request.models = {"lambert"};
  request.sigma_from_duplicates = true;
  {
    const std::string path = test::scratch_path("single.csv");
    std::ofstream(path) << "theta_i,phi_i,theta_r,phi_r,500\n0,0,10,0,0.1\n0,0,20,0,0.1\n";
    request.data = path;
    const std::string e = field_of_error(request);
    EXPECT_NE(e.find("sigma_from_duplicates"), std::string::npos) << e;
    EXPECT_NE(e.find("no repeated geometry"), std::string::npos) << e;
  }
  {
    const std::string path = test::scratch_path("with-sigma.csv");
    std::ofstream(path) << "theta_i,phi_i,theta_r,phi_r,500,sigma_500\n0,0,10,0,0.1,0.01\n0,0,10,0,0.11,0.01\n";
    request.data = path;
    const std::string e = field_of_error(request);
    EXPECT_NE(e.find("sigma_from_duplicates"), std::string::npos) << e;
    EXPECT_NE(e.find("has a sigma column"), std::string::npos) << e;
  }
  {
    SpectralDataset d;
    d.wavelengths = {500.0};
    d.geometries = {geometry_from_degrees(0, 0, 10, 0), geometry_from_degrees(0, 0, 20, 0)};
    d.brdf = {0.1, 0.1};
    try {
      (void)run_fit(request, d);
      ADD_FAILURE() << "a dataset in memory was accepted";
    } catch (const FieldError& e) {
      EXPECT_EQ(e.field(), "sigma_from_duplicates");
      EXPECT_NE(std::string(e.what()).find("needs the dataset's file"), std::string::npos) << e.what();
    }
  }
  {
    const std::string path = test::scratch_path("duplicates.csv");
    std::ofstream(path) << "theta_i,phi_i,theta_r,phi_r,500\n0,0,10,0,0.1\n0,0,10,0,0.11\n0,0,20,0,0.1\n";
    request.data = path;
    request.use_sigma = false;
    const std::string e = field_of_error(request);
    EXPECT_NE(e.find("`use_sigma` off"), std::string::npos) << e;
  }
}

}  // namespace
}  // namespace roadbrdf
