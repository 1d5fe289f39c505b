// Mixing: predict the BRDF of a road formulation from the fitted BRDFs of its components (report
// sections 1.1, 5.1 and 6.2; domain notes section 2).
//
// End-members. The optical inputs are the distinct fit files of a formulation (a component's own
// measured BRDF, or the mastic that contains it, e.g. the filler and the 0/2 fines in "mastic 1").
// Components sharing a fit file are one end-member; their weights add up. An end-member is named
// after its fit file (file name without ".fit.json"/".json").
//
// Methods (each returns a MixtureModel, mixture_model.h, with a per-wavelength parameter table; one
// source file per method, method_<name>.cpp, behind the method table of method_table.h):
//  areal     Areal (checkerboard) mixing f = sum a_k f_k with area fractions from the formulation:
//            - granular components (aggregate, filler) expose projected area in proportion to
//              M_k / (rho_k D_k): a sphere of diameter D and density rho has projected area per unit
//              mass pi D^2/4 / (rho pi D^3/6) = 3 / (2 rho D), so fine grains expose far more area per
//              kilogram (D = effective_diameter_mm(), formulation.h);
//            - binder and pigment cover a fraction c of the surface ("binder coverage"), shared in
//              proportion to their volumes M/rho; the granular components share 1 - c.
//              Default c = volume fraction of binder + pigment in the formulation (Delesse's
//              principle: on a plane section, area fraction = volume fraction); set it in the
//              formulation ("binder_coverage") or with MixSettings::binder_coverage (0 = clean
//              aggregates, 1 = everything coated).
//  fitted    The same form with weights fitted to a measured mixed sample by non-negative least
//            squares (Lawson-Hanson), one weight set for all wavelengths (default) or one per
//            wavelength, optionally constrained to sum to one. Reports the distance to the areal
//            weights: half the L1 distance between the normalised fitted weights and the areal
//            weights (0 = same proportions, 1 = disjoint), and the sum of the fitted weights.
//            When the measured mixture has sigma, residuals are divided by sigma (weighted least
//            squares, weights 1/sigma^2; MixSettings::use_sigma), for "shadowed" too.
//  mastic    The report's structure: the measured mastic (binder + fines + filler + pigment, i.e.
//            every component that is not a coarse aggregate) plus the coarse aggregate classes
//            (aggregates with d_min >= coarse_min_size_mm), areal mixing between them. The mastic's
//            area fraction m defaults to the volume fraction of its constituents (Delesse); the
//            coarse classes share 1 - m in proportion to M/(rho D). Needs the formulation's "mastic".
//  hapke     Intimate mixing (Hapke 1981 eq. 17): w_k of every end-member inverted from its white-sky
//            albedo with the IMSA-H1 forward model (hapke_imsa.h), mixed with cross-section weights
//            M_k/(rho_k D_k) (Q_E = 1: grains much larger than the wavelength; binder and pigment
//            without a size class use binder_film_thickness_mm as D: a film of thickness t has area
//            per unit mass 1/(rho t)); effective phase terms mixed with weights c_k w_k; see
//            MixtureModel kind "hapke". Calibrated: each weight times a fitted factor k_e
//            (MixSettings::cross_section_factors, calibration.h).
//  shadowed  Nonlinear fitted mixing: MixtureModel kind "shadowed" (the coarse aggregates shadow the
//            matrix at grazing angles through a shared term exp(-s (tan theta_i + tan theta_r))). The
//            end-members are those of the mastic method (matrix = the measured mastic) when the
//            formulation has a "mastic", else the components' fits (matrix = binder and fines);
//            "formulation_weights" are then the mastic or the areal weights.
//            with one weight set for all wavelengths and s fitted with Ceres to the measured mixture
//            (weights >= 0, 0 <= s <= 100; started from the NNLS weights and s = 0, 0.1, 0.3, 1, 3;
//            the lowest cost is kept). Coarse end-members: fit files used only by coarse aggregates.
//
// Wavelengths: with data, the data's wavelengths (each must lie inside every end-member's range); without,
// the union of the end-members' tabulated wavelengths inside their common range (or no wavelength
// dependence when no end-member is spectral).
#pragma once

#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/formulation/formulation.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/mixing/albedo_cache.h"
#include "roadbrdf/mixing/nnls.h"
#include "roadbrdf/mixing/spectral_evaluation.h"
#include "roadbrdf/modelfile/fit_file_read.h"
#include "roadbrdf/models/mixture_model.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf::mixing {

// Loads a fit file (resolved path, selected fit) as a spectral model; default: read_fit_file.
using FitLoader = std::function<SpectralModel(const std::string& path, const std::string& fit_model)>;

struct EndMember {
  std::string name;       // from the fit file's name
  std::string fit_path;   // resolved path
  std::string fit_model;  // selected fit ("" = best)
  std::shared_ptr<const SpectralModel> model;
  std::vector<std::size_t> components;  // indices of the formulation components using it
  bool is_mastic = false;               // the formulation's "mastic" fit
};

struct MixInputs {
  Formulation formulation;
  std::vector<EndMember> end_members;  // the components' distinct fits, then the mastic's if separate
  // End-member white-sky albedos computed so far (hapke inversion, albedo summaries); copies share it.
  std::shared_ptr<AlbedoCache> albedo_cache = std::make_shared<AlbedoCache>();
};

// Load every distinct fit file of the formulation (errors name the formulation key).
MixInputs load_mix_inputs(const Formulation& formulation, const FitLoader& loader = {});
// The FitLoader of fit files, except those given as values: `texts` holds a fit file's JSON text by
// the path a formulation resolves it to, parsed instead of a file read.
FitLoader fit_loader(const std::map<std::string, std::string>& texts);

// The mixing methods, their names (command line, MIX.json) and the line that describes each (MIX.json).
enum class Method { kAreal, kFitted, kMastic, kHapke, kShadowed };
inline constexpr EnumName<Method> kMethodNames[] = {
    {Method::kAreal, "areal",
     "areal mixing, area fractions from the formulation (projected area per mass 3/(2 rho D), binder coverage)"},
    {Method::kFitted, "fitted", "linear mixing, weights fitted to the measured mixture by non-negative least squares"},
    {Method::kMastic, "mastic", "measured mastic + coarse aggregate classes, areal mixing"},
    {Method::kHapke, "hapke",
     "intimate Hapke mixing: w from white-sky albedo (IMSA H1), weights M/(rho D), phase terms by c w"},
    {Method::kShadowed, "shadowed",
     "nonlinear fitted mixing: coarse aggregates shadow the matrix, exp(-s (tan theta_i + tan theta_r))"},
};
constexpr std::span<const EnumName<Method>> enum_names(Method) { return kMethodNames; }

bool method_needs_data(Method method);  // fitted, shadowed
// Linear in the end-members' BRDFs (areal, fitted, mastic; method_table.h MethodEntry::linear).
bool method_is_linear(Method method);

struct MixSettings {
  std::optional<double> binder_coverage;       // overrides the formulation (areal)
  std::optional<double> mastic_area_fraction;  // overrides the formulation (mastic)
  bool per_wavelength = false;                 // fitted: one NNLS per wavelength
  bool sum_to_one = false;                     // fitted, shadowed: weights sum to one
  // fitted, shadowed: when the measured mixture has sigma, each residual f - y is divided by its
  // sigma (weights 1/sigma^2, as `fit` does, fitting/fit.h use_sigma); false: plain least squares.
  bool use_sigma = true;
  std::vector<double> wavelengths;  // output grid [nm]; empty: automatic (see above)
  // hapke: calibrated effective cross-section factor k per end-member name (calibration.h): the
  // weight of end-member e becomes k_e * sum M/(rho D) over its components. Empty: k = 1 for all;
  // otherwise every end-member of the mixture needs one (extra names are ignored).
  std::map<std::string, double> cross_section_factors;
};

struct MixResult {
  Method method = Method::kAreal;
  std::string description;
  std::shared_ptr<const MixtureModel> mixture;
  std::shared_ptr<const SpectralModel> model;  // the mixture with its parameter table
  std::vector<std::string> end_members;        // names, in the mixture's order
  std::vector<std::string> end_member_fits;    // resolved fit paths, same order
  // Weights per end-member: areal fractions; fitted (mean over wavelengths when per wavelength);
  // hapke: normalised cross-section weights c_k.
  std::vector<double> weights;
  // Areal formulation weights of the same end-members (fitted, shadowed): what the fit is compared to.
  std::vector<double> formulation_weights;
  double weight_distance = std::numeric_limits<double>::quiet_NaN();  // see "fitted" above
  double weight_sum = std::numeric_limits<double>::quiet_NaN();
  std::map<std::string, double> settings;  // binder_coverage, mastic_area_fraction, shadowing...
  std::vector<std::string> notes;
};

// Run one method. Methods that need data (fitted, shadowed) use `data`, restricted to the geometry
// indices `training` when given (cross-validation). Throws InputError.
MixResult mix(const MixInputs& inputs, Method method, const MixSettings& settings,
              const SpectralDataset* data = nullptr, const std::vector<std::size_t>* training = nullptr);

// spectral_white_sky_albedo (spectral_evaluation.h) of the mixture of a MixResult, from the
// end-members' albedos (inputs.albedo_cache) where the quadrature allows it: for the linear and hapke kinds f = sum_k
// e_k f_k + f_0(mu0, mu) with coefficients e_k that do not depend on the geometry (e_k = a_k; hapke: c_k / sum c), so
// the same quadrature gives A = sum_k e_k A_k + A(f_0) exactly (to rounding; the delta parts mix with the same e_k,
// mixture_model.h). f_0 (hapke multiple-scattering correction) is cheap. The shadowed kind, or a table whose end-member
// parameters are not the end-members' own, uses the full quadrature.
std::vector<double> mixture_white_sky_albedo(const MixInputs& inputs, const MixResult& result,
                                             const std::vector<double>& wavelengths);

inline constexpr std::size_t kAlbedoWavelengths = 24;

struct Comparison {
  Method method = Method::kAreal;
  int folds = 0;
  double rmse = 0.0;            // held-out (k-fold over geometries) [sr^-1]
  double relative_rmse = 0.0;   // held-out rmse / mean |measured|
  double rmse_in_sample = 0.0;  // all geometries used for fitting and evaluation
  double relative_rmse_in_sample = 0.0;
  // Reduced chi^2 of the held-out residuals, (1 / (N M)) sum ((f - y) / sigma)^2 over every held-out
  // value (no parameter count is subtracted: the held-out values were not used by the fit). NaN
  // when the data have no sigma. About 1 when the method predicts within the measurement noise.
  // Computed from the data's sigma whether or not the fit used it (MixSettings::use_sigma).
  double chi2_reduced = std::numeric_limits<double>::quiet_NaN();
  // Held-out predictions [sr^-1], N x M geometry-major in the data's order (each geometry predicted
  // by the fit that did not see it; methods without fitted parameters: the one prediction), and the
  // fold (1..folds) that held out each geometry (0 for methods without fitted parameters).
  std::vector<double> predicted;
  std::vector<int> fold_of_geometry;
  double albedo = 0.0;  // mean of the mixture's white-sky albedo over the data's
                        // wavelengths (at most kAlbedoWavelengths, evenly spaced in index)
  double albedo_reference = std::numeric_limits<double>::quiet_NaN();   // same for the reference fit
  double albedo_difference = std::numeric_limits<double>::quiet_NaN();  // albedo - albedo_reference
  MixResult result;                                                     // fitted on every geometry
};

// Compare a method with measured data: k-fold cross-validation over geometries (folds >= 2;
// geometries shuffled with a fixed seed; methods without fitted parameters predict every fold the
// same), in-sample errors, held-out reduced chi^2 (data with sigma), albedo, and the albedo
// difference to `reference` (e.g. the fit of the measured mixed sample) when given. `progress`
// counts one unit per mix: 1 + folds for a method fitted to the data, 1 otherwise
// (comparison_mixes).
Comparison compare_method(const MixInputs& inputs, Method method, const MixSettings& settings,
                          const SpectralDataset& data, int folds, unsigned seed = 1,
                          const SpectralModel* reference = nullptr, ProgressCounter* progress = nullptr);
std::size_t comparison_mixes(Method method, int folds);

}  // namespace roadbrdf::mixing
