#include "roadbrdf/photometry/marking.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/core/error.h"

namespace roadbrdf::photometry {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

constexpr MarkingClass kRlClasses[] = {
    {"R0", 0.0}, {"R1", 80.0}, {"R2", 100.0}, {"R3", 150.0}, {"R4", 200.0}, {"R5", 300.0},
};
constexpr MarkingClass kQdClasses[] = {
    {"Q0", 0.0}, {"Q1", 80.0}, {"Q2", 100.0}, {"Q3", 130.0}, {"Q4", 160.0},
};

// f(w_r, w_i): the model with its two directions exchanged. Its black-sky albedo at a "sun" zenith
// theta_r is int f(w_i, w_r) cos(theta_i) dw_i, the integral of Q_d (see marking.h). An ideal specular
// part is its own mirror image (R(theta) at theta_i = theta_r), so delta_reflectance is the model's.
class ExchangedDirections final : public Model {
 public:
  explicit ExchangedDirections(const Model& model) : Model(model.description()), model_(model) {}
  double evaluate(const double* params, const Geometry& g) const override {
    return model_.evaluate(params, g.swapped());
  }
  double evaluate_with_gradient(const double* params, const Geometry& g, double* gradient) const override {
    return model_.evaluate_with_gradient(params, g.swapped(), gradient);
  }
  void evaluate_batch(const Geometry* geometries, std::size_t n_geometries, const double* params, std::size_t n_sets,
                      double* out) const override {
    const std::vector<Geometry> swapped = exchange(geometries, n_geometries);
    model_.evaluate_batch(swapped.data(), n_geometries, params, n_sets, out);
  }
  void evaluate_batch_with_gradient(const Geometry* geometries, std::size_t n_geometries, const double* params,
                                    double* values, double* jacobian) const override {
    const std::vector<Geometry> swapped = exchange(geometries, n_geometries);
    model_.evaluate_batch_with_gradient(swapped.data(), n_geometries, params, values, jacobian);
  }
  double delta_reflectance(const double* params, double cos_theta_i) const override {
    return model_.delta_reflectance(params, cos_theta_i);
  }

 private:
  static std::vector<Geometry> exchange(const Geometry* geometries, std::size_t n) {
    std::vector<Geometry> out(n);
    for (std::size_t k = 0; k < n; ++k) out[k] = geometries[k].swapped();
    return out;
  }
  const Model& model_;
};

double angle_between(const Vec3& a, const Vec3& b) {
  // atan2 of |a x b| and a.b: accurate for small angles, where acos(a.b) is not.
  const Vec3 c{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  return std::atan2(length(c), dot(a, b));
}

// The geometry turned about the normal so that phi_i = 0.
Geometry relative_to_incidence(const Geometry& g) {
  return geometry_from_radians(g.theta_i, 0.0, g.theta_r, g.phi_r - g.phi_i);
}

}  // namespace

Geometry retroreflection_geometry(double illumination_angle_deg, double observation_angle_deg) {
  return geometry_from_degrees(90.0 - illumination_angle_deg, 0.0, 90.0 - observation_angle_deg, 0.0);
}

Geometry luminance_factor_geometry() { return geometry_from_degrees(kLuminanceFactorIncidenceDeg, 0.0, 0.0, 0.0); }

double rl_from_brdf(double brdf, double illumination_angle_deg) {
  return kMillicandela * brdf * std::sin(illumination_angle_deg * kDeg);
}

std::span<const MarkingClass> rl_classes() { return kRlClasses; }
std::span<const MarkingClass> qd_classes() { return kQdClasses; }

std::string_view marking_class(std::span<const MarkingClass> classes, double value) {
  std::string_view reached = classes.front().name;
  for (const MarkingClass& c : classes) {
    if (value >= c.minimum) reached = c.name;
  }
  return reached;
}

QdIntegral qd_of_model(const Model& model, const double* params, std::size_t n_sets, double observation_angle_deg) {
  const ExchangedDirections exchanged(model);
  const double theta_r = (90.0 - observation_angle_deg) * kDeg;
  const albedo::SpectralIntegral integral = albedo::black_sky(exchanged, params, n_sets, theta_r);
  QdIntegral out;
  out.converged = integral.converged;
  for (std::size_t s = 0; s < n_sets; ++s) {
    out.value.push_back(kMillicandela * integral.value[s] / std::numbers::pi);
    out.error.push_back(kMillicandela * integral.error[s] / std::numbers::pi);
  }
  return out;
}

MarkingFigures marking_figures(const SpectralModel& model, const SpectralWeighting& weighting,
                               double illumination_angle_deg, double observation_angle_deg) {
  const std::vector<Geometry> geometries = {retroreflection_geometry(illumination_angle_deg, observation_angle_deg),
                                            luminance_factor_geometry()};
  const std::vector<double> brdf = weighted_brdf(model, weighting, geometries);
  MarkingFigures f;
  f.brdf_retro = brdf[0];
  f.rl = rl_from_brdf(brdf[0], illumination_angle_deg);
  f.beta = std::numbers::pi * brdf[1];
  // Q_d per weighted wavelength, then weighted: the integral is linear in f_r.
  std::vector<double> params = model.parameter_table();
  std::vector<double> weights = {1.0};
  if (model.is_spectral()) {
    const WeightedWavelengths w = weighted_wavelengths(model, weighting);
    params.clear();
    for (double wavelength : w.wavelengths) {
      const std::vector<double> p = model.parameters_at(wavelength);
      params.insert(params.end(), p.begin(), p.end());
    }
    weights = w.weights;
  }
  const QdIntegral qd = qd_of_model(model.model(), params.data(), weights.size(), observation_angle_deg);
  f.qd_converged = qd.converged;
  for (std::size_t k = 0; k < weights.size(); ++k) {
    f.qd += weights[k] * qd.value[k];
    f.qd_error += weights[k] * qd.error[k];
  }
  return f;
}

std::optional<DataValue> data_value_at(const SpectralDataset& data, const Geometry& target,
                                       const std::vector<double>& wavelength_weights, double tolerance_deg,
                                       double* nearest_distance_deg) {
  if (wavelength_weights.size() != data.wavelength_count()) {
    throw InputError("one weight per wavelength of the data is needed");
  }
  const Geometry t = relative_to_incidence(target);
  struct Candidate {
    double distance_deg;
    double value;
  };
  std::vector<Candidate> candidates;
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t n = 0; n < data.geometry_count(); ++n) {
    double value = 0.0;
    for (std::size_t j = 0; j < data.wavelength_count(); ++j) {
      if (wavelength_weights[j] != 0.0) value += wavelength_weights[j] * data.value(n, j);
    }
    if (std::isnan(value)) continue;
    const Geometry g = relative_to_incidence(data.geometries[n]);
    const double di = angle_between(g.wi, t.wi), dr = angle_between(g.wr, t.wr);
    const double distance = std::sqrt(di * di + dr * dr) / kDeg;
    nearest = std::min(nearest, distance);
    if (distance <= tolerance_deg) candidates.push_back({distance, value});
  }
  if (nearest_distance_deg != nullptr) *nearest_distance_deg = nearest;
  if (candidates.empty()) return std::nullopt;
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.distance_deg < b.distance_deg; });
  DataValue out;
  out.nearest_distance_deg = candidates.front().distance_deg;
  if (candidates.front().distance_deg < 1e-9) {
    out.value = candidates.front().value;
    out.points = 1;
    return out;
  }
  // Shepard's inverse-distance weighting (power 2) over the nearest four.
  double sum_w = 0.0, sum_wf = 0.0;
  const std::size_t used = std::min<std::size_t>(4, candidates.size());
  for (std::size_t k = 0; k < used; ++k) {
    const double w = 1.0 / (candidates[k].distance_deg * candidates[k].distance_deg);
    sum_w += w;
    sum_wf += w * candidates[k].value;
  }
  out.value = sum_wf / sum_w;
  out.points = used;
  return out;
}

}  // namespace roadbrdf::photometry
