#include "roadbrdf/fitting/losses.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <string>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/number.h"

namespace roadbrdf::fitting {

bool FitData::residuals(std::size_t w, const double* params, double* r, double* jac, double* scratch_f,
                        double* scratch_j, bool apply_robust) const {
  if (jac != nullptr) {
    model->evaluate_prepared_with_gradient(*prepared_geometries, params, scratch_f, scratch_j);
  } else {
    model->evaluate_prepared(*prepared_geometries, params, scratch_f);
  }
  return residuals_of_values(w, scratch_f, jac != nullptr ? scratch_j : nullptr, r, jac, apply_robust);
}

bool FitData::residuals_of_values(std::size_t w, const double* f_values, const double* model_jac, double* r,
                                  double* jac, bool apply_robust) const {
  const double* yw = y.data() + w * n;
  const double* mw = mult.data() + w * n;
  for (std::size_t g = 0; g < n; ++g) {
    const double f = f_values[g];
    double d = 0.0;  // dr/df
    if (loss == FitLoss::kLog) {
      const double c = cos_i[g];
      const double a = 1.0 + f * c;
      if (!(a > 0.0) || !std::isfinite(f)) return false;
      r[g] = mw[g] * (std::log(a) - std::log(1.0 + yw[g] * c));
      d = mw[g] * c / a;
    } else {
      if (!std::isfinite(f)) return false;
      r[g] = mw[g] * (f - yw[g]);
      d = mw[g];
    }
    if (apply_robust && robust != RobustLoss::kNone) {
      const double sq = r[g] * r[g];
      double rho = sq, drho = 1.0;
      if (robust == RobustLoss::kHuber) {
        if (sq > robust_b) {
          const double root = std::sqrt(sq * robust_b);
          rho = 2.0 * root - robust_b;
          drho = robust_b / root;
        }
      } else {
        rho = robust_b * std::log1p(sq / robust_b);
        drho = 1.0 / (1.0 + sq / robust_b);
      }
      const double rt = std::sqrt(rho);
      if (sq > 0.0) d *= drho * std::fabs(r[g]) / rt;
      r[g] = r[g] < 0.0 ? -rt : rt;
    }
    if (jac != nullptr) {
      const double* js = model_jac + g * p;
      double* jr = jac + g * p;
      for (std::size_t k = 0; k < p; ++k) jr[k] = d * js[k];
    }
  }
  return true;
}

double FitData::chi2(std::size_t w, const double* params, bool apply_robust) const {
  std::vector<double> f(n);
  model->evaluate_prepared(*prepared_geometries, params, f.data());
  return chi2_of_values(w, f.data(), apply_robust);
}

double FitData::chi2_of_values(std::size_t w, const double* f, bool apply_robust) const {
  std::vector<double> r(n);
  if (!residuals_of_values(w, f, nullptr, r.data(), nullptr, apply_robust)) {
    return std::numeric_limits<double>::infinity();
  }
  double s = 0.0;
  for (double v : r) s += v * v;
  return s;
}

}  // namespace roadbrdf::fitting

namespace roadbrdf {

namespace {

std::string lower_case(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

FitLoss fit_loss_from_string(const std::string& name, const std::string& field) {
  return parse_name<FitLoss>(lower_case(name), field);
}

void robust_loss_from_string(const std::string& text, RobustLoss& kind, double& scale, const std::string& field) {
  const std::string s = lower_case(text);
  kind = RobustLoss::kNone;
  scale = 1.0;
  if (s.empty()) return;
  // (An iterator search: g++ 12 warns falsely, -Wstringop-overread, on s.find(':') here.)
  const auto colon = std::find(s.begin(), s.end(), ':');
  const std::string name(s.begin(), colon);
  kind = parse_name<RobustLoss>(name, field);
  if (kind == RobustLoss::kNone) {
    if (colon != s.end()) throw FieldError(field, "'" + text + "' takes no scale");
    return;
  }
  if (colon == s.end()) throw FieldError(field, "'" + text + "' needs a scale, e.g. " + name + ":0.01");
  const std::string number(colon + 1, s.end());
  double v = 0.0;
  if (!parse_finite_double(number, v) || !(v > 0.0)) {
    throw FieldError(field, "the scale '" + number + "' must be a positive number");
  }
  scale = v;
}

}  // namespace roadbrdf
