#include "roadbrdf/mixing/mixture_covariance.h"

#include <limits>
#include <string>
#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/propagation.h"
#include "roadbrdf/models/hapke_imsa.h"

namespace roadbrdf::mixing {

namespace {

constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

// The covariance of `model`'s parameter set at each wavelength of `grid` (grid x P x P):
// sum_j a_lj^2 Sigma_j over the fit wavelengths j it is interpolated from. Exact zeros (fixed
// parameters) stay zero; NaN (undefined) propagates. `interpolated`: some set lies between two j.
std::vector<double> interpolated_covariance(const SpectralModel& model, const std::vector<double>& grid,
                                            bool& interpolated) {
  const std::size_t P = model.model().parameter_count(), PP = P * P;
  const std::vector<double>& covariance = model.parameter_covariance();
  std::vector<double> out(grid.size() * PP, 0.0);
  for (std::size_t l = 0; l < grid.size(); ++l) {
    for (const auto& [j, a] : model.interpolation_weights(grid[l])) {
      if (a == 0.0) continue;
      if (a != 1.0) interpolated = true;
      for (std::size_t e = 0; e < PP; ++e) {
        const double c = covariance[j * PP + e];
        if (c != 0.0) out[l * PP + e] += a * a * c;
      }
    }
  }
  return out;
}

// The single-scattering albedo the hapke method gives each parameter set (the IMSA-H1 inversion of
// its white-sky albedo, method_hapke.cpp); NaN where the albedo cannot be inverted.
std::vector<double> single_scattering_albedos(const Model& model, const std::vector<double>& params,
                                              std::size_t n_sets) {
  std::vector<double> w = white_sky_albedo(model, params.data(), n_sets);
  for (double& x : w) {
    try {
      x = invert_imsa_white_sky_albedo(x);
    } catch (const InputError&) {
      x = kUndefined;
    }
  }
  return w;
}

// The end-member of `inputs` behind position k of the result's mixture.
const EndMember* end_member_of(const MixInputs& inputs, const MixResult& r, std::size_t k) {
  for (const EndMember& e : inputs.end_members) {
    if (e.name == r.end_members[k] && e.fit_path == r.end_member_fits[k]) return &e;
  }
  return nullptr;
}

}  // namespace

void attach_parameter_covariance(const MixInputs& inputs, MixResult& r) {
  const std::string none = "no parameter covariance (albedo and r-table of this method without uncertainty): ";
  if (method_needs_data(r.method)) {
    r.notes.push_back(none +
                      "the weights fitted to the measured mixture have an uncertainty of their own, which is "
                      "not propagated");
    return;
  }
  const std::vector<double>& grid = r.model->wavelengths();
  if (grid.empty()) {
    r.notes.push_back(none + "no end-member depends on wavelength (a fit's covariance is per wavelength)");
    return;
  }
  const MixtureModel& mixture = *r.mixture;
  const std::size_t Pm = mixture.parameter_count(), L = grid.size();
  std::vector<double> covariance(L * Pm * Pm, 0.0);
  auto at = [&](std::size_t l, std::size_t a, std::size_t b) -> double& { return covariance[(l * Pm + a) * Pm + b]; };
  std::vector<std::string> interpolated_members;
  for (std::size_t k = 0; k < mixture.component_count(); ++k) {
    const EndMember* e = end_member_of(inputs, r, k);
    if (!e || e->model->parameter_covariance().empty()) {
      r.notes.push_back(none + "end-member '" + r.end_members[k] +
                        "' has none (a model given by its parameters, or a fit without standard errors)");
      return;
    }
    const SpectralModel& member = *e->model;
    const std::size_t P = member.model().parameter_count(), offset = mixture.component_offset(k);
    bool interpolated = false;
    const std::vector<double> sigma = interpolated_covariance(member, grid, interpolated);
    if (interpolated) interpolated_members.push_back(r.end_members[k]);
    for (std::size_t l = 0; l < L; ++l) {
      for (std::size_t a = 0; a < P; ++a) {
        for (std::size_t b = 0; b < P; ++b) at(l, offset + a, offset + b) = sigma[(l * P + a) * P + b];
      }
    }
    if (mixture.kind() != MixtureKind::kHapke) continue;
    // w_k = W(A_k(p_k)): its variance and covariances with p_k through g = dw_k/dp_k.
    std::vector<double> params;
    for (double wavelength : grid) {
      const std::vector<double> p = member.parameters_at(wavelength);
      params.insert(params.end(), p.begin(), p.end());
    }
    const SetIntegral ssa = [&](const std::vector<double>& p, std::size_t n) {
      return single_scattering_albedos(member.model(), p, n);
    };
    const std::vector<double> g = parameter_gradient(member.model().description(), params, L, sigma, ssa);
    const std::vector<double> u = propagate(g, sigma, L, P);
    const std::size_t s = mixture.ssa_index(k);
    for (std::size_t l = 0; l < L; ++l) {
      at(l, s, s) = u[l] * u[l];
      for (std::size_t b = 0; b < P; ++b) {
        double c = 0.0;
        for (std::size_t a = 0; a < P; ++a) {
          const double sigma_ab = sigma[(l * P + a) * P + b];
          if (sigma_ab != 0.0) c += g[l * P + a] * sigma_ab;  // a fixed parameter contributes nothing
        }
        at(l, s, offset + b) = at(l, offset + b, s) = c;
      }
    }
  }
  auto model = std::make_shared<SpectralModel>(*r.model);
  model->set_parameter_covariance(std::move(covariance));
  r.model = std::move(model);
  std::string note =
      "parameter covariance from the end-members' fits (independent of each other), the formulation's weights "
      "exact";
  if (mixture.kind() == MixtureKind::kHapke) note += ", the single-scattering albedos through their inversion";
  if (!r.settings.empty() && mixture.kind() == MixtureKind::kHapke) {
    for (const auto& [key, value] : r.settings) {
      if (key.rfind("cross_section_factor.", 0) == 0) {
        note += ", the calibrated cross-section factors exact";
        break;
      }
    }
  }
  r.notes.push_back(note);
  for (const std::string& name : interpolated_members) {
    r.notes.push_back("end-member '" + name +
                      "' is interpolated between its fit wavelengths at some output wavelengths: the correlation this "
                      "makes across wavelengths is not carried, so broadband and r-table uncertainties 'independent' "
                      "are approximate there ('correlated' remains an upper bound)");
  }
}

}  // namespace roadbrdf::mixing
