// Calibrated intimate mixing: the fit of the cross-section factors (calibration.h).
#include "roadbrdf/mixing/calibration.h"

#include <ceres/ceres.h>
#include <fmt/core.h>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/mixing/method_support.h"

namespace roadbrdf::mixing {

namespace {

constexpr double kLogFactorBound = 9.210340371976184;  // ln 1e4

// One measured mixture reduced to what the cost needs: for every measured value the end-members'
// BRDFs f_k at its geometry and wavelength, and per wavelength the end-members' single-scattering
// albedos w_k; the uncalibrated weights M/(rho D) per end-member. The hapke mixture is then
// MixtureModel::combine with weights k_e * base_k (mixture_model.h, kind "hapke").
struct PreparedMixture {
  std::string name;
  std::shared_ptr<const MixtureModel> mixture;
  std::size_t K = 0;
  std::vector<std::size_t> factor_of;  // per mixture end-member: index into the calibration's end-members
  std::vector<double> base;            // uncalibrated normalised weights c_k
  std::vector<double> ssa;             // [row][k]: w_k at each used wavelength
  struct Sample {
    std::size_t row;       // used wavelength
    std::size_t geometry;  // index into geometries
    double measured;       // f [sr^-1]
  };
  std::vector<Sample> samples;
  std::vector<double> f;  // [sample][k]
  std::vector<Geometry> geometries;

  // Residuals pi (f_pred - f_meas) (reflectance factor) for the factors k (calibration order).
  void residuals(const std::vector<double>& k, double* out) const {
    std::vector<double> p(2 * K);
    for (std::size_t s = 0; s < samples.size(); ++s) {
      const Sample& x = samples[s];
      for (std::size_t j = 0; j < K; ++j) {
        p[j] = base[j] * k[factor_of[j]];
        p[K + j] = ssa[x.row * K + j];
      }
      out[s] = kPi * (mixture->combine(p.data(), geometries[x.geometry], f.data() + s * K, nullptr) - x.measured);
    }
  }
};

// The data's wavelength indices inside the common range of the mixture's end-members.
std::vector<std::size_t> wavelengths_in_range(const MixInputs& inputs, const std::vector<std::size_t>& members,
                                              const SpectralDataset& data) {
  double lo = -INFINITY, hi = INFINITY;
  for (std::size_t e : members) {
    const SpectralModel& m = *inputs.end_members[e].model;
    if (!m.is_spectral()) continue;
    lo = std::max(lo, m.wavelengths().front());
    hi = std::min(hi, m.wavelengths().back());
  }
  std::vector<std::size_t> used;
  for (std::size_t q = 0; q < data.wavelengths.size(); ++q) {
    if (data.wavelengths[q] >= lo && data.wavelengths[q] <= hi) used.push_back(q);
  }
  return used;
}

// Prepare one mixture (factor_of is left to the caller).
PreparedMixture prepare(const MixInputs& inputs, const SpectralDataset& data, const std::string& name,
                        const MixSettings& factors_settings) {
  PreparedMixture pm;
  pm.name = name;
  const std::vector<std::size_t> members = detail::component_members(inputs);
  const std::vector<std::size_t> used = wavelengths_in_range(inputs, members, data);
  if (used.empty()) {
    throw FieldError(
        "mixtures",
        "mixture '" + name + "': no wavelength of its data lies inside the common range of its end-members' fits");
  }
  MixSettings settings = factors_settings;
  for (std::size_t q : used) settings.wavelengths.push_back(data.wavelengths[q]);
  // The library's hapke mix: weights from the formulation, w_k inverted from white-sky albedos.
  const MixResult r = mix(inputs, Method::kHapke, settings);
  pm.mixture = r.mixture;
  pm.K = r.mixture->component_count();
  pm.base = r.weights;
  pm.geometries = data.geometries;
  const std::size_t K = pm.K;
  std::vector<std::vector<double>> rows;
  for (double wl : settings.wavelengths) rows.push_back(r.model->parameters_at(wl));
  pm.ssa.resize(rows.size() * K);
  for (std::size_t row = 0; row < rows.size(); ++row) {
    for (std::size_t j = 0; j < K; ++j) pm.ssa[row * K + j] = rows[row][r.mixture->ssa_index(j)];
  }
  for (std::size_t g = 0; g < data.geometries.size(); ++g) {
    for (std::size_t row = 0; row < used.size(); ++row) {
      const double y = data.value(g, used[row]);
      if (!std::isfinite(y)) continue;
      pm.samples.push_back({row, g, y});
      for (std::size_t j = 0; j < K; ++j) {
        const double* params = rows[row].data() + r.mixture->component_offset(j);
        pm.f.push_back(r.mixture->component(j).evaluate(params, data.geometries[g]));
      }
    }
  }
  if (pm.samples.empty()) throw FieldError("mixtures", "mixture '" + name + "': no measured value in range");
  return pm;
}

double rms_of(const std::vector<double>& r) {
  double s = 0.0;
  for (double x : r) s += x * x;
  return std::sqrt(s / static_cast<double>(r.size()));
}

std::string canonical(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::weakly_canonical(path, ec);
  return ec ? path : p.string();
}

// Union-find over end-member indices: which factors the mixtures link.
std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// Ceres cost over the free log-factors u (every end-member but the reference).
struct LogFactorCost {
  const PreparedMixture* mixture;
  std::size_t n_factors;
  std::size_t reference;
  bool operator()(double const* const* u, double* residuals) const {
    mixture->residuals(factors_from(u[0]), residuals);
    return true;
  }
  std::vector<double> factors_from(const double* u) const {
    std::vector<double> k(n_factors, 1.0);
    for (std::size_t i = 0, j = 0; i < n_factors; ++i) {
      if (i != reference) k[i] = std::exp(u[j++]);
    }
    return k;
  }
};

// Prepare every mixture and give each of its end-members the index of its factor: end-members are
// matched by name, in order of first appearance, and one name must be one fit file. Fills the
// calibration's end-member and mixture lists.
std::vector<PreparedMixture> prepare_mixtures(const std::vector<CalibrationMixture>& mixtures,
                                              CrossSectionCalibration& cal) {
  std::vector<PreparedMixture> prepared;
  std::vector<std::string> canonical_fits;
  for (std::size_t m = 0; m < mixtures.size(); ++m) {
    const CalibrationMixture& mx = mixtures[m];
    const std::string label = mx.name.empty() ? fmt::format("#{}", m + 1) : mx.name;
    if (!mx.inputs || !mx.data) throw FieldError("mixtures", "mixture '" + label + "' has no formulation or data");
    PreparedMixture pm = prepare(*mx.inputs, *mx.data, label, {});
    pm.factor_of.assign(pm.K, 0);
    const std::vector<std::size_t> members = detail::component_members(*mx.inputs);
    for (std::size_t j = 0; j < pm.K; ++j) {
      const EndMember& em = mx.inputs->end_members[members[j]];
      const auto it = std::find(cal.end_members.begin(), cal.end_members.end(), em.name);
      if (it == cal.end_members.end()) {
        pm.factor_of[j] = cal.end_members.size();
        cal.end_members.push_back(em.name);
        cal.end_member_fits.push_back(em.fit_path);
        canonical_fits.push_back(canonical(em.fit_path));
        continue;
      }
      const std::size_t i = static_cast<std::size_t>(it - cal.end_members.begin());
      if (canonical(em.fit_path) != canonical_fits[i]) {
        throw FieldError("mixtures", "end-member '" + em.name + "' is '" + em.fit_path + "' in mixture '" + label +
                                         "' but '" + cal.end_member_fits[i] +
                                         "' in an earlier mixture (end-members are matched by name)");
      }
      pm.factor_of[j] = i;
    }
    cal.mixtures.push_back(label);
    prepared.push_back(std::move(pm));
  }
  return prepared;
}

// Set cal.reference ("" = the first end-member) and return its index among the end-members.
std::size_t reference_index(CrossSectionCalibration& cal, const std::string& reference) {
  cal.reference = reference.empty() ? cal.end_members.front() : reference;
  const auto ref_it = std::find(cal.end_members.begin(), cal.end_members.end(), cal.reference);
  if (ref_it == cal.end_members.end()) {
    std::string known;
    for (const auto& e : cal.end_members) known += (known.empty() ? "" : ", ") + e;
    throw FieldError("reference", "'" + cal.reference + "' is not an end-member of the mixtures (" + known + ")");
  }
  return static_cast<std::size_t>(ref_it - cal.end_members.begin());
}

// Identifiability: only ratios of factors of end-members that share a mixture (directly or through a
// chain of mixtures) are determined, so every end-member must be linked to the reference.
void require_linked_to_reference(const std::vector<PreparedMixture>& prepared, const CrossSectionCalibration& cal,
                                 std::size_t ref) {
  const std::size_t n = cal.end_members.size();
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const PreparedMixture& pm : prepared) {
    for (std::size_t j = 1; j < pm.K; ++j) parent[root(parent, pm.factor_of[j])] = root(parent, pm.factor_of[0]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (root(parent, i) != root(parent, ref)) {
      throw FieldError("mixtures", "end-member '" + cal.end_members[i] +
                                       "' never shares a mixture (directly or "
                                       "through other mixtures) with '" +
                                       cal.reference +
                                       "': the ratio of their factors is not determined by these mixtures");
    }
  }
}

// Bounded least squares in u = ln k of the free factors (every end-member but the reference); records
// the iterations and a note when the solver stopped at its limit. Returns u.
std::vector<double> solve_log_factors(const std::vector<PreparedMixture>& prepared, std::size_t n, std::size_t ref,
                                      CrossSectionCalibration& cal) {
  const std::size_t p = n - 1;
  std::vector<double> u(p, 0.0);
  ceres::Problem problem;
  std::vector<LogFactorCost> costs;
  costs.reserve(prepared.size());
  for (const PreparedMixture& pm : prepared) costs.push_back({&pm, n, ref});
  for (const LogFactorCost& c : costs) {
    auto* cost =
        new ceres::DynamicNumericDiffCostFunction<LogFactorCost, ceres::CENTRAL>(&c, ceres::DO_NOT_TAKE_OWNERSHIP);
    cost->AddParameterBlock(static_cast<int>(p));
    cost->SetNumResiduals(static_cast<int>(c.mixture->samples.size()));
    problem.AddResidualBlock(cost, nullptr, u.data());
  }
  for (std::size_t j = 0; j < p; ++j) {
    problem.SetParameterLowerBound(u.data(), static_cast<int>(j), -kLogFactorBound);
    problem.SetParameterUpperBound(u.data(), static_cast<int>(j), kLogFactorBound);
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 200;
  options.function_tolerance = 1e-15;
  options.parameter_tolerance = 1e-13;
  options.gradient_tolerance = 1e-16;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  if (summary.termination_type == ceres::FAILURE || summary.termination_type == ceres::USER_FAILURE) {
    throw InputError("cross-section calibration: the solver failed: " + summary.message);
  }
  if (summary.termination_type == ceres::NO_CONVERGENCE) {
    cal.notes.push_back("the solver stopped at its iteration limit: " + summary.message);
  }
  cal.iterations = static_cast<int>(summary.iterations.size());
  return u;
}

// Reflectance-factor RMS per mixture and over all of them, with k = 1 and with the fitted factors.
// Returns the calibrated residuals of every mixture, in mixture order.
std::vector<double> record_rms(const std::vector<PreparedMixture>& prepared, CrossSectionCalibration& cal) {
  const std::vector<double> ones(cal.end_members.size(), 1.0);
  std::vector<double> all_uncal, all_cal;
  for (const PreparedMixture& pm : prepared) {
    std::vector<double> r0(pm.samples.size()), r1(pm.samples.size());
    pm.residuals(ones, r0.data());
    pm.residuals(cal.factors, r1.data());
    cal.rms_uncalibrated.push_back(rms_of(r0));
    cal.rms_calibrated.push_back(rms_of(r1));
    all_uncal.insert(all_uncal.end(), r0.begin(), r0.end());
    all_cal.insert(all_cal.end(), r1.begin(), r1.end());
  }
  cal.residual_count = all_cal.size();
  cal.rms_uncalibrated_all = rms_of(all_uncal);
  cal.rms_calibrated_all = rms_of(all_cal);
  return all_cal;
}

// Jacobian [residual][j] of all residuals (mixture order) in u, by central differences.
std::vector<double> log_factor_jacobian(const std::vector<PreparedMixture>& prepared, const LogFactorCost& factors,
                                        const std::vector<double>& u, std::size_t N) {
  const std::size_t p = u.size();
  std::vector<double> J(N * p);
  for (std::size_t j = 0; j < p; ++j) {
    const double h = 1e-6 * std::max(1.0, std::abs(u[j]));
    std::vector<double> up = u, dn = u;
    up[j] += h;
    dn[j] -= h;
    std::size_t offset = 0;
    for (const PreparedMixture& pm : prepared) {
      std::vector<double> a(pm.samples.size()), b(pm.samples.size());
      pm.residuals(factors.factors_from(up.data()), a.data());
      pm.residuals(factors.factors_from(dn.data()), b.data());
      for (std::size_t s = 0; s < a.size(); ++s) J[(offset + s) * p + j] = (a[s] - b[s]) / (2.0 * h);
      offset += a.size();
    }
  }
  return J;
}

// Standard errors of the factors: s (J^T J)^-1/2 in u with s^2 = SSR/(N - p), mapped to k = e^u
// (SE(k) = k SE(u)); 0 for the reference, NaN without degrees of freedom or when J^T J is singular.
void record_standard_errors(const std::vector<PreparedMixture>& prepared, const LogFactorCost& factors,
                            const std::vector<double>& u, const std::vector<double>& all_cal, std::size_t ref,
                            CrossSectionCalibration& cal) {
  const std::size_t n = cal.end_members.size();
  const std::size_t p = u.size();
  const std::size_t N = all_cal.size();
  const std::vector<double> J = log_factor_jacobian(prepared, factors, u, N);
  cal.standard_errors.assign(n, 0.0);
  if (N <= p) {
    for (std::size_t i = 0; i < n; ++i) {
      if (i != ref) cal.standard_errors[i] = NAN;
    }
    return;
  }
  Eigen::MatrixXd JtJ = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(p));
  for (std::size_t s = 0; s < N; ++s) {
    for (std::size_t a = 0; a < p; ++a) {
      for (std::size_t b = 0; b < p; ++b) JtJ(a, b) += J[s * p + a] * J[s * p + b];
    }
  }
  double ssr = 0.0;
  for (double x : all_cal) ssr += x * x;
  const double s2 = ssr / static_cast<double>(N - p);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(JtJ);
  const bool singular = !lu.isInvertible();
  const Eigen::MatrixXd cov = singular ? Eigen::MatrixXd() : Eigen::MatrixXd(lu.inverse() * s2);
  for (std::size_t i = 0, j = 0; i < n; ++i) {
    if (i == ref) continue;
    const Eigen::Index jj = static_cast<Eigen::Index>(j++);
    cal.standard_errors[i] = singular ? NAN : cal.factors[i] * std::sqrt(std::max(0.0, cov(jj, jj)));
  }
  if (singular) cal.notes.push_back("J^T J is singular at the optimum: no standard errors");
}

}  // namespace

double cross_section_factor(const MixSettings& settings, const std::string& name) {
  if (settings.cross_section_factors.empty()) return 1.0;
  const auto it = settings.cross_section_factors.find(name);
  if (it == settings.cross_section_factors.end()) {
    std::string known;
    for (const auto& [key, value] : settings.cross_section_factors) known += (known.empty() ? "" : ", ") + key;
    throw InputError("hapke mixing: no cross-section factor for end-member '" + name +
                     "' (factors given for: " + known + ")");
  }
  return it->second;
}

void validate_cross_section_factors(const std::map<std::string, double>& factors, const std::string& field) {
  for (const auto& [name, k] : factors) {
    if (name.empty()) throw FieldError(field, "an end-member name is empty");
    if (!(std::isfinite(k) && k > 0.0))
      throw FieldError(field, fmt::format("factor of '{}' must be > 0, not {}", name, k));
  }
}

double hapke_reflectance_rms(const MixInputs& inputs, const MixSettings& settings, const SpectralDataset& data) {
  MixSettings plain = settings;
  plain.cross_section_factors.clear();
  PreparedMixture pm = prepare(inputs, data, inputs.formulation.name, plain);
  std::vector<double> k(pm.K);
  pm.factor_of.resize(pm.K);
  for (std::size_t j = 0; j < pm.K; ++j) {
    pm.factor_of[j] = j;
    k[j] = cross_section_factor(settings, pm.mixture->component_name(j));
  }
  std::vector<double> r(pm.samples.size());
  pm.residuals(k, r.data());
  return rms_of(r);
}

CrossSectionCalibration calibrate_cross_sections(const std::vector<CalibrationMixture>& mixtures,
                                                 const std::string& reference) {
  if (mixtures.empty()) throw FieldError("mixtures", "give at least one measured mixture");
  CrossSectionCalibration cal;
  const std::vector<PreparedMixture> prepared = prepare_mixtures(mixtures, cal);
  const std::size_t n = cal.end_members.size();
  if (n < 2) throw FieldError("mixtures", "the mixtures have a single end-member: there is no factor to calibrate");
  const std::size_t ref = reference_index(cal, reference);
  require_linked_to_reference(prepared, cal, ref);

  const std::vector<double> u = solve_log_factors(prepared, n, ref, cal);
  const LogFactorCost factors{&prepared.front(), n, ref};
  cal.factors = factors.factors_from(u.data());
  for (std::size_t i = 0, j = 0; i < n; ++i) {
    if (i == ref) continue;
    if (std::abs(u[j++]) > kLogFactorBound * (1.0 - 1e-9)) {
      cal.notes.push_back(fmt::format("the factor of '{}' is at its bound ({:g}): the mixtures barely constrain it",
                                      cal.end_members[i], cal.factors[i]));
    }
  }
  const std::vector<double> all_cal = record_rms(prepared, cal);
  record_standard_errors(prepared, factors, u, all_cal, ref, cal);
  return cal;
}

}  // namespace roadbrdf::mixing
