// The luminance of every grid point of the CIE standard tables (scaled to their Q0) under a road
// luminaire, against a second, plain implementation written here from the standard's formulas:
// L = sum r(beta, tan gamma) I(C, gamma) MF / h^2 over the luminaires within 5 h along the road, with
// r interpolated quadratically (Neville's scheme on the three tabulated values nearest to the point)
// and beta the angle between the vertical planes through the point and the observer and through the
// point and the luminaire, measured so that 0 is the luminaire beyond the point.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>

#include "roadbrdf/core/error.h"
#include "roadbrdf/lighting/calculation.h"
#include "roadbrdf/lighting/luminaire_file.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/photometry/rtable_io.h"
#include "support/paths.h"

namespace roadbrdf::lighting {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A road luminaire's typical shape: a wide beam along the road (peak near gamma 65 deg in C0 and
// C180), thrown towards the carriageway (C90 brighter than C270), nothing upward.
Luminaire road_luminaire() {
  Luminaire l;
  l.name = "synthetic road luminaire";
  for (int c = 0; c < 360; c += 5) l.distribution.c_deg.push_back(c);
  for (int g = 0; g <= 180; g += 5) l.distribution.gamma_deg.push_back(g * 0.5);
  for (double c : l.distribution.c_deg) {
    for (double g : l.distribution.gamma_deg) {
      const double along = std::pow(std::abs(std::cos(c * kDeg)), 2.0);
      const double across = 1.0 + 0.6 * std::sin(c * kDeg);
      const double beam =
          g <= 90.0 ? std::cos(g * kDeg) + 2.5 * along * std::exp(-std::pow((g - 65.0) / 12.0, 2)) : 0.0;
      l.distribution.candela.push_back(g < 90.0 ? 400.0 * across * beam : 0.0);
    }
  }
  l.flux_lm = 10000.0;
  l.power_w = 80.0;
  return l;
}

// Neville's scheme through three points.
double quadratic(const double* x, const double* f, double at) {
  double p01 = ((at - x[1]) * f[0] - (at - x[0]) * f[1]) / (x[0] - x[1]);
  double p12 = ((at - x[2]) * f[1] - (at - x[1]) * f[2]) / (x[1] - x[2]);
  return ((at - x[2]) * p01 - (at - x[0]) * p12) / (x[0] - x[2]);
}

template <std::size_t N>
std::size_t first_of_three(const std::array<double, N>& axis, double at) {
  std::size_t best = 0;
  for (std::size_t k = 0; k < N; ++k) {
    if (std::abs(axis[k] - at) < std::abs(axis[best] - at)) best = k;
  }
  if (best == 0) return 0;
  if (best == N - 1) return N - 3;
  return best - 1;
}

double reference_r(const photometry::RTable& table, double t, double beta) {
  const auto& ts = photometry::standard_tan_gamma();
  const auto& bs = photometry::standard_beta_deg();
  if (t > 12.0) return 0.0;
  const std::size_t i = first_of_three(ts, t), j = first_of_three(bs, beta);
  double rows[3];
  for (std::size_t a = 0; a < 3; ++a) {
    double f[3];
    for (std::size_t b = 0; b < 3; ++b) {
      const double v = table.r(i + a, j + b);
      f[b] = std::isnan(v) ? 0.0 : v;
    }
    rows[a] = quadratic(&bs[j], f, beta);
  }
  return quadratic(&ts[i], rows, t);
}

// Every grid luminance of `surface` against the reference; with a BRDF also the luminance at each
// point's true observation angle alpha = atan(1.5 m / distance to the observer), from the model itself.
void compare_with_reference(const Luminaire& luminaire, const RoadSurface& surface, Arrangement arrangement) {
  const photometry::RTable& table = surface.table;
  const std::string table_name = surface.description;
  Installation inst;
  inst.road.lanes = 3;
  inst.road.lane_width_m = 3.25;
  inst.luminaires.arrangement = arrangement;
  inst.luminaires.spacing_m = 42.0;  // N = 14
  inst.luminaires.height_m = 11.0;
  inst.luminaires.overhang_m = 1.2;
  inst.luminaires.maintenance_factor = 0.85;
  Diagnostics d;
  const LightingFigures fig = compute_lighting(inst, luminaire, surface, d);
  const double w = inst.road.width_m(), h = 11.0, s = 42.0;
  ASSERT_EQ(fig.grid.x.size(), 14u);
  std::vector<std::array<double, 3>> poles;  // x, y, turn of the C-planes [deg]
  for (int k = -6; k <= 8; ++k) {
    if (arrangement == Arrangement::single_sided) poles.push_back({k * s, 1.2, 0.0});
    if (arrangement == Arrangement::staggered) {
      poles.push_back({k * s, 1.2, 0.0});
      poles.push_back({k * s + 0.5 * s, w - 1.2, 180.0});
    }
  }
  double worst = 0.0;
  std::size_t compared = 0;
  for (const ObserverFigures& o : fig.observers) {
    const double ox = -60.0, oy = (o.lane + 0.5) * 3.25;
    EXPECT_EQ(o.x_m, ox);
    EXPECT_EQ(o.y_m, oy);
    for (std::size_t i = 0; i < fig.grid.x.size(); ++i) {
      for (std::size_t j = 0; j < fig.grid.y.size(); ++j) {
        const double px = (i + 0.5) * s / 14.0, py = (j + 0.5) * 3.25 / 3.0;
        double l = 0.0, l_true = 0.0;
        const double alpha = std::atan2(1.5, std::hypot(ox - px, oy - py)) / kDeg;
        for (const auto& [lx, ly, turn] : poles) {
          if (std::abs(lx - px) > 5.0 * h) continue;
          const double foot = std::hypot(lx - px, ly - py);
          const double to_observer = std::atan2(oy - py, ox - px) / kDeg;
          const double to_luminaire = std::atan2(ly - py, lx - px) / kDeg;
          double plan = std::fmod(std::abs(to_observer - to_luminaire), 360.0);
          if (plan > 180.0) plan = 360.0 - plan;
          const double beta = foot == 0.0 ? 0.0 : 180.0 - plan;
          double c = std::atan2(py - ly, px - lx) / kDeg - turn;
          c = std::fmod(c + 720.0, 360.0);
          const double gamma = std::atan(foot / h) / kDeg;
          const double intensity = luminaire.distribution.intensity(c, gamma);
          l += reference_r(table, foot / h, beta) * intensity * 0.85 / (h * h);
          if (surface.has_brdf()) {
            // L = f_r(gamma, alpha, beta) E, E = I cos^3(gamma) / h^2 (MF included).
            const Geometry g = geometry_from_road_angles({gamma, alpha, beta, 0.0});
            const double f_r = surface.model->model().evaluate(surface.model->parameter_table().data(), g);
            l_true += f_r * intensity * 0.85 * std::pow(std::cos(gamma * kDeg), 3) / (h * h);
          }
        }
        const std::size_t k = i * fig.grid.y.size() + j;
        const double got = o.luminance[k];
        worst = std::max(worst, std::abs(got - l) / l);
        if (surface.has_brdf()) worst = std::max(worst, std::abs(o.luminance_true_alpha[k] - l_true) / l_true);
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 3u * 14u * 9u);
  EXPECT_LT(worst, 1e-9) << table_name;
}

RoadSurface cie_table(const std::string& name) {
  const std::string file = test::source_dir() + "/data/third-party/rtables/" + name + "-table.dat";
  return surface_from_table(photometry::read_rtable(file, photometry::RTableFormat::radiance).table, name);
}

TEST(LightingRTableReference, EveryCieTableUnderARoadLuminaire) {
  const Luminaire luminaire = road_luminaire();
  for (const char* name : {"r1", "r2", "r3", "r4", "c1", "c2"}) {
    compare_with_reference(luminaire, cie_table(name), Arrangement::single_sided);
    compare_with_reference(luminaire, cie_table(name), Arrangement::staggered);
  }
}

TEST(LightingRTableReference, LuminanceAtTheTrueObservationAngle) {
  // A rough diffuse surface whose luminance depends on the viewing direction (Oren-Nayar, sigma 0.4).
  const std::shared_ptr<const Model> model(make_model("oren-nayar"));
  std::vector<double> p = model->description().default_parameters();
  p[*model->description().parameter_index("sigma")] = 0.4;
  Diagnostics d;
  const RoadSurface surface = surface_from_model(SpectralModel(model, p), "oren-nayar", d);
  compare_with_reference(road_luminaire(), surface, Arrangement::single_sided);
  compare_with_reference(road_luminaire(), surface, Arrangement::staggered);
}

TEST(LightingRTableReference, TheSharedCopyOfTheTablesIsTheBundledOne) {
  // The tests read data/third-party; the project's shared folder holds the same six tables.
  const std::string shared = test::shared_real_data_dir();
  if (shared.empty()) GTEST_SKIP() << "../shared/real-data is absent";
  const std::string folder = std::filesystem::path(shared).parent_path().string() + "/data/rtables";
  for (const char* name : {"r1", "r2", "r3", "r4", "c1", "c2"}) {
    const auto a = photometry::read_rtable(folder + "/" + name + "-table.dat", photometry::RTableFormat::radiance);
    const auto b = photometry::read_rtable(test::source_dir() + "/data/third-party/rtables/" + name + "-table.dat",
                                           photometry::RTableFormat::radiance);
    for (std::size_t k = 0; k < a.table.scaled.size(); ++k) {
      EXPECT_TRUE(a.table.scaled[k] == b.table.scaled[k] ||
                  (std::isnan(a.table.scaled[k]) && std::isnan(b.table.scaled[k])));
    }
  }
}

TEST(LightingRTableReference, HellaRoadLuminaire) {
  const std::string shared = test::shared_real_data_dir();
  if (shared.empty()) GTEST_SKIP() << "../shared/real-data is absent";
  const std::string file = shared + "/luminaires/tuberlin-roadrad/HellaEcoLight_2070lm_LDT.ies";
  Diagnostics d;
  Luminaire luminaire;
  try {
    luminaire = read_luminaire(file, d);
  } catch (const FileError& e) {
    GTEST_SKIP() << "the luminaire reader cannot read " << file << " yet: " << e.what();
  }
  compare_with_reference(luminaire, cie_table("r3"), Arrangement::single_sided);
  compare_with_reference(luminaire, cie_table("c2"), Arrangement::staggered);
}

}  // namespace
}  // namespace roadbrdf::lighting
