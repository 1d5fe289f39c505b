// Fitting any model (models/registry.h) to a measured spectral BRDF (io/dataset.h) with Ceres Solver.
//
// Two modes:
//  - per wavelength: one small nonlinear least-squares problem per wavelength, solved in parallel.
//    Each wavelength starts from the solution of the previous one ("warm start") along chains of 32
//    wavelengths; the first wavelength of a chain starts from the first of the previous chain. The
//    chains do not depend on the thread count, and neither do the results (bit for bit);
//  - joint spectral ("shared" parameters): one problem holding the shared parameters once and one
//    block of the other parameters per wavelength. The per-wavelength blocks form the first
//    elimination group of Ceres' Schur-complement solver, so the linear algebra per iteration is
//    W small dense solves plus one |shared| x |shared| system.
//
// Residual of geometry n at wavelength w (f: model, y: measured, c = cos theta_i):
//   plain     r = f - y
//   relative  r = (f - y) / |y|                      (every |y| must be > 0)
//   log       r = ln(1 + f c) - ln(1 + y c)          (Loew et al. 2012, "log" metric; 1 + y c > 0 required)
//   cosine    r = (f - y) c                          (Ngan et al. 2005, cosine-weighted L2)
// then multiplied by sqrt(solid-angle weight) when asked, and divided by sigma_nw when the dataset
// has uncertainties (weights 1/sigma^2). An optional robust loss (Huber or Cauchy with scale s, in
// the units of r) wraps the sum (ceres::HuberLoss / ceres::CauchyLoss).
//
// Solid-angle weights (option): each geometry is a pair of directions (w_i, w_r); its weight is the
// product of the solid-angle cell of its incidence direction among the distinct incidence
// directions and of its reflection direction among the reflection directions measured at that
// incidence. Each cell is estimated by the nearest-neighbour disc: pi (d/2)^2 with d the chord
// distance to the nearest other direction (a direction measured alone gets weight 1 for that factor;
// duplicated directions share their cell). Weights are scaled to mean 1.
//
// Statistics (per wavelength): on the raw differences f - y [sr^-1]: RMSE, relative RMSE
// (RMSE / mean |y|), maximum relative error max |f - y| / |y| over |y| > 0, R^2 = 1 - SS_res/SS_tot;
// on the weighted residuals r of the chosen loss (without the robust function): chi2 = sum r^2,
// AIC = n ln(chi2/n) + 2k and BIC = n ln(chi2/n) + k ln n (Gaussian likelihood with unknown variance,
// k = number of free parameters). Standard errors: sqrt of the diagonal of the covariance
// (J^T J)^-1 s^2, s^2 = chi2/(n - k) (as scipy's curve_fit with absolute_sigma=False), computed by
// a Householder QR of the Jacobian (per wavelength) or by the block Schur formula (joint mode); when J^T J is rank
// deficient the standard errors are NaN and `covariance_ok` is false with a reason.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/core/coverage.h"
#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/models/model.h"

namespace roadbrdf {

// The residual r of a measured value y and the model's value f (see the header comment).
enum class FitLoss { kPlain, kRelative, kLog, kCosine };
inline constexpr EnumName<FitLoss> kFitLossNames[] = {
    {FitLoss::kPlain, "plain", "f-y"},
    {FitLoss::kRelative, "relative", "(f-y)/y"},
    {FitLoss::kLog, "log", "ln(1+f cos)-ln(1+y cos), Loew 2012"},
    {FitLoss::kCosine, "cosine", "(f-y) cos, Ngan 2005"},
};
constexpr std::span<const EnumName<FitLoss>> enum_names(FitLoss) { return kFitLossNames; }

// The function of the residuals that is minimised: their squares, or a robust function of them
// that grows slower beyond a scale (Huber: linearly; Cauchy: logarithmically).
enum class RobustLoss { kNone, kHuber, kCauchy };
inline constexpr EnumName<RobustLoss> kRobustLossNames[] = {
    {RobustLoss::kNone, "none", "least squares"},
    {RobustLoss::kHuber, "huber", "quadratic within the scale, linear beyond"},
    {RobustLoss::kCauchy, "cauchy", "logarithmic beyond the scale"},
};
constexpr std::span<const EnumName<RobustLoss>> enum_names(RobustLoss) { return kRobustLossNames; }

// The linear solver of a joint fit (Schur complement, per-wavelength blocks eliminated first). Dense
// is the default: the reduced system has the size of the shared block. Iterative is EXPERIMENTAL: on
// a small test problem Ceres 2.1 stopped with "Numerical failure, rho = r'z = 0".
enum class JointSolver { kDenseSchur, kSparseSchur, kIterativeSchur };
inline constexpr EnumName<JointSolver> kJointSolverNames[] = {
    {JointSolver::kDenseSchur, "dense-schur", "dense Schur complement"},
    {JointSolver::kSparseSchur, "sparse-schur", "sparse Schur complement"},
    {JointSolver::kIterativeSchur, "iterative-schur",
     "conjugate gradients on the Schur complement, Jacobi preconditioner"},
};
constexpr std::span<const EnumName<JointSolver>> enum_names(JointSolver) { return kJointSolverNames; }

// A name of kFitLossNames, in any letter case; throws FieldError(field, ...).
FitLoss fit_loss_from_string(const std::string& name, const std::string& field = "loss");
// "huber:S" | "cauchy:S" (S > 0, in residual units) or "none" (or ""), in any letter case; throws
// FieldError(field, ...).
void robust_loss_from_string(const std::string& text, RobustLoss& kind, double& scale,
                             const std::string& field = "robust");

// The counts a fit accepts, so that a request too large for the memory or a lifetime is refused
// before the work: each start is a whole fit (the Latin hypercube holds every start's parameters at
// once), each iteration a Ceres step, each thread a Ceres problem in memory.
inline constexpr int kMaxMultistart = 10000;
inline constexpr int kMaxFitThreads = 1024;
inline constexpr int kMaxFitIterations = 100000;
// Throws FieldError("multistart" / "threads" / "max_iterations") for a count outside [1, its limit].
void check_fit_counts(int multistart, int threads, int max_iterations);

struct FitOptions {
  FitLoss loss = FitLoss::kPlain;
  RobustLoss robust = RobustLoss::kNone;
  double robust_scale = 1.0;
  bool use_sigma = true;             // 1/sigma^2 weights when the dataset has sigma
  bool solid_angle_weights = false;  // see the header comment
  // Parameters held at a value (name -> value), at every wavelength.
  std::map<std::string, double> fixed;
  // Starting values (name -> value); the model's defaults for the rest. Must lie inside the bounds.
  std::map<std::string, double> start;
  // Bounds (name -> [lower, upper]) replacing a parameter's default fitting range, narrower or wider,
  // inside its physical range (ModelDescription::physical_range: model metadata); a default start
  // outside them is moved to the middle of the interval (a given start must lie inside).
  std::map<std::string, std::pair<double, double>> bounds;
  // Parameter names shared across wavelengths: non-empty selects the joint spectral mode.
  std::vector<std::string> shared;
  // Number of starting points (1 to kMaxMultistart): the first is the given start (or, per wavelength, the warm
  // start), the others a Latin hypercube over the free nonlinear parameters within their bounds
  // (seeded). Free linear amplitudes are solved by bounded linear least squares for every start.
  int multistart = 1;
  unsigned seed = 1;
  bool solve_linear = true;  // bounded linear least squares for the amplitudes of every start
  bool warm_start = true;    // per wavelength: start from the previous wavelength's solution
  JointSolver joint_solver = JointSolver::kDenseSchur;  // joint mode
  int threads = 1;  // per-wavelength mode (the results do not depend on it); joint mode: 1
  int max_iterations = 200;
  double function_tolerance = 1e-10;
  double gradient_tolerance = 1e-12;
  double parameter_tolerance = 1e-10;
  bool compute_covariance = true;
  // Called from the calling thread with (wavelengths done, total) while fitting.
  std::function<void(std::size_t, std::size_t)> progress;
};

// Result at one wavelength. Vectors are indexed like the model's parameters.
struct WavelengthFit {
  double wavelength = 0.0;  // nm
  std::vector<double> parameters;
  std::vector<double> standard_errors;  // NaN for fixed parameters and when the covariance failed
  std::vector<double> correlation;      // p x p row-major (NaN where undefined)
  bool covariance_ok = false;
  std::string covariance_message;   // why it failed (rank deficiency...)
  std::size_t points = 0;           // geometries used (measured at this wavelength)
  std::size_t free_parameters = 0;  // counted in AIC/BIC (joint mode: this wavelength's + shared)
  double cost = 0.0;                // Ceres' final cost, 1/2 sum rho(r^2)
  double chi2 = 0.0;                // sum r^2 of the loss residuals (no robust function)
  double rmse = 0.0;                // sr^-1
  double relative_rmse = 0.0;       // 1
  double max_relative_error = 0.0;  // 1
  double r_squared = 0.0;           // 1 (NaN when the data are constant)
  double aic = 0.0;
  double bic = 0.0;
  int iterations = 0;
  bool converged = false;
  std::string status;                  // Ceres termination message
  std::vector<std::string> at_bounds;  // free parameters ending on a bound: "name=lower" / "name=upper"
  int start_index = 0;                 // which multi-start point won (0: the given/warm start)
  // Every free nonlinear parameter ended at its given starting value (to 1e-9): a "converged" fit
  // that never moved, i.e. data that do not constrain those parameters (warned about).
  bool stayed_at_start = false;
};

struct FitResult {
  std::string model;
  // The geometry group fitted (`fit --group-by`, io/geometry_selection.h): column -> value [deg];
  // empty when the fit used every geometry of the dataset (after any `where` selection).
  std::vector<std::pair<std::string, double>> group;
  OptionSet options;  // resolved model options
  std::vector<std::string> parameter_names;
  std::vector<std::string> parameter_units;
  std::vector<std::string> fixed;   // fixed parameter names
  std::vector<std::string> shared;  // shared parameter names (joint mode)
  FitOptions settings;              // as used (progress callback dropped)
  std::vector<WavelengthFit> wavelengths;
  // Totals over all wavelengths and geometries.
  double rmse_total = 0.0;           // sr^-1, over all points
  double relative_rmse_total = 0.0;  // rmse_total / mean |y|
  double max_relative_error_total = 0.0;
  double chi2_total = 0.0;
  double aic_total = 0.0;  // n ln(chi2/n) summed per wavelength + 2 k_total (k_total counts shared once)
  double bic_total = 0.0;
  std::size_t points_total = 0;    // measured values fitted (missing values excluded)
  std::size_t missing_values = 0;  // NaN values of the dataset, masked out of the fit at their wavelength
  std::size_t free_parameters_total = 0;
  std::size_t converged_count = 0;
  std::size_t at_bound_count = 0;  // wavelengths with at least one parameter on a bound
  std::size_t covariance_failures = 0;
  std::size_t stayed_at_start_count = 0;  // converged wavelengths with stayed_at_start
  // Models of the same request (and group) that this model contains (it equals them at some parameter
  // values: a composite its components, Oren-Nayar Lambert; ModelDescription::reduces_to) and whose fit
  // has a lower total relative RMSE (by more than 0.1 % + 1e-6): this fit missed its optimum (set by
  // run_fit, fitting/fit_request.h).
  std::vector<std::string> worse_than_nested;
  AngularCoverage coverage;  // of the geometries measured at one wavelength at least
  double seconds = 0.0;      // wall time of fit_model
  double cpu_seconds = 0.0;  // process CPU time during fit_model (all threads; noisy machines: compare this)
  bool joint = false;
  // Joint mode: iterations and status of the single problem.
  int joint_iterations = 0;
  std::string joint_status;
};

// Fit `model` to every wavelength of `data`. A NaN value is a measurement not made: it is masked out
// of the fit at its wavelength (the same solution as without that geometry at that wavelength) and
// counted in FitResult::missing_values. Throws InputError for unusable input (infinite data, unknown
// or out-of-bounds parameter names, fewer points than free parameters, relative loss with zero data...).
FitResult fit_model(const Model& model, const SpectralDataset& data, const FitOptions& options);

// Solid-angle weights of the geometries (see the header comment), mean 1.
std::vector<double> solid_angle_weights(const std::vector<Geometry>& geometries);

// Model values at the fitted parameters: N x M (geometry-major), like SpectralDataset::brdf.
std::vector<double> fitted_values(const Model& model, const SpectralDataset& data, const FitResult& fit);

// The indices of the `wanted` wavelengths [nm] in the dataset's, in increasing order. A wanted
// wavelength is found to 1e-6 nm; with `notes`, one that is not on the grid but within its widest gap
// of a band is answered by the nearest band, with a note ("600 nm: nearest band 610 nm"; a band is
// used once however many wavelengths it answers; of two equally near bands, the shorter). Without `notes`, or farther
// from every band, it is an error. Text such as "400:1000:10" is parsed by parse_range_list (core/range.h). Throws
// FieldError("wavelengths", ...).
std::vector<std::size_t> select_wavelengths(const std::vector<double>& available, const std::vector<double>& wanted,
                                            std::vector<std::string>* notes = nullptr);
// The dataset restricted to some wavelength indices.
SpectralDataset subset_wavelengths(const SpectralDataset& data, const std::vector<std::size_t>& indices);

}  // namespace roadbrdf
