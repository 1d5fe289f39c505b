#include "roadbrdf/photometry/rtable_uncertainty.h"

#include <array>
#include <cmath>
#include <utility>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/propagation.h"

namespace roadbrdf::photometry {

namespace {

enum Figure : std::size_t { kQ0, kS1, kS2, kQd, kFigures };

// Standard normal distribution function.
double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

}  // namespace

std::optional<RTableUncertainty> summary_uncertainty(const SpectralModel& model, const SpectralWeighting& weighting,
                                                     const RTable& table, Q0Region region) {
  const std::vector<double>& covariance = model.parameter_covariance();
  if (covariance.empty() || !model.is_spectral()) return std::nullopt;
  const Model& m = model.model();
  const ModelDescription& description = m.description();
  const std::size_t P = m.parameter_count(), J = model.wavelengths().size();
  const WeightedWavelengths reduction = weighted_wavelengths(model, weighting);
  const std::vector<Geometry> geometries = rtable_geometries(table.alpha_deg);
  const std::size_t G = geometries.size();

  // The reduction's parameter sets p(l), and for each fit wavelength j the sets it enters, with its
  // interpolation weight a_lj there.
  std::vector<std::vector<double>> sets;
  std::vector<std::vector<std::pair<std::size_t, double>>> entered(J);
  for (std::size_t l = 0; l < reduction.wavelengths.size(); ++l) {
    sets.push_back(model.parameters_at(reduction.wavelengths[l]));
    for (const auto& [j, a] : model.interpolation_weights(reduction.wavelengths[l])) {
      if (a != 0.0) entered[j].push_back({l, a});
    }
  }

  // The figures of the table and the factor 1e4 cos^3(gamma) that turns a BRDF into R.
  const double r00 = table.r(0, 0), s1_value = s1(table), q0_value = q0(table, region);
  const double s2_value = q0_value / r00;
  std::array<double, kRows> to_scaled{};
  for (std::size_t i = 0; i < kRows; ++i) {
    const double t = standard_tan_gamma()[i];
    to_scaled[i] = kRScale * std::pow(1.0 + t * t, -1.5);
  }

  // The model's values and parameter gradients at the table's geometries for every set of the
  // reduction, once: df/dp_k(p(l), geometry g) = set_gradient[(l * G + g) * P + k].
  std::vector<double> set_gradient(sets.size() * G * P), values(G);
  for (std::size_t l = 0; l < sets.size(); ++l) {
    m.evaluate_batch_with_gradient(geometries.data(), G, sets[l].data(), values.data(),
                                   set_gradient.data() + l * G * P);
  }

  std::array<std::vector<double>, kFigures> gradient;  // [figure][j * P + k] = dY/dp_jk
  for (auto& g : gradient) g.assign(J * P, 0.0);
  for (std::size_t j = 0; j < J; ++j) {
    const std::vector<std::pair<std::size_t, double>>& sets_j = entered[j];
    if (sets_j.empty()) continue;  // a fit wavelength outside the weighting: no effect
    for (std::size_t k = 0; k < P; ++k) {
      // The parameters that propagate (core/propagation.h): a positive variance and room in the
      // physical range; the derivative itself is the model's analytic (or Jet) gradient.
      const auto [lower, upper] = description.physical_range(k);
      const double p = model.parameter_table()[j * P + k];
      if (!(derivative_step(p, covariance[(j * P + k) * P + k], lower, upper).span() > 0.0)) continue;
      // dT/dp_jk, the table's derivative (R = 1e4 r per unit of p_jk): p_jk enters set l with the
      // interpolation weight a_lj, and set l the reduction with the weight w_l.
      RTable derivative;
      derivative.alpha_deg = table.alpha_deg;
      for (std::size_t g = 0; g < G; ++g) {
        double sum = 0.0;
        for (const auto& [l, a] : sets_j) sum += reduction.weights[l] * a * set_gradient[(l * G + g) * P + k];
        derivative.scaled[g] = to_scaled[g / kColumns] * sum;
      }
      // Q0 and Qd are linear in the table; S1 and S2 are ratios (quotient rule).
      const double d_q0 = q0(derivative, region);
      gradient[kQ0][j * P + k] = d_q0;
      gradient[kQd][j * P + k] = qd(derivative);
      gradient[kS1][j * P + k] = (derivative.at(8, 0) - s1_value * derivative.at(0, 0)) / table.at(0, 0);
      gradient[kS2][j * P + k] = (d_q0 - s2_value * derivative.r(0, 0)) / r00;
    }
  }

  // u^2 = sum_j g_j^T Sigma_j g_j over the independent fit wavelengths; sum_j u_j fully correlated.
  std::array<double, kFigures> independent{}, correlated{};
  for (std::size_t f = 0; f < kFigures; ++f) {
    double sum_squares = 0.0, sum = 0.0;
    for (double u_j : propagate(gradient[f], covariance, J, P)) {
      sum_squares += u_j * u_j;  // NaN propagates
      sum += u_j;
    }
    independent[f] = std::sqrt(sum_squares);
    correlated[f] = sum;
  }
  return RTableUncertainty{{independent[kQ0], independent[kS1], independent[kS2], independent[kQd]},
                           {correlated[kQ0], correlated[kS1], correlated[kS2], correlated[kQd]}};
}

std::vector<ClassProbability> class_probabilities(double s1_value, double u_s1, ClassSystem system) {
  if (!std::isfinite(s1_value)) throw InputError("class probabilities: S1 is not finite");
  if (!(u_s1 >= 0.0)) throw InputError("class probabilities: u(S1) must be a non-negative number");
  const std::string certain = classify(s1_value, system).name;
  std::vector<ClassProbability> result;
  for (const RoadClass& c : road_classes(system)) {
    double probability = c.name == certain ? 1.0 : 0.0;
    if (u_s1 > 0.0) {
      // P(lower <= S1 < upper); Phi(+-inf) = 1, 0 at the open ends of the first and last class.
      probability = normal_cdf((c.s1_upper - s1_value) / u_s1) - normal_cdf((c.s1_lower - s1_value) / u_s1);
    }
    result.push_back({c.name, probability});
  }
  return result;
}

}  // namespace roadbrdf::photometry
