// compute_albedo's uncertainty stage (report_stages.h): standard uncertainties of every albedo from
// the fit's parameter covariance, per wavelength and broadband (albedo/uncertainty.h explains the
// linearised propagation and why it is preferred to sampling here).
#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <cmath>

#include "roadbrdf/albedo/gradient_integrals.h"
#include "roadbrdf/albedo/report_stages.h"
#include "roadbrdf/albedo/uncertainty.h"
#include "roadbrdf/core/math.h"

namespace roadbrdf::albedo::detail {

namespace {

// Undefined (NaN) uncertainties are JSON null, in the document itself and not only when dumped.
nlohmann::json number_or_null(double x) { return std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x); }

nlohmann::json with_nulls(const std::vector<double>& v) {
  nlohmann::json out = nlohmann::json::array();
  for (double x : v) out.push_back(number_or_null(x));
  return out;
}

nlohmann::json rows_with_nulls(const std::vector<std::vector<double>>& rows) {
  if (rows.empty()) return nullptr;
  nlohmann::json out = nlohmann::json::array();
  for (const auto& row : rows) out.push_back(with_nulls(row));
  return out;
}

nlohmann::json broadband_json(const BroadbandUncertainty& b) {
  return {{"independent", number_or_null(b.independent)}, {"correlated", number_or_null(b.correlated)}};
}

// The gradient of blue = (1 - D) black + D white is the same combination of theirs.
std::vector<double> blue_sky_gradient(const std::vector<double>& g_black, const std::vector<double>& g_white,
                                      const std::vector<double>& diffuse, std::size_t n_params) {
  std::vector<double> g(g_black.size());
  for (std::size_t k = 0; k < g.size(); ++k) {
    const double d = diffuse[k / n_params];
    g[k] = (1.0 - d) * g_black[k] + d * g_white[k];
  }
  return g;
}

}  // namespace

UncertaintyPlan uncertainty_plan(const SpectralModel& sm, const ParameterSets& sets, const AlbedoRequest& a) {
  UncertaintyPlan plan;
  const std::vector<double>& covariance = sm.parameter_covariance();
  if (covariance.empty()) return plan;
  if (!a.uncertainty) {
    plan.notes.emplace_back("standard uncertainties not computed: values only were requested");
    return plan;
  }
  // At the fit's own wavelengths only: an interpolated parameter set has no covariance of its own.
  if (!sets.spectral || !a.wavelengths.empty()) {
    plan.notes.emplace_back(
        "standard uncertainties are given at the fit's own wavelengths only, not at requested wavelengths");
    return plan;
  }
  plan.gradients = gradient_plan(covariance, sets.n_sets, sm.model().parameter_count(), a.tolerance);
  if (plan.gradients->undefined_sets > 0) {
    plan.notes.push_back(fmt::format(
        "the parameter covariance is undefined at {} of {} wavelengths (a parameter on its bound, or a singular "
        "fit): their standard uncertainties are null and were not computed",
        plan.gradients->undefined_sets, sets.n_sets));
  }
  return plan;
}

nlohmann::json albedo_uncertainty(const SpectralModel& sm, const ParameterSets& sets, const AlbedoRequest& a,
                                  const UncertaintyPlan& uncertainty_plan, const SunAzimuth& azimuth,
                                  const Hemispherical& albedos, const Sky& sky, const Broadband& broadband,
                                  ProgressCounter& progress, std::vector<std::string>& notes) {
  notes.insert(notes.end(), uncertainty_plan.notes.begin(), uncertainty_plan.notes.end());
  if (!uncertainty_plan.gradients) return nullptr;
  const GradientPlan& plan = *uncertainty_plan.gradients;
  const std::vector<double>& covariance = sm.parameter_covariance();
  const Model& model = sm.model();
  const std::size_t n_params = model.parameter_count();
  const std::size_t n_sets = sets.n_sets;
  auto propagated = [&](const std::vector<double>& g) { return propagate(g, covariance, n_sets, n_params); };
  auto broadband_of = [&](const std::vector<const std::vector<double>*>& gradients,
                          const std::vector<const std::vector<double>*>& coefficients) {
    return broadband_json(broadband_uncertainty(gradients, coefficients, covariance, n_sets, n_params));
  };

  // The gradients not integrated with their values (hemispherical_albedos), one task each as the
  // values' ([0]: white-sky, [1 + z]: black-sky).
  const std::vector<double>& zeniths = a.sun_zenith_deg;
  std::vector<std::vector<double>> gradients(zeniths.size() + 1);
  gradients[0] = albedos.white_gradient;
  for (std::size_t z = 0; z < zeniths.size(); ++z) gradients[1 + z] = albedos.black_gradient[z];
  std::size_t left = 0;
  for (const auto& g : gradients) left += g.empty() ? 1 : 0;
  progress.add_total(left);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, gradients.size(), 1),
      [&](const tbb::blocked_range<std::size_t>& tasks) {
        for (std::size_t t = tasks.begin(); t != tasks.end(); ++t) {
          if (!gradients[t].empty()) continue;
          if (t == 0) {
            gradients[t] = plan.with_nans(
                white_sky_gradient(model, sets.params.data(), n_sets, plan.scale, plan.settings, plan.nodes).gradient);
          } else {
            // The value's grazing cross-check found no lobe between the (mu, dphi) rule's nodes: its
            // derivatives have none either (gradient_integrals.h), so theirs is not repeated.
            QuadratureSettings settings = plan.settings;
            settings.grazing_check = !albedos.black_lobes_checked[t - 1];
            gradients[t] = plan.with_nans(black_sky_gradient(model, sets.params.data(), n_sets, plan.scale,
                                                             zeniths[t - 1] * kDegree, azimuth.phi_s, azimuth.mean,
                                                             settings, plan.nodes)
                                              .gradient);
          }
          progress.add();
        }
      },
      tbb::simple_partitioner());
  const std::vector<double>& g_white = gradients[0];

  const bool with_broadband = broadband.formed && !broadband.black_means.empty();
  std::vector<std::vector<double>> u_black, u_blue;
  nlohmann::json bb_black = nlohmann::json::array(), bb_blue = nlohmann::json::array();
  for (std::size_t z = 0; z < zeniths.size(); ++z) {
    const std::vector<double>& g_black = gradients[1 + z];
    u_black.push_back(propagated(g_black));
    if (with_broadband) bb_black.push_back(broadband_of({&g_black}, {&broadband.black_means[z].first}));
    if (!sky.diffuse.empty()) {
      const std::vector<double> g_blue = blue_sky_gradient(g_black, g_white, sky.diffuse[z], n_params);
      u_blue.push_back(propagated(g_blue));
      if (with_broadband && !broadband.blue_means.empty()) {
        const WeightedValue& m = broadband.blue_means[z];
        // SPECTRL2: direct-weighted black-sky plus diffuse-weighted white-sky; else one weight on blue.
        bb_blue.push_back(m.second.empty() ? broadband_of({&g_blue}, {&m.first})
                                           : broadband_of({&g_black, &g_white}, {&m.first, &m.second}));
      }
    }
  }

  nlohmann::json u = {{"method",
                       "linearised (GUM eq. 10) from the parameter covariance at each wavelength (a fit's, or a "
                       "mixture's from its end-members' fits)"},
                      {"black_sky", rows_with_nulls(u_black)},
                      {"white_sky", with_nulls(propagated(g_white))},
                      {"blue_sky", rows_with_nulls(u_blue)},
                      {"broadband", nullptr}};
  if (with_broadband) {
    u["broadband"] = {{"black_sky", bb_black},
                      {"white_sky", broadband_of({&g_white}, {&broadband.white_mean.first})},
                      {"blue_sky", bb_blue.empty() ? nlohmann::json(nullptr) : bb_blue}};
  }
  notes.emplace_back(
      "standard uncertainties from the parameter covariance, per wavelength; the broadband ones "
      "treat the wavelengths as independent ('independent') and give the bound for errors correlated "
      "across wavelengths ('correlated')");
  if (!sm.shared_parameters().empty()) notes.push_back(shared_parameters_note(sm));
  return u;
}

}  // namespace roadbrdf::albedo::detail
