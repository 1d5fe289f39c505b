// Losses: the data of one fit, prepared once, and its weighted residuals: the loss (plain, relative,
// log, cosine; see fit.h), the per-point multipliers (sqrt solid-angle weight / sigma [/ |y|] [* cos])
// and the robust function, applied point by point. Internal to fitting/ (the loss names are in fit.h).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "roadbrdf/core/huge_pages.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/models/model.h"

namespace roadbrdf::fitting {

struct FitData {
  const Model* model = nullptr;
  std::size_t p = 0;  // parameter count
  std::size_t n = 0;  // geometries
  std::size_t m = 0;  // wavelengths
  FitLoss loss = FitLoss::kPlain;
  const Geometry* geometries = nullptr;
  // Geometry-only data of `geometries` (Model::prepare), built once and shared by every wavelength,
  // iteration and thread.
  std::shared_ptr<const PreparedGeometries> prepared_geometries;
  // The M x N arrays are filled completely by fit_data() (LargeArray: not zeroed first).
  LargeArray<double> y;           // M x N (wavelength-major: y[w * n + g]) for contiguous access
  LargeArray<double> mult;        // M x N multiplier of the loss residual
  std::vector<double> cos_i;      // N
  LargeArray<double> lin_weight;  // M x N weight of (f - y) in the linearised loss (for the amplitude solve)
  // M x N: 1 where a value was measured, 0 where it is missing (NaN in the dataset). A missing value
  // has y = 0 and mult = lin_weight = 0: its residual and Jacobian row are zero, which is the same
  // least-squares problem as without that geometry at that wavelength; the statistics skip it.
  LargeArray<unsigned char> measured;
  std::vector<std::size_t> measured_count;  // M: measured geometries per wavelength
  bool is_measured(std::size_t w, std::size_t g) const { return measured[w * n + g] != 0; }

  RobustLoss robust = RobustLoss::kNone;
  double robust_b = 1.0;  // scale^2

  // Residuals r[g] (and, if jac != nullptr, jac[g * p + k] = dr/dp_k) of wavelength w at full params.
  // scratch_f: N, scratch_j: N * p. Returns false where the loss is undefined (log of <= 0).
  // With a robust loss rho (and apply_robust), each residual is replaced by sign(r) sqrt(rho(r^2)),
  // so that 1/2 sum of squares is 1/2 sum rho(r_g^2) per point. (Ceres' LossFunction would act on
  // the squared norm of the whole residual block, i.e. of all geometries together.)
  bool residuals(std::size_t w, const double* params, double* r, double* jac, double* scratch_f, double* scratch_j,
                 bool apply_robust = true) const;

  // The same from model values f (N) and, if jac != nullptr, their gradients model_jac (N x p).
  bool residuals_of_values(std::size_t w, const double* f, const double* model_jac, double* r, double* jac,
                           bool apply_robust) const;

  // sum r^2 at params (infinity where the loss is undefined).
  double chi2(std::size_t w, const double* params, bool apply_robust = false) const;
  // The same from model values f (N).
  double chi2_of_values(std::size_t w, const double* f, bool apply_robust = false) const;
};

}  // namespace roadbrdf::fitting
