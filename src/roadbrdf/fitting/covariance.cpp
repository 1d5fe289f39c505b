#include "roadbrdf/fitting/covariance.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "roadbrdf/fitting/cost_functions.h"

namespace roadbrdf::fitting {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Standard errors and correlation from a covariance (p x p, zero rows for fixed parameters).
void set_covariance(const ParameterLayout& L, const Eigen::MatrixXd& cov, WavelengthFit& out) {
  const std::size_t p = L.info.size();
  out.standard_errors.assign(p, kNaN);
  out.correlation.assign(p * p, kNaN);
  for (std::size_t a = 0; a < p; ++a) {
    if (L.fixed[a]) continue;
    const double v = cov(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(a));
    out.standard_errors[a] = v >= 0.0 ? std::sqrt(v) : kNaN;
  }
  for (std::size_t a = 0; a < p; ++a) {
    for (std::size_t b = 0; b < p; ++b) {
      if (L.fixed[a] || L.fixed[b]) continue;
      const double sa = out.standard_errors[a], sb = out.standard_errors[b];
      if (sa > 0.0 && sb > 0.0) {
        out.correlation[a * p + b] = cov(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) / (sa * sb);
      }
    }
  }
}

}  // namespace

void no_covariance(const ParameterLayout& L, WavelengthFit& out, const std::string& why) {
  const std::size_t p = L.info.size();
  out.standard_errors.assign(p, kNaN);
  out.correlation.assign(p * p, kNaN);
  out.covariance_ok = false;
  out.covariance_message = why;
}

void wavelength_covariance(const FitData& d, const ParameterLayout& L, std::size_t w, WavelengthFit& out,
                           const std::vector<double>& free_jacobian) {
  if (out.free_parameters == 0) return no_covariance(L, out, "no free parameter");
  if (out.points <= out.free_parameters)
    return no_covariance(L, out, "no degrees of freedom (points <= free parameters)");
  std::vector<std::size_t> free;
  for (std::size_t k = 0; k < d.p; ++k) {
    if (!L.fixed[k]) free.push_back(k);
  }
  const auto nf = static_cast<Eigen::Index>(free.size());
  const auto n = static_cast<Eigen::Index>(d.n);
  // Jacobian of the residuals at the solution over the free columns (the fixed ones have no
  // covariance), as Ceres' DENSE_SVD covariance of the same cost function would use it.
  Eigen::MatrixXd Jf(n, nf);
  if (free_jacobian.size() == d.n * free.size()) {
    Jf = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(free_jacobian.data(),
                                                                                                  n, nf);
  } else {
    std::vector<double> x = out.parameters;
    std::vector<double> r(d.n), J(d.n * d.p), f(d.n), js(d.n * d.p);
    if (!d.residuals(w, x.data(), r.data(), J.data(), f.data(), js.data())) {
      return no_covariance(L, out, "residuals undefined at the solution");
    }
    for (Eigen::Index g = 0; g < n; ++g) {
      for (Eigen::Index a = 0; a < nf; ++a)
        Jf(g, a) = J[static_cast<std::size_t>(g) * d.p + free[static_cast<std::size_t>(a)]];
    }
  }
  // (J^T J)^-1 = R^-1 R^-T from a Householder QR of J (N x free): the accuracy of an SVD of J (the
  // condition number of J, not its square as inverting J^T J would give), for a few thousand flops
  // instead of a ceres::Covariance problem per wavelength (which computed the same matrix by a
  // dense SVD and was ~40 % of a Hapke fit's CPU).
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Jf);
  const Eigen::MatrixXd R = qr.matrixQR().topRows(nf).triangularView<Eigen::Upper>();
  // Rank check: eigenvalues of J^T J = R^T R, with the reciprocal-condition criterion used before.
  const Eigen::MatrixXd H = R.transpose() * R;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(H, Eigen::EigenvaluesOnly);
  const double emax = es.eigenvalues().cwiseAbs().maxCoeff();
  if (!H.allFinite() || !(emax > 0.0) || !(es.eigenvalues().minCoeff() > 1e-13 * emax)) {
    return no_covariance(L, out, "rank-deficient Jacobian (parameters not separately identifiable at this solution)");
  }
  const Eigen::MatrixXd R_inv = R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(nf, nf));
  const Eigen::MatrixXd c_free = R_inv * R_inv.transpose();
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(d.p), static_cast<Eigen::Index>(d.p));
  for (Eigen::Index a = 0; a < nf; ++a) {
    for (Eigen::Index b = 0; b < nf; ++b) {
      c(static_cast<Eigen::Index>(free[static_cast<std::size_t>(a)]),
        static_cast<Eigen::Index>(free[static_cast<std::size_t>(b)])) = c_free(a, b);
    }
  }
  const double s2 = out.chi2 / static_cast<double>(out.points - out.free_parameters);
  Eigen::MatrixXd cov = c * s2;
  if (!cov.allFinite()) return no_covariance(L, out, "covariance not finite");
  out.covariance_ok = true;
  out.covariance_message.clear();
  set_covariance(L, cov, out);
}

void joint_covariance(const FitData& d, const ParameterLayout& L, std::vector<WavelengthFit>& fits) {
  const std::size_t M = d.m, p = d.p;
  std::vector<std::size_t> lf, sf;  // free local / shared full indices
  for (std::size_t k = 0; k < p; ++k) {
    if (!L.fixed[k]) (L.shared[k] ? sf : lf).push_back(k);
  }
  const auto nl = static_cast<Eigen::Index>(lf.size()), ns = static_cast<Eigen::Index>(sf.size());
  std::size_t n_total = 0;
  double chi2_total = 0.0;
  Eigen::MatrixXd Hss = Eigen::MatrixXd::Zero(ns, ns);
  std::vector<Eigen::MatrixXd> Hll_inv(M), Hls(M);
  std::vector<bool> ok(M, true);
  std::vector<double> r(d.n), J(d.n * p), f(d.n), Js(d.n * p);
  Eigen::MatrixXd schur = Eigen::MatrixXd::Zero(ns, ns);
  for (std::size_t w = 0; w < M; ++w) {
    WavelengthFit& out = fits[w];
    d.residuals(w, out.parameters.data(), r.data(), J.data(), f.data(), Js.data());
    n_total += out.points;  // measured values (missing ones have zero Jacobian rows)
    chi2_total += out.chi2;
    Eigen::MatrixXd Jl(static_cast<Eigen::Index>(d.n), nl), Jsh(static_cast<Eigen::Index>(d.n), ns);
    for (std::size_t g = 0; g < d.n; ++g) {
      for (Eigen::Index i = 0; i < nl; ++i)
        Jl(static_cast<Eigen::Index>(g), i) = J[g * p + lf[static_cast<std::size_t>(i)]];
      for (Eigen::Index i = 0; i < ns; ++i)
        Jsh(static_cast<Eigen::Index>(g), i) = J[g * p + sf[static_cast<std::size_t>(i)]];
    }
    const Eigen::MatrixXd Hll = Jl.transpose() * Jl;
    Hls[w] = Jl.transpose() * Jsh;
    Hss += Jsh.transpose() * Jsh;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Hll);
    const double emax = nl > 0 ? es.eigenvalues().cwiseAbs().maxCoeff() : 1.0;
    if (nl > 0 && !(es.eigenvalues().minCoeff() > 1e-14 * emax)) {
      ok[w] = false;
      continue;
    }
    Hll_inv[w] = nl > 0 ? Eigen::MatrixXd(es.eigenvectors() * es.eigenvalues().cwiseInverse().asDiagonal() *
                                          es.eigenvectors().transpose())
                        : Eigen::MatrixXd(0, 0);
    schur += Hls[w].transpose() * Hll_inv[w] * Hls[w];
  }
  const std::size_t k_total = sf.size() + M * lf.size();
  if (n_total <= k_total) {
    for (auto& out : fits) no_covariance(L, out, "no degrees of freedom");
    return;
  }
  const double s2 = chi2_total / static_cast<double>(n_total - k_total);
  const bool all_ok = std::all_of(ok.begin(), ok.end(), [](bool b) { return b; });
  Eigen::MatrixXd Css;
  bool shared_ok = all_ok;
  if (all_ok && ns > 0) {
    const Eigen::MatrixXd Sm = Hss - schur;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Sm);
    const double emax = es.eigenvalues().cwiseAbs().maxCoeff();
    if (!(es.eigenvalues().minCoeff() > 1e-14 * emax)) {
      shared_ok = false;
    } else {
      Css = es.eigenvectors() * es.eigenvalues().cwiseInverse().asDiagonal() * es.eigenvectors().transpose();
    }
  } else if (ns == 0) {
    Css = Eigen::MatrixXd(0, 0);
  }
  for (std::size_t w = 0; w < M; ++w) {
    WavelengthFit& out = fits[w];
    if (!shared_ok) {
      no_covariance(L, out,
                    all_ok ? "rank-deficient: shared parameters not identifiable"
                           : "rank-deficient Jacobian at some wavelength (parameters not separately identifiable)");
      continue;
    }
    // Blocks of the inverse of [[Hll, Hls], [Hsl, Hss]] (all wavelengths): Css = S^-1,
    // Cll = Hll^-1 + Hll^-1 Hls Css Hsl Hll^-1, Cls = -Hll^-1 Hls Css.
    const Eigen::MatrixXd Bw = Hll_inv[w] * Hls[w];
    const Eigen::MatrixXd Cll = Hll_inv[w] + Bw * Css * Bw.transpose();
    const Eigen::MatrixXd Cls = -Bw * Css;
    Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(p));
    for (Eigen::Index a = 0; a < nl; ++a) {
      const auto ia = static_cast<Eigen::Index>(lf[static_cast<std::size_t>(a)]);
      for (Eigen::Index b = 0; b < nl; ++b)
        cov(ia, static_cast<Eigen::Index>(lf[static_cast<std::size_t>(b)])) = Cll(a, b);
      for (Eigen::Index b = 0; b < ns; ++b) {
        const auto ib = static_cast<Eigen::Index>(sf[static_cast<std::size_t>(b)]);
        cov(ia, ib) = Cls(a, b);
        cov(ib, ia) = Cls(a, b);
      }
    }
    for (Eigen::Index a = 0; a < ns; ++a) {
      for (Eigen::Index b = 0; b < ns; ++b) {
        cov(static_cast<Eigen::Index>(sf[static_cast<std::size_t>(a)]),
            static_cast<Eigen::Index>(sf[static_cast<std::size_t>(b)])) = Css(a, b);
      }
    }
    cov *= s2;
    out.covariance_ok = true;
    out.covariance_message.clear();
    set_covariance(L, cov, out);
  }
}

}  // namespace roadbrdf::fitting
