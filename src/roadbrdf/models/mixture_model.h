// MixtureModel: the BRDF of a mixed road surface as a roadbrdf::Model built from K end-member models
// (the models of the components' fit files). It is an ordinary Model, so a SpectralModel holding a
// MixtureModel and a per-wavelength parameter table is evaluated by every command that takes a
// SpectralModel (albedo, r-tables, figures): wavelength enters exactly as for a fit, through the
// parameter table (weights, single-scattering albedos and every end-member parameter per wavelength).
//
// Parameter vector (names as in MIX.json):
//   weight.<name>      K weights (unit 1): area fractions (linear, shadowed) or normalised
//                      cross-section weights c_k = (M_k / rho_k D_k) / sum_j (M_j / rho_j D_j) (hapke)
//   ssa.<name>         K single-scattering albedos w_k (hapke only)
//   shadowing          shadowing coefficient s >= 0 (shadowed only, not spectral)
//   <name>.<param>     every parameter of end-member k, in its model's order
//
// Kinds (f_k = BRDF of end-member k at its own parameters; mu0 = cos theta_i, mu = cos theta_r):
//   linear    f = sum_k a_k f_k                                                  (areal mixing)
//   hapke     f = sum_k c_k f_k + [w H(mu0; w) H(mu; w) - sum_k c_k w_k H(mu0; w_k) H(mu; w_k)]
//                                  / (4 pi (mu0 + mu)),   w = sum_k c_k w_k,  H = H1 (hapke_imsa.h)
//             This is Hapke's intimate mixture (Hapke 1981 eq. 17; domain notes section 2) written
//             without dividing by w_k: with the IMSA decomposition of each end-member,
//             f_k = (w_k / 4pi) [P_k + H_k(mu0) H_k(mu) - 1] / (mu0 + mu), where P_k(geometry) is the
//             end-member's effective single-scattering phase term (its phase function with opposition
//             and roughness effects, whatever model was fitted), the mixture of the P_k weighted by
//             c_k w_k and of the w_k weighted by c_k gives exactly the expression above. Single
//             scattering therefore mixes linearly in cross-section; multiple scattering is replaced by
//             that of the mixed albedo (nonlinear: a dark binder darkens bright fines far more than a
//             linear mix). Equal w_k give the linear mixture sum_k c_k f_k; one end-member gives f_1.
//             The c_k are normalised internally (c_k / sum_j c_j), so only their ratios matter.
//   shadowed  f = S sum_{k in matrix} a_k f_k + sum_{k coarse} a_k [1 + (1 - S) A_m / A_c] f_k,
//             S = exp(-s (tan theta_i + tan theta_r)),  A_m = sum_matrix a_k,  A_c = sum_coarse a_k.
//             The coarse aggregates shadow and hide the matrix (binder, mastic, fines) between them:
//             S is the fraction of the matrix both lit and seen (independent shadowing and masking,
//             exponential in the path tangent as for randomly placed protrusions; no hot-spot
//             correlation); the hidden matrix area is seen as coarse-grain tops instead, shared in
//             proportion to a_k. At normal incidence and view S = 1 and the weights are the a_k.
//             If no end-member is coarse, S does not enter (f = sum a_k f_k).
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/models/model.h"

namespace roadbrdf::mixing {

// The model's name is "mixture-" and its kind's name, its summary the kind's description.
enum class MixtureKind { kLinear, kHapke, kShadowed };
inline constexpr EnumName<MixtureKind> kMixtureKindNames[] = {
    {MixtureKind::kLinear, "linear", "areal (linear) mixture of end-member BRDFs"},
    {MixtureKind::kHapke, "hapke", "intimate (Hapke) mixture of end-member BRDFs"},
    {MixtureKind::kShadowed, "shadowed", "areal mixture with shadowing of the matrix by coarse aggregates"},
};
constexpr std::span<const EnumName<MixtureKind>> enum_names(MixtureKind) { return kMixtureKindNames; }

class MixtureModel final : public Model {
 public:
  // names[k] names end-member k in parameter names; coarse[k] marks coarse end-members (shadowed only;
  // empty = none coarse).
  MixtureModel(MixtureKind kind, std::vector<std::shared_ptr<const Model>> components, std::vector<std::string> names,
               std::vector<bool> coarse = {});

  double evaluate(const double* params, const Geometry& g) const override;
  double evaluate_with_gradient(const double* params, const Geometry& g, double* gradient) const override;
  void evaluate_batch(const Geometry* geometries, std::size_t n_geometries, const double* params, std::size_t n_sets,
                      double* out) const override;
  void evaluate_batch_with_gradient(const Geometry* geometries, std::size_t n_geometries, const double* params,
                                    double* values, double* jacobian) const override;
  double delta_reflectance(const double* params, double cos_theta_i) const override;

  MixtureKind kind() const { return kind_; }
  std::size_t component_count() const { return components_.size(); }
  const Model& component(std::size_t k) const { return *components_[k]; }
  std::shared_ptr<const Model> component_ptr(std::size_t k) const { return components_[k]; }
  const std::string& component_name(std::size_t k) const { return names_[k]; }
  bool is_coarse(std::size_t k) const { return coarse_[k]; }
  const std::vector<bool>& coarse_flags() const { return coarse_; }

  std::size_t weight_index(std::size_t k) const { return k; }
  std::size_t ssa_index(std::size_t k) const { return components_.size() + k; }  // hapke only
  std::size_t shadowing_index() const { return components_.size(); }             // shadowed only
  // First parameter of end-member k.
  std::size_t component_offset(std::size_t k) const { return offsets_[k]; }
  // Number of mixture-level parameters (before the first end-member's).
  std::size_t mixing_parameter_count() const { return offsets_.empty() ? 0 : offsets_[0]; }

  // The mixture value from the end-member values f[k] at one geometry; d_df (optional, K values)
  // receives df/df_k.
  double combine(const double* params, const Geometry& g, const double* f, double* d_df) const;

  // Geometry-dependent factor S of the shadowed kind (1 for the other kinds).
  static double shadowing_factor(double s, const Geometry& g);

  // At a grazing geometry (theta_i or theta_r = 90 deg), whether an end-member value f[k] is exactly 0
  // while that end-member declares a grazing zero (ModelDescription::grazing_zero): the end-member
  // diverges there (or tends to 0) and the mixture's value is 0, as its description declares (the
  // conservative reading: where the declaring end-member's 0 is a true limit of 0, the other
  // end-members' part is dropped too; a fit leaves grazing geometries out, fit_request.h).
  bool grazing_zero_at(const Geometry& g, const double* f) const;

 private:
  static ModelDescription make_description(MixtureKind kind,
                                           const std::vector<std::shared_ptr<const Model>>& components,
                                           const std::vector<std::string>& names);
  MixtureKind kind_;
  std::vector<std::shared_ptr<const Model>> components_;
  std::vector<std::string> names_;
  std::vector<bool> coarse_;
  std::vector<std::size_t> offsets_;
  std::size_t max_component_parameters_ = 0;
};

}  // namespace roadbrdf::mixing
