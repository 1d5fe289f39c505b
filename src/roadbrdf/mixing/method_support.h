// Helpers shared by the mixing methods (method_table.h): end-member bookkeeping, weights from the
// formulation (projected area per mass, Delesse coverage), the output wavelength grid, the mixture's
// per-wavelength parameter table and the linear least-squares system of the fitted methods.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "roadbrdf/mixing/method_table.h"
#include "roadbrdf/mixing/mixing.h"

namespace roadbrdf::mixing::detail {

// The output wavelength grid of a method over the given end-members (mixing.h "Wavelengths").
std::vector<double> output_grid(const MixInputs& inputs, const std::vector<std::size_t>& members,
                                const MixSettings& settings, const SpectralDataset* data);

// Per-wavelength parameter table of a mixture: mixing parameters from `mixing(w_index, out)` then
// every end-member's parameters at the wavelength.
SpectralModel build_table(const std::shared_ptr<const MixtureModel>& mixture, const MixInputs& inputs,
                          const std::vector<std::size_t>& members, const std::vector<double>& grid,
                          const std::function<void(std::size_t, double*)>& mixing);

std::shared_ptr<const MixtureModel> make_mixture(MixtureKind kind, const MixInputs& inputs,
                                                 const std::vector<std::size_t>& members,
                                                 const std::vector<bool>& coarse = {});

// End-members used by the components (not the separate mastic fit), in order.
std::vector<std::size_t> component_members(const MixInputs& inputs);
// Position of end-member e in `members` (members.size() when absent).
std::size_t member_position(const std::vector<std::size_t>& members, std::size_t e);
// The end-member a formulation component uses.
std::size_t member_of_component(const MixInputs& inputs, std::size_t component);

// Areal weights on the component end-members (mixing.h "areal"); fills info["binder_coverage"].
std::vector<double> areal_weights(const MixInputs& inputs, const MixSettings& settings,
                                  const std::vector<std::size_t>& members, std::map<std::string, double>& info);

// Mastic method: sets `members` to the mastic, then the coarse classes' fits, and returns their area
// weights (mixing.h "mastic"); fills info["mastic_area_fraction"].
std::vector<double> mastic_weights(const MixInputs& inputs, const MixSettings& settings,
                                   std::vector<std::size_t>& members, std::map<std::string, double>& info,
                                   std::vector<std::string>& notes);

// Weighted least squares setup for linear fits: component values on the training geometries.
struct LinearSystem {
  std::vector<std::size_t> rows;  // geometry indices
  std::size_t M = 0, K = 0;
  std::vector<double> F;  // [row][k][m]
  std::vector<double> y;  // [row][m]
  // [row][m]: residual multiplier: 1/sigma of each measured value (sigma_weighted), else 1; 0 for a
  // missing value (NaN in the data, y = 0 here: masked out). Empty: unweighted and nothing missing.
  std::vector<double> inverse_sigma;
  bool sigma_weighted = false;
  std::size_t measured = 0;  // measured values (rows x M minus the missing ones)
  double multiplier(std::size_t row, std::size_t m) const {
    return inverse_sigma.empty() ? 1.0 : inverse_sigma[row * M + m];
  }
};

LinearSystem linear_system(const MixInputs& inputs, const std::vector<std::size_t>& members,
                           const SpectralDataset& data, const std::vector<std::size_t>* training,
                           const std::vector<double>& grid, bool use_sigma);

// The output grid (`grid`) and linear system of a method fitted to the measured mixture, with the check
// that there are at least as many measured values as weights.
LinearSystem fitted_system(const MethodCall& call, const std::vector<std::size_t>& members, std::vector<double>& grid);

// NNLS over the wavelengths in [m0, m1) of the system, optionally sum-to-one. With sigma, weighted
// least squares: min sum ((sum_k x_k F_k - y) / sigma)^2, i.e. G = A^T W A, h = A^T W y, W = 1/sigma^2.
std::vector<double> solve_weights(const LinearSystem& s, std::size_t m0, std::size_t m1, bool sum_to_one);

// Sets r.weight_sum and r.weight_distance from r.weights and r.formulation_weights (mixing.h "fitted").
void weight_distance(MixResult& r);

}  // namespace roadbrdf::mixing::detail
