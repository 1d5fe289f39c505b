#include "roadbrdf/albedo/solar.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string_view>

#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/spectra/spectrum_file.h"

namespace roadbrdf::albedo {

namespace {

// A column of a bundled table (wavelength in the first column, the value named in the header).
spectra::Spectrum bundled_column(const std::string& file, const std::string& column, const std::string& name,
                                 bool non_negative) {
  spectra::SpectrumReadOptions o;
  o.name = name;
  o.quantity = column;
  o.value_column = column;
  o.non_negative = non_negative;
  o.min_points = 2;
  o.outside = spectra::Extrapolation::kRefuse;
  return spectra::read_spectrum(data_file(file), o);
}

spectra::Spectrum astm_column(const std::string& which) {
  return bundled_column("third-party/solar/astm-g173-03.csv", which, "astm-g173-" + which, true);
}

// SPECTRL2's extraterrestrial spectrum and absorption coefficients, on one grid.
struct Spectrl2Coefficients {
  spectra::Spectrum extraterrestrial, water, ozone, mixed_gas;
};

const Spectrl2Coefficients& spectrl2_coefficients() {
  static const Spectrl2Coefficients c = [] {
    const auto column = [](const std::string& name) {
      return bundled_column("third-party/solar/spectrl2-coefficients.csv", name, "SPECTRL2 " + name, false);
    };
    return Spectrl2Coefficients{column("et_irradiance_W_m2_nm"), column("water_vapor_absorption"),
                                column("ozone_absorption"), column("mixed_gas_absorption")};
  }();
  return c;
}

}  // namespace

spectra::Spectrum astm_g173(const std::string& which) {
  if (which == "extraterrestrial") {
    static const spectra::Spectrum s = astm_column(which);
    return s;
  }
  if (which == "global") {
    static const spectra::Spectrum s = astm_column(which);
    return s;
  }
  if (which == "direct") {
    static const spectra::Spectrum s = astm_column(which);
    return s;
  }
  throw InputError("ASTM G173 spectrum '" + which + "': use global, direct or extraterrestrial");
}

spectra::Spectrum read_solar_spectrum(const std::string& path) {
  spectra::SpectrumReadOptions o;
  o.quantity = "irradiance";
  o.uncertainties = false;
  o.one_column = false;
  o.non_negative = true;
  o.min_points = 2;
  o.positive_integral = true;
  o.outside = spectra::Extrapolation::kRefuse;
  return spectra::read_spectrum(path, o);
}

spectra::Spectrum solar_spectrum_from_name(const std::string& name) {
  if (name == "astm-g173-global") return astm_g173("global");
  if (name == "astm-g173-direct") return astm_g173("direct");
  return read_solar_spectrum(name);
}

double integrate_spectrum(const spectra::Spectrum& e) { return spectra::trapezoid_integral(e); }

// ---- SPECTRL2 ---------------------------------------------------------------------------------

double kasten_young_airmass(double zenith_deg) {
  // Kasten & Young, Appl. Opt. 28 (1989) 4735, eq. 3.
  return 1.0 / (std::cos(zenith_deg * kDegree) + 0.50572 * std::pow(96.07995 - zenith_deg, -1.6364));
}

Spectrl2Output spectrl2(const Spectrl2Input& in) {
  if (!(in.zenith_deg >= 0.0 && in.zenith_deg < 90.0)) throw InputError("SPECTRL2: zenith must be in [0, 90) deg");
  if (!(in.aod500 >= 0.0 && in.aod500 <= 10.0)) throw InputError("SPECTRL2: aod must be in [0, 10]");
  if (!(in.water_cm >= 0.0 && in.water_cm <= 100.0)) throw InputError("SPECTRL2: water must be in [0, 100] cm");
  if (!(in.ozone_atm_cm >= 0.0 && in.ozone_atm_cm <= 2.0)) throw InputError("SPECTRL2: ozone must be in [0, 2] atm-cm");
  if (!(in.pressure_pa > 0.0 && in.pressure_pa <= 120000.0))
    throw InputError("SPECTRL2: pressure must be in (0, 120000] Pa");
  if (!(in.asymmetry > 0.0 && in.asymmetry < 1.0)) throw InputError("SPECTRL2: asymmetry must be in (0, 1)");
  if (!(in.ground_albedo >= 0.0 && in.ground_albedo <= 1.0))
    throw InputError("SPECTRL2: ground albedo must be in [0, 1]");
  if (!(in.day_of_year >= 1 && in.day_of_year <= 366)) throw InputError("SPECTRL2: day must be in 1..366");

  // Extraterrestrial spectrum and absorption coefficients (Bird & Riordan table, in W m^-2 nm^-1).
  const Spectrl2Coefficients& coefficients = spectrl2_coefficients();
  const auto& wl = coefficients.extraterrestrial.wavelengths();
  const auto& h0 = coefficients.extraterrestrial.values();
  const auto& aw = coefficients.water.values();
  const auto& ao = coefficients.ozone.values();
  const auto& au = coefficients.mixed_gas.values();

  // Earth-Sun distance factor (Spencer 1971; report eq. 2-2/2-3), day angle 2 pi (doy - 1)/365.
  const double b = 2.0 * kPi * (in.day_of_year - 1) / 365.0;
  const double d = 1.00011 + 0.034221 * std::cos(b) + 0.00128 * std::sin(b) + 0.000719 * std::cos(2.0 * b) +
                   0.000077 * std::sin(2.0 * b);
  const double cz = std::cos(in.zenith_deg * kDegree);
  const double m = in.relative_airmass > 0.0 ? in.relative_airmass : kasten_young_airmass(in.zenith_deg);
  const double mp = m * in.pressure_pa / 101300.0;  // pressure-corrected air mass (spectrl2_2.c: press/1013 mb)
  // Ozone air mass (eq. 2-10 with h0 = 22 km, Earth radius 6370 km).
  const double ho = 22.0 / 6370.0;
  const double mo = (1.0 + ho) / std::sqrt(cz * cz + 2.0 * ho);
  // Aerosol forward-scattering (eqs. 3-11 to 3-15).
  const double alg = std::log(1.0 - in.asymmetry);
  const double afs = alg * (1.459 + alg * (0.1595 + alg * 0.4129));
  const double bfs = alg * (0.0783 + alg * (-0.3824 - alg * 0.5874));
  const double fs = 1.0 - 0.5 * std::exp((afs + bfs * cz) * cz);
  const double fsp = 1.0 - 0.5 * std::exp((afs + bfs / 1.8) / 1.8);

  Spectrl2Output out;
  out.cos_zenith = cz;
  for (std::size_t i = 0; i < wl.size(); ++i) {
    const double l = wl[i] / 1000.0;  // um
    const double et = h0[i] * d;
    const double omega = in.omega400 * std::exp(-in.omega_prime * std::pow(std::log(l / 0.4), 2));  // eq. 3-16
    const double tau = in.aod500 * std::pow(l / 0.5, -in.alpha);                                    // eq. 2-7
    const double rayleigh_depth = 1.0 / (std::pow(l, 4) * (115.6406 - 1.3366 / (l * l)));
    const double tr = std::exp(-mp * rayleigh_depth);           // eq. 2-4
    const double to = std::exp(-ao[i] * in.ozone_atm_cm * mo);  // eq. 2-9
    const double aww = aw[i] * in.water_cm * m;
    const double tw = std::exp(-0.2385 * aww / std::pow(1.0 + 20.07 * aww, 0.45));  // eq. 2-8
    const double aum = au[i] * mp;
    const double tu = std::exp(-1.41 * aum / std::pow(1.0 + 118.3 * aum, 0.45));  // eq. 2-11
    const double tas = std::exp(-omega * tau * m);                                // eq. 3-9
    const double taa = std::exp(-(1.0 - omega) * tau * m);                        // eq. 3-10
    const double ta = std::exp(-tau * m);                                         // eq. 2-6
    // Primed transmittances at air mass 1.8 (section 3.1; no pressure correction, as spectrl2_2.c).
    const double trp = std::exp(-1.8 * rayleigh_depth);
    const double aw18 = aw[i] * in.water_cm * 1.8;
    const double twp = std::exp(-0.2385 * aw18 / std::pow(1.0 + 20.07 * aw18, 0.45));
    const double au18 = au[i] * 1.8;
    const double tup = std::exp(-1.41 * au18 / std::pow(1.0 + 118.3 * au18, 0.45));
    const double tasp = std::exp(-omega * tau * 1.8);
    const double taap = std::exp(-(1.0 - omega) * tau * 1.8);

    const double direct = et * tr * ta * tw * to * tu;  // eq. 2-1
    const double common = et * cz * to * tw * tu * taa;
    const double cs = l <= 0.45 ? std::pow(l + 0.55, 1.8) : 1.0;                                    // eq. 3-17
    const double rhoa = tup * twp * taap * (0.5 * (1.0 - trp) + (1.0 - fsp) * trp * (1.0 - tasp));  // eq. 3-8
    const double ir = common * (1.0 - std::pow(tr, 0.95)) * 0.5;                                    // eq. 3-5
    const double ia = common * std::pow(tr, 1.5) * (1.0 - tas) * fs;                                // eq. 3-6
    const double rg = in.ground_albedo;
    const double ig = (direct * cz + ir + ia) * rhoa * rg / (1.0 - rhoa * rg);  // eq. 3-7
    const double diffuse = (ir + ia + ig) * cs;                                 // eq. 3-1 (Cs once)

    out.wavelengths.push_back(wl[i]);
    out.extraterrestrial.push_back(et);
    out.direct_normal.push_back(direct);
    out.diffuse.push_back(diffuse);
    out.global.push_back(direct * cz + diffuse);
  }
  return out;
}

Spectrl2Input parse_spectrl2_spec(const std::string& spec) {
  Spectrl2Input in;
  const std::string head = "spectrl2";
  if (spec.compare(0, head.size(), head) != 0 || (spec.size() > head.size() && spec[head.size()] != ':')) {
    throw FieldError("atmosphere", "expected spectrl2[:aod=...,water=...,ozone=...,pressure=...], got '" + spec + "'");
  }
  if (spec.size() <= head.size() + 1) return in;
  std::string rest = spec.substr(head.size() + 1);
  std::size_t start = 0;
  while (start <= rest.size()) {
    const std::size_t comma = rest.find(',', start);
    const std::string item = rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw FieldError("atmosphere", "spectrl2: expected NAME=VALUE, got '" + item + "'");
    const std::string name = item.substr(0, eq), text = item.substr(eq + 1);
    double v = 0.0;
    if (!parse_finite_double(text, v)) {
      throw FieldError("atmosphere", "spectrl2: " + name + " = '" + text + "' is not a number");
    }
    if (name == "aod")
      in.aod500 = v;
    else if (name == "water")
      in.water_cm = v;
    else if (name == "ozone")
      in.ozone_atm_cm = v;
    else if (name == "pressure")
      in.pressure_pa = v;
    else if (name == "alpha")
      in.alpha = v;
    else if (name == "asymmetry")
      in.asymmetry = v;
    else if (name == "ground")
      in.ground_albedo = v;
    else if (name == "day") {
      // Day of year: an integer, checked as a double (casting 1e10 to int is undefined; 81.9 is no day).
      if (!(v >= 1.0 && v <= 366.0) || v != std::floor(v)) {
        throw FieldError("atmosphere", "spectrl2: day = '" + text + "' must be an integer day of year in 1..366");
      }
      in.day_of_year = static_cast<int>(v);
    } else {
      throw FieldError("atmosphere",
                       "spectrl2: unknown setting '" + name +
                           "' (known: aod, water [cm], ozone [atm-cm], pressure [Pa], alpha, asymmetry, ground, day)");
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return in;
}

// ---- weighting ------------------------------------------------------------------------------

namespace {

std::vector<double> union_grid(double lo, double hi, const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> g{lo, hi};
  for (double x : a)
    if (x > lo && x < hi) g.push_back(x);
  for (double x : b)
    if (x > lo && x < hi) g.push_back(x);
  std::sort(g.begin(), g.end());
  g.erase(std::unique(g.begin(), g.end()), g.end());
  return g;
}

double range_integral(const spectra::Spectrum& e, double lo, double hi) {
  const double a = std::max(lo, e.min_wavelength()), b = std::min(hi, e.max_wavelength());
  if (!(b > a)) return 0.0;
  const std::vector<double> g = union_grid(a, b, e.wavelengths(), {});
  double sum = 0.0;
  for (std::size_t k = 1; k < g.size(); ++k) sum += 0.5 * (e.value(g[k]) + e.value(g[k - 1])) * (g[k] - g[k - 1]);
  return sum;
}

// A tabulated albedo (or its error) at x inside the tabulated range.
double albedo_at(const std::vector<double>& wavelengths, const std::vector<double>& values, double x,
                 std::string_view what) {
  return spectra::interpolate_linear(wavelengths, values, x, spectra::Extrapolation::kRefuse, what);
}

}  // namespace

WeightedValue spectral_weighted_mean2(const std::vector<double>& wavelengths, const std::vector<double>& values1,
                                      const std::vector<double>& errors1, const spectra::Spectrum& weight1,
                                      const std::vector<double>& values2, const std::vector<double>& errors2,
                                      const spectra::Spectrum& weight2) {
  if (wavelengths.size() < 2) throw InputError("spectral weighting needs at least two wavelengths");
  const double lo = std::max({wavelengths.front(), weight1.min_wavelength(), weight2.min_wavelength()});
  const double hi = std::min({wavelengths.back(), weight1.max_wavelength(), weight2.max_wavelength()});
  if (!(hi > lo)) {
    throw InputError("the model's wavelengths [" + std::to_string(wavelengths.front()) + ", " +
                     std::to_string(wavelengths.back()) + "] nm do not overlap the solar spectrum");
  }
  std::vector<double> g = union_grid(lo, hi, wavelengths, weight1.wavelengths());
  if (&weight1 != &weight2) g = union_grid(lo, hi, g, weight2.wavelengths());
  const bool two = !values2.empty();
  WeightedValue result;
  result.first.assign(wavelengths.size(), 0.0);
  if (two) result.second.assign(wavelengths.size(), 0.0);
  // d(value * den)/da[k]: a(x) = (1 - t) a[j] + t a[j+1] between the bands j, j+1 around x, so the
  // trapezoid weight `h` of the point x goes to those two bands.
  auto spread = [&](double x, double h1, double h2) {
    const auto upper = std::upper_bound(wavelengths.begin(), wavelengths.end(), x);
    const std::size_t j = std::min(
        static_cast<std::size_t>(std::max<std::ptrdiff_t>(upper - wavelengths.begin() - 1, 0)), wavelengths.size() - 2);
    const double t = std::clamp((x - wavelengths[j]) / (wavelengths[j + 1] - wavelengths[j]), 0.0, 1.0);
    result.first[j] += (1.0 - t) * h1;
    result.first[j + 1] += t * h1;
    if (two) {
      result.second[j] += (1.0 - t) * h2;
      result.second[j + 1] += t * h2;
    }
  };
  double num = 0.0, den = 0.0, err = 0.0;
  auto at = [&](double x, double& n, double& dd, double& e) {
    const double w1 = weight1.value(x);
    const double a1 = albedo_at(wavelengths, values1, x, "albedo");
    const double e1 = errors1.empty() ? 0.0 : albedo_at(wavelengths, errors1, x, "error");
    n = w1 * a1;
    dd = w1;
    e = w1 * e1;
    if (two) {
      const double w2 = weight2.value(x);
      n += w2 * albedo_at(wavelengths, values2, x, "albedo");
      dd += w2;
      e += w2 * (errors2.empty() ? 0.0 : albedo_at(wavelengths, errors2, x, "error"));
    }
  };
  double n0 = 0.0, d0 = 0.0, e0 = 0.0;
  at(g[0], n0, d0, e0);
  for (std::size_t k = 1; k < g.size(); ++k) {
    double n1 = 0.0, d1 = 0.0, e1 = 0.0;
    at(g[k], n1, d1, e1);
    const double dx = g[k] - g[k - 1];
    for (const double x : {g[k - 1], g[k]}) {
      const double w1 = weight1.value(x);
      const double w2 = two ? weight2.value(x) : 0.0;
      spread(x, 0.5 * dx * w1, 0.5 * dx * w2);
    }
    num += 0.5 * (n0 + n1) * dx;
    den += 0.5 * (d0 + d1) * dx;
    err += 0.5 * (e0 + e1) * dx;
    n0 = n1;
    d0 = d1;
    e0 = e1;
  }
  if (!(den > 0.0)) throw InputError("the solar spectrum is zero over the model's wavelength range");
  double total = integrate_spectrum(weight1);
  double inside = range_integral(weight1, wavelengths.front(), wavelengths.back());
  if (two) {
    total += integrate_spectrum(weight2);
    inside += range_integral(weight2, wavelengths.front(), wavelengths.back());
  }
  for (double& c : result.first) c /= den;
  for (double& c : result.second) c /= den;
  result.value = num / den;
  result.error = err / den;
  result.fraction_outside = total > 0.0 ? std::max(0.0, 1.0 - inside / total) : 0.0;
  return result;
}

WeightedValue spectral_weighted_mean(const std::vector<double>& wavelengths, const std::vector<double>& values,
                                     const std::vector<double>& errors, const spectra::Spectrum& weight) {
  return spectral_weighted_mean2(wavelengths, values, errors, weight, {}, {}, weight);
}

}  // namespace roadbrdf::albedo
