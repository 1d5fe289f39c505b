// End-members prepared once for many mixtures of the same fits: the candidates of a design study
// (python/roadbrdf/studies, docs/studies.md) mix the same few fit files in other proportions, so each
// fit file is read once, and what a mixture's albedo and r-table need from its end-members is computed
// once and combined per mixture.
//
//  - Albedo. A method whose mixture is linear in the end-members' BRDFs (method_is_linear: areal,
//    fitted, mastic; f = sum_k a_k f_k with coefficients a_k that do not depend on the geometry)
//    has, at every wavelength, black-sky and white-sky albedos A = sum_k a_k A_k: the integral of a
//    linear combination (the ideal specular parts mix with the same a_k, mixture_model.h). The A_k
//    are the end-members' integrals over the mixture's own parameter sets (the end-member parameters
//    of its table, wavelength by wavelength), by the same adaptive quadrature and tolerance as the
//    mixture's own integral would use. The result is not bit for bit that of integrating the mixture:
//    the adaptive rule refines where the integrand it is given needs it, so both are the exact value
//    to within their error estimates, and differ by at most the sum of the two (tested). The error
//    estimate of the combination is sum_k |a_k| e_k (triangle inequality). Nonlinear methods (hapke,
//    shadowed) integrate the mixture itself.
//  - r-table. Every mixture kind is evaluated by MixtureModel::evaluate_batch as the end-members'
//    values at the geometries and parameter sets (their own parameters), then combined geometry by
//    geometry. The end-members' values at the r-table's 580 geometries and the weighted wavelengths
//    are kept, and each mixture combines them exactly as evaluate_batch does: the same numbers, bit
//    for bit, for every method.
//
// Uncertainties: the cache shares end-members' values and integrals, not parameter covariances. A
// mixture carries a covariance only when mixed with `mix --uncertainty` (mixture_covariance.h), which
// is opt-in because its albedo uncertainty costs minutes of CPU per mixture; a study's fast path mixes
// without it, so its albedo's *_error values are the quadrature error estimates (sum_k |a_k| e_k for
// a linear method) and its r-table has none.
//
// The cache is safe to share between threads. It keeps every end-member model it has seen alive (its
// entries are keyed by the model and the exact parameter values and geometries).
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

#include "roadbrdf/albedo/report.h"
#include "roadbrdf/mixing/mixing.h"
#include "roadbrdf/photometry/rtable_request.h"

namespace roadbrdf::mixing {

class EndMemberCache {
 public:
  // A FitLoader (mixing.h) that reads each fit file (path, selected fit) once; a file whose size or
  // modification time changed since is read again. A fit given as a value (`texts`: JSON text by path,
  // fit_loader) is parsed once per distinct text.
  FitLoader loader(const std::map<std::string, std::string>& texts = {});

  // Black-sky (white_sky = false) or white-sky albedo of `model` for the parameter sets `params`
  // (n_sets x parameter_count), as albedo::HemisphericalIntegrals computes it, once per distinct input.
  albedo::SpectralIntegral integral(const std::shared_ptr<const Model>& model, const std::vector<double>& params,
                                    std::size_t n_sets, bool white_sky, double theta_s, double phi_s, bool azimuth_mean,
                                    const albedo::QuadratureSettings& settings);

  // Model::evaluate_batch of `model` at the geometries for the parameter sets, once per distinct input.
  std::shared_ptr<const std::vector<double>> values(const std::shared_ptr<const Model>& model,
                                                    const std::vector<Geometry>& geometries,
                                                    const std::vector<double>& params, std::size_t n_sets);

  std::size_t fits_read() const { return fits_read_; }
  std::size_t integrals_computed() const { return integrals_computed_; }
  std::size_t values_computed() const { return values_computed_; }

 private:
  struct Fit {
    long long size = -1;
    long long modified = 0;
    std::shared_ptr<const SpectralModel> model;
  };
  // (model, quantity and angles, tolerance, parameter sets) and (model, geometries, parameter sets).
  using IntegralKey = std::tuple<const Model*, std::vector<double>, std::vector<double>>;
  using ValuesKey = std::tuple<const Model*, std::vector<double>, std::vector<double>>;

  std::mutex mutex_;
  std::map<std::pair<std::string, std::string>, Fit> fits_;
  std::map<IntegralKey, albedo::SpectralIntegral> integrals_;
  std::map<ValuesKey, std::shared_ptr<const std::vector<double>>> values_;
  std::vector<std::shared_ptr<const Model>> models_;  // keeps the keys' models alive
  std::size_t fits_read_ = 0, integrals_computed_ = 0, values_computed_ = 0;
};

// The albedo report (albedo/report.h compute_albedo) of a mixing result, its hemispherical integrals
// from the end-members' (above) when the method is linear, else from the mixture's own quadrature.
nlohmann::json mixture_albedo(const MixResult& result, const albedo::AlbedoRequest& request, EndMemberCache& cache);

// The r-table report (photometry/rtable_request.h rtable_report) of a mixing result, from the
// end-members' values at the table's geometries (above): the numbers rtable_report(*result.model)
// gives.
photometry::RTableReport mixture_rtable(const MixResult& result, const photometry::RTableRequest& request,
                                        EndMemberCache& cache);

// The weighted BRDF of the mixing result at any geometries, from its end-members' values there (kept in
// the cache: the same geometries for many mixtures cost one evaluation of each end-member); the
// numbers photometry::weighted_brdf gives, bit for bit. `cache` must outlive the function.
photometry::WeightedBrdf mixture_weighted_brdf(const MixResult& result, EndMemberCache& cache);

}  // namespace roadbrdf::mixing
