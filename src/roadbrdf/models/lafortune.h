// Lafortune generalised cosine lobes plus a Lambertian term.
//
// E. P. F. Lafortune, S.-C. Foo, K. E. Torrance, D. P. Greenberg, "Non-linear approximation of
// reflectance functions", SIGGRAPH 1997, eq. 4 (one lobe) and the sum of lobes of section 4:
//
//   f = k_d / pi + sum_k rho_k max(0, C_x,k w_rx w_ix + C_y,k w_ry w_iy + C_z,k w_rz w_iz)^{n_k}
//
// with both w_i and w_r pointing away from the surface (library convention, and the paper's u, v).
// The report's eq. 3.25 is garbled (it writes dot products instead of component products, and its
// eq. 3.26 clamps the sum instead of each lobe); we follow the paper (docs/report-corrections.md):
// each lobe is clamped at 0 before the power. C_x = C_y < 0, C_z > 0 gives a forward (off-)specular
// lobe (C_x = C_y = -1, C_z = 1 peaks at the mirror direction with base exactly 1); C_x = C_y > 0 a
// retro lobe; C_x = C_y = 0 a generalised diffuse lobe. The paper's (n+2)/(2 pi) normalisation is
// absorbed in rho_k and C (so rho_k is in sr^-1: the lobe's value where its base is 1).
// k_d is a diffuse albedo (f_d = k_d / pi), as in the report's dry/wet road sets (rho_d = 0.2).
//
// Options: lobes = 1..4; isotropic = yes (C_y = C_x, no cy parameters) | no.
// Parameters: kd, then for k = 1..lobes: rhok, cxk, [cyk,] czk, nk.
// Reciprocal (the base is symmetric in w_i, w_r); not energy conserving in general (rho_k and C are
// free); non-negative (rho_k >= 0, clamped base).
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/parameters.h"

namespace roadbrdf {

struct Lafortune {
  static constexpr const char* kName = "lafortune";
  static constexpr int kMaxLobes = 4;
  static constexpr int kMaxParametersPerLobe = 5;  // rho, cx, cy, cz, n
  static constexpr int kMaxParameters = 1 + kMaxLobes * kMaxParametersPerLobe;
  // Bounds chosen so that no lobe can overflow a double: the lobe base sum_k C_k u_k v_k is at most
  // max_k |C_k| for unit vectors u, v, and 1.5^1000 ~ 1e176. Lafortune et al.'s fitted lobes have
  // |C| ~ 1 and n up to a few hundred.
  static constexpr double kMaxCoefficient = 1.5;
  static constexpr double kMaxExponent = 1000.0;
  static constexpr double kMaxLobeAmplitude = 1000.0;

  static std::vector<OptionInfo> options() {
    return {{"lobes", "number of generalised cosine lobes (integer 1..4)", {}, "1"},
            {"isotropic",
             "yes: C_y = C_x for every lobe (isotropic); no: separate C_x and C_y (anisotropic)",
             {"yes", "no"},
             "yes"}};
  }

  static int lobe_count(const OptionSet& options) { return integer_option(kName, options, "lobes", 1, kMaxLobes); }
  static bool is_isotropic(const OptionSet& options) { return options.at("isotropic") == "yes"; }

  static ModelDescription describe(const OptionSet& options) {
    const int lobes = lobe_count(options);
    const bool isotropic = is_isotropic(options);
    // Default lobes: 1 forward specular (the report's dry road), 2 retro, 3 broad forward, 4 generalised diffuse.
    struct LobeDefault {
      double rho, cx, cz, n;
    };
    const LobeDefault defaults[kMaxLobes] = {
        {0.3, -1.0, 1.0, 5.0}, {0.1, 1.0, 1.0, 5.0}, {0.1, -1.0, 1.0, 1.0}, {0.1, 0.0, 1.0, 1.0}};
    ModelDescription d;
    d.summary = "Lafortune generalised cosine lobes (" + std::to_string(lobes) +
                (isotropic ? ", isotropic" : ", anisotropic") + ") + Lambertian term";
    d.citation =
        "Lafortune et al., SIGGRAPH 1997, eq. 4 (report eq. 3.25-3.26 garbled; per-lobe clamp as in the paper)";
    d.parameters.push_back(
        {"kd", "1", "diffuse albedo k_d of the Lambertian term (f_d = k_d/pi)", 0.2, 0.0, 1.0, true, true});
    for (int k = 0; k < lobes; ++k) {
      const std::string s = std::to_string(k + 1);
      const LobeDefault& def = defaults[k];
      d.parameters.push_back({"rho" + s, "sr^-1",
                              "amplitude of lobe " + s +
                                  " (BRDF value where the lobe base is 1, e.g. at the mirror "
                                  "direction for C = (-1,-1,1))",
                              def.rho, 0.0, kMaxLobeAmplitude, true, true});
      d.parameters.push_back(
          {"cx" + s, "1",
           std::string("coefficient C_x of lobe ") + s +
               (isotropic ? " (also C_y); < 0 forward, > 0 retro" : " (surface x axis); < 0 forward"),
           def.cx, -kMaxCoefficient, kMaxCoefficient, false, false});
      if (!isotropic) {
        d.isotropic_when_equal.emplace_back("cx" + s, "cy" + s);  // C_x = C_y: a lobe symmetric about the normal
        d.parameters.push_back({"cy" + s, "1", "coefficient C_y of lobe " + s + " (surface y axis); < 0 forward",
                                def.cx, -kMaxCoefficient, kMaxCoefficient, false, false});
      }
      d.parameters.push_back({"cz" + s, "1", "coefficient C_z of lobe " + s + " (normal component)", def.cz,
                              -kMaxCoefficient, kMaxCoefficient, false, false});
      d.parameters.push_back(
          {"n" + s, "1", "exponent n of lobe " + s + " (larger = narrower)", def.n, 0.0, kMaxExponent, false, false});
    }
    d.isotropic = isotropic;
    d.reciprocal = true;
    d.energy_conserving = false;  // rho_k and C are unconstrained: the albedo can exceed 1
    d.non_negative = true;
    return d;
  }

  explicit Lafortune(const OptionSet& options) : lobes_(lobe_count(options)), isotropic_(is_isotropic(options)) {}

  // The geometry enters only through the component products w_r,x w_i,x, w_r,y w_i,y, w_r,z w_i,z.
  struct Prepared {
    double px = 0.0, py = 0.0, pz = 0.0;
  };
  Prepared prepare(const Geometry& g) const { return {g.wr.x * g.wi.x, g.wr.y * g.wi.y, g.wr.z * g.wi.z}; }

  template <typename T>
  T operator()(const T* p, const Geometry& g) const {
    return (*this)(p, prepare(g));
  }

  template <typename T>
  T operator()(const T* p, const Prepared& g) const {
    using std::pow;
    T f = p[0] * kInvPi;
    for (int k = 0; k < lobes_; ++k) {
      const Lobe<T> lobe = lobe_of(p, k);
      const T base = lobe.cx * g.px + lobe.cy * g.py + lobe.cz * g.pz;
      // Per-lobe clamp (paper eq. 4). At base <= 0 the lobe and its gradient are 0 (also for n = 0,
      // where max(0, base)^0 is taken as 0 to keep the clamp).
      if (scalar_value(base) > 0.0) f += lobe.rho * pow(base, lobe.n);
    }
    return f;
  }

  // The analytic gradient (model.h, HasSharedTerms): nothing is shared between geometries, but the
  // derivative of each lobe rho b^n is written out instead of differentiated with Jets, where the
  // generic Jet pow costs most of a fit's time:
  //   d/d rho = b^n,  d/dC_x = rho n b^(n-1) p_x (isotropic: p_x + p_y),  d/dC_y = rho n b^(n-1) p_y,
  //   d/dC_z = rho n b^(n-1) p_z,  d/dn = rho b^n ln b,  d/dk_d = 1/pi;  all 0 where the lobe is clamped.
  // The values are operator()'s, bit for bit (same operations in the same order).
  struct SharedTerms {};
  SharedTerms share(const Prepared*, std::size_t) const { return {}; }

  void evaluate_shared(const SharedTerms&, const Prepared* g, std::size_t n, const double* p, double* values,
                       double* jacobian) const {
    const std::size_t stride = isotropic_ ? 4 : 5;
    const std::size_t count = 1 + static_cast<std::size_t>(lobes_) * stride;
    for (std::size_t m = 0; m < n; ++m) {
      const Prepared& q = g[m];
      double f = p[0] * kInvPi;
      double* row = jacobian == nullptr ? nullptr : jacobian + m * count;
      if (row != nullptr) {
        for (std::size_t k = 0; k < count; ++k) row[k] = 0.0;
        row[0] = kInvPi;
      }
      for (int k = 0; k < lobes_; ++k) {
        const Lobe<double> lobe = lobe_of(p, k);
        const double base = lobe.cx * q.px + lobe.cy * q.py + lobe.cz * q.pz;
        if (!(base > 0.0)) continue;
        const double power = std::pow(base, lobe.n);
        f += lobe.rho * power;
        if (row == nullptr) continue;
        double* d = row + 1 + static_cast<std::size_t>(k) * stride;
        const double slope = lobe.rho * (lobe.n * power / base);  // rho d(b^n)/db = rho n b^(n-1), b > 0
        d[0] = power;
        if (isotropic_) {
          d[1] = slope * (q.px + q.py);
          d[2] = slope * q.pz;
          d[3] = lobe.rho * (power * std::log(base));
        } else {
          d[1] = slope * q.px;
          d[2] = slope * q.py;
          d[3] = slope * q.pz;
          d[4] = lobe.rho * (power * std::log(base));
        }
      }
      values[m] = f;
    }
  }

 private:
  template <typename T>
  struct Lobe {
    const T& rho;
    const T& cx;
    const T& cy;
    const T& cz;
    const T& n;
  };
  // Lobe k's parameters: rho, cx, [cy,] cz, n (isotropic: C_y = C_x).
  template <typename T>
  Lobe<T> lobe_of(const T* p, int k) const {
    const T* q = p + 1 + k * (isotropic_ ? 4 : 5);
    return isotropic_ ? Lobe<T>{q[0], q[1], q[1], q[2], q[3]} : Lobe<T>{q[0], q[1], q[2], q[3], q[4]};
  }

  int lobes_;
  bool isotropic_;
};

}  // namespace roadbrdf
