// The integrated parameter gradients of the hemispherical integrals (albedo/gradient_integrals.h)
// against central differences of the value integrals themselves, taken far tighter (an independent
// route to the same derivatives, through the value quadrature only): for every bundled model, the standard
// uncertainty u = sqrt(g^T Sigma g) of black-sky (two sun zeniths) and white-sky albedo must agree to 1 %,
// and so must each scaled derivative u(p_k) dA/dp_k (to 1 % of u).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "roadbrdf/albedo/gradient_integrals.h"
#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {
namespace {

// Two parameter sets inside the declared ranges, away from their ends and from each other, with
// standard uncertainties of 2 % of the range.
struct Case {
  std::vector<double> params, scale;
};

Case case_of(const ModelDescription& d) {
  Case c;
  for (const double fraction : {0.37, 0.61}) {
    for (const ParameterInfo& p : d.parameters) {
      c.params.push_back(p.lower + fraction * (p.upper - p.lower));
      c.scale.push_back(0.02 * (p.upper - p.lower));
    }
  }
  return c;
}

// dA_s/dp_k by the central difference of `integral` (values of all sets at once) with step
// 1e-3 of the parameter's range.
std::vector<double> central_differences(
    const ModelDescription& d, const std::vector<double>& params, std::size_t n_sets,
    const std::function<std::vector<double>(const std::vector<double>&)>& integral) {
  const std::size_t P = d.parameters.size();
  std::vector<double> g(n_sets * P, 0.0);
  for (std::size_t k = 0; k < P; ++k) {
    const double h = 1e-3 * (d.parameters[k].upper - d.parameters[k].lower);
    std::vector<double> up = params, down = params;
    for (std::size_t s = 0; s < n_sets; ++s) {
      up[s * P + k] += h;
      down[s * P + k] -= h;
    }
    const std::vector<double> a = integral(up), b = integral(down);
    for (std::size_t s = 0; s < n_sets; ++s) g[s * P + k] = (a[s] - b[s]) / (2.0 * h);
  }
  return g;
}

// u of set s for a diagonal covariance (scale^2) plus a correlation 0.5 between the first two
// parameters, so that cross terms count too.
double uncertainty(const std::vector<double>& g, const std::vector<double>& scale, std::size_t s, std::size_t P) {
  double sum = 0.0;
  for (std::size_t a = 0; a < P; ++a) {
    for (std::size_t b = 0; b < P; ++b) {
      const double r = a == b ? 1.0 : ((a < 2 && b < 2) ? 0.5 : 0.0);
      sum += g[s * P + a] * r * scale[s * P + a] * scale[s * P + b] * g[s * P + b];
    }
  }
  return std::sqrt(sum);
}

void expect_agreement(const std::string& what, const std::vector<double>& integrated,
                      const std::vector<double>& differenced, const std::vector<double>& scale, std::size_t P) {
  for (std::size_t s = 0; s < 2; ++s) {
    const double u = uncertainty(differenced, scale, s, P);
    EXPECT_NEAR(uncertainty(integrated, scale, s, P), u, 0.01 * u + 1e-9) << what << " set " << s;
    for (std::size_t k = 0; k < P; ++k) {
      EXPECT_NEAR(scale[s * P + k] * integrated[s * P + k], scale[s * P + k] * differenced[s * P + k], 0.01 * u + 1e-9)
          << what << " set " << s << " parameter " << k;
    }
  }
}

TEST(GradientIntegral, EqualsCentralDifferencesOfTheValueIntegralsForEveryModel) {
  albedo::QuadratureSettings reference;
  // Difference quotients with step 2e-3 of the range: the integrals' errors (1e-8) add < 1e-5 / range
  // to a derivative, < 2e-7 to a scaled one, against u ~ 1e-3.
  reference.tolerance = 1e-8;
  albedo::QuadratureSettings settings;
  settings.tolerance = 1e-6;
  for (const std::string& name : model_names()) {
    SCOPED_TRACE(name);
    const std::shared_ptr<const Model> model = make_model(name);
    const ModelDescription& d = model->description();
    const std::size_t P = d.parameters.size();
    const Case c = case_of(d);
    const double phi_s = d.isotropic ? 0.0 : 0.4;
    for (const double zenith : {20.0, 65.0}) {
      const double theta_s = zenith * kDegree;
      const albedo::GradientIntegral g =
          albedo::black_sky_gradient(*model, c.params.data(), 2, c.scale, theta_s, phi_s, false, settings);
      const std::vector<double> reference_g = central_differences(d, c.params, 2, [&](const std::vector<double>& p) {
        return albedo::black_sky(*model, p.data(), 2, theta_s, phi_s, reference).value;
      });
      expect_agreement("black-sky " + std::to_string(zenith), g.gradient, reference_g, c.scale, P);
    }
    const albedo::GradientIntegral w = albedo::white_sky_gradient(*model, c.params.data(), 2, c.scale, settings);
    const std::vector<double> reference_w = central_differences(d, c.params, 2, [&](const std::vector<double>& p) {
      return albedo::white_sky(*model, p.data(), 2, reference).value;
    });
    expect_agreement("white-sky", w.gradient, reference_w, c.scale, P);
  }
}

TEST(GradientIntegral, AtGrazingSunTheValuesCrossCheckServesTheGradient) {
  // At 80 deg black_sky() cross-checks its rule with the mirror-polar rule. Where the value passed
  // (lobes_checked), the gradient without its own check (grazing_check false, as the albedo report
  // integrates it) must still equal central differences of fully checked value integrals.
  albedo::QuadratureSettings reference;
  reference.tolerance = 1e-8;
  albedo::QuadratureSettings settings;
  settings.tolerance = 1e-6;
  settings.grazing_check = false;
  const double theta_s = 80.0 * kDegree;
  std::size_t checked = 0;
  for (const std::string& name : model_names()) {
    SCOPED_TRACE(name);
    const std::shared_ptr<const Model> model = make_model(name);
    const ModelDescription& d = model->description();
    const Case c = case_of(d);
    const double phi_s = d.isotropic ? 0.0 : 0.4;
    if (!albedo::black_sky(*model, c.params.data(), 2, theta_s, phi_s).lobes_checked) continue;
    ++checked;
    const albedo::GradientIntegral g =
        albedo::black_sky_gradient(*model, c.params.data(), 2, c.scale, theta_s, phi_s, false, settings);
    const std::vector<double> reference_g = central_differences(d, c.params, 2, [&](const std::vector<double>& p) {
      return albedo::black_sky(*model, p.data(), 2, theta_s, phi_s, reference).value;
    });
    expect_agreement("black-sky 80", g.gradient, reference_g, c.scale, d.parameters.size());
  }
  EXPECT_GT(checked, 0u);
}

// The gradient on the value integral's nodes (GradientNodes::value_nodes, as the albedo report
// integrates it) against the same gradient with every component refined to a tolerance 100 times
// tighter: u and each u(p_k) dA/dp_k within 1 % of u, for every bundled model at the report's default
// tolerance, black-sky at normal incidence (Hapke's opposition peak on the edge of the domain), 45 and
// 80 deg (without the grazing check where the value passed it, as the report does) and white-sky.
// Hapke also at the bench's sand parameters (narrow opposition peak, h = 0.08).
void expect_value_nodes_agree(const Model& model, const std::vector<double>& params, const std::vector<double>& scale) {
  const std::size_t P = model.parameter_count();
  albedo::QuadratureSettings settings;  // the report's default tolerance, 1e-5
  albedo::QuadratureSettings reference;
  reference.tolerance = 1e-7;
  const double phi_s = model.description().isotropic ? 0.0 : 0.4;
  for (const double zenith : {0.0, 45.0, 80.0}) {
    const double theta_s = zenith * kDegree;
    albedo::QuadratureSettings s = settings;
    s.grazing_check = !albedo::black_sky(model, params.data(), 2, theta_s, phi_s, settings).lobes_checked;
    const albedo::GradientIntegral g = albedo::black_sky_gradient(model, params.data(), 2, scale, theta_s, phi_s, false,
                                                                  s, albedo::GradientNodes::value_nodes);
    const albedo::GradientIntegral r =
        albedo::black_sky_gradient(model, params.data(), 2, scale, theta_s, phi_s, false, reference);
    expect_agreement("black-sky " + std::to_string(zenith), g.gradient, r.gradient, scale, P);
  }
  const albedo::GradientIntegral w =
      albedo::white_sky_gradient(model, params.data(), 2, scale, settings, albedo::GradientNodes::value_nodes);
  const albedo::GradientIntegral r = albedo::white_sky_gradient(model, params.data(), 2, scale, reference);
  expect_agreement("white-sky", w.gradient, r.gradient, scale, P);
}

TEST(GradientIntegral, OnTheValuesNodesAgreesWithTheRefinedGradientForEveryModel) {
  for (const std::string& name : model_names()) {
    SCOPED_TRACE(name);
    const std::shared_ptr<const Model> model = make_model(name);
    const Case c = case_of(model->description());
    expect_value_nodes_agree(*model, c.params, c.scale);
  }
  SCOPED_TRACE("hapke, sand");
  const std::shared_ptr<const Model> hapke = make_model("hapke");
  // w, b0, h, xi at two wavelengths of the bench's sand; u 2 % of each range.
  const std::vector<double> params = {0.25, 0.4, 0.08, -0.25, 0.65, 0.4, 0.08, -0.25};
  const std::vector<double> scale = {0.02, 0.02, 0.04, 0.038, 0.02, 0.02, 0.04, 0.038};
  expect_value_nodes_agree(*hapke, params, scale);
}

TEST(GradientIntegral, ComponentsWithoutScaleAreNotIntegrated) {
  // Lambert: A = albedo for every sky, so dA/dalbedo = 1; a set with scale 0 reports 0.
  const std::shared_ptr<const Model> model = make_model("lambert");
  const std::vector<double> params = {0.3, 0.6}, scale = {0.01, 0.0};
  const albedo::GradientIntegral b = albedo::black_sky_gradient(*model, params.data(), 2, scale, 0.5, 0.0, false, {});
  EXPECT_NEAR(b.gradient[0], 1.0, 1e-12);
  EXPECT_EQ(b.gradient[1], 0.0);
  const albedo::GradientIntegral w = albedo::white_sky_gradient(*model, params.data(), 2, scale, {});
  EXPECT_NEAR(w.gradient[0], 1.0, 1e-12);
  EXPECT_EQ(w.gradient[1], 0.0);
}

}  // namespace
}  // namespace roadbrdf
