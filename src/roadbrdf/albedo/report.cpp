#include "roadbrdf/albedo/report.h"

#include <fmt/core.h>
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

#include "roadbrdf/albedo/coverage.h"
#include "roadbrdf/albedo/hemisphere.h"
#include "roadbrdf/albedo/solar.h"
#include "roadbrdf/albedo/uncertainty.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/number.h"
#include "roadbrdf/spectra/cie.h"

namespace roadbrdf::albedo {

namespace {

// A standard uncertainty in the table: "nan" where undefined (JSON null).
std::string u_text_of(const nlohmann::json& v) {
  return v.is_null() ? std::string("nan") : fmt::format("{:.2e}", v.get<double>());
}

// Diffuse-fraction table: CSV wavelength_nm, diffuse_fraction.
SolarSpectrum read_diffuse_table(const std::string& path) {
  SolarSpectrum t = read_solar_spectrum(path);  // same two-column format and checks
  for (double d : t.irradiance) {
    if (d > 1.0) throw FileError(path, 0, 0, "a diffuse fraction must be in [0, 1]");
  }
  return t;
}

// Whether the luminous (V(lambda)-weighted) albedo can be formed from these wavelengths: at least
// two, covering 99% of the luminous integral (photometry::photometric_weights). Otherwise a note.
bool luminous_possible(const std::vector<double>& wavelengths, const photometry::TabulatedSpectrum& illuminant,
                       std::vector<std::string>& notes) {
  if (wavelengths.size() < 2) {
    notes.push_back(
        fmt::format("single-band fit ({:g} nm): the luminous (V(lambda)-weighted) values need a spectrum "
                    "and are omitted",
                    wavelengths.front()));
    return false;
  }
  const double coverage = photometry::luminous_coverage(wavelengths.front(), wavelengths.back(), illuminant);
  if (coverage < 0.99) {
    notes.push_back(
        fmt::format("the fit's wavelengths ({:g}-{:g} nm) hold {:.1f}% of the luminous integral under {} "
                    "(99% needed): the luminous values are omitted",
                    wavelengths.front(), wavelengths.back(), 100.0 * coverage, illuminant.name()));
    return false;
  }
  return true;
}

nlohmann::json nullable(const std::vector<std::vector<double>>& v) {
  if (v.empty()) return nullptr;
  return v;
}

}  // namespace

nlohmann::json compute_albedo(const SpectralModel& sm, const AlbedoRequest& a) {
  const Model& model = sm.model();
  const std::size_t n_params = model.parameter_count();
  if (!(a.tolerance > 0.0)) throw InputError("--tolerance must be > 0");
  if (!a.diffuse_fraction.empty() && !a.atmosphere.empty()) {
    throw InputError("give either --diffuse-fraction or --atmosphere, not both");
  }

  // Wavelength axis and parameter sets.
  const bool spectral = sm.is_spectral();
  std::vector<double> wavelengths;
  std::vector<double> params;
  if (spectral) {
    wavelengths = a.wavelengths.empty() ? sm.wavelengths() : a.wavelengths;
    if (a.wavelengths.empty()) {
      params = sm.parameter_table();
    } else {
      for (double l : wavelengths) {
        const auto p = sm.parameters_at(l);
        params.insert(params.end(), p.begin(), p.end());
      }
    }
  } else {
    if (!a.wavelengths.empty()) {
      throw InputError("--wavelengths needs a fit file: MODEL -p ... has no wavelength axis");
    }
    params = sm.parameter_table();
  }
  const std::size_t n_sets = params.size() / n_params;

  const std::vector<double>& zeniths = a.sun_zenith_deg;
  if (zeniths.empty()) throw InputError("no sun zenith given");
  for (double z : zeniths) {
    if (!(z >= 0.0 && z < 90.0)) throw InputError("--sun-zenith values must be in [0, 90) deg");
  }
  const bool isotropic = is_isotropic(model, params.data(), n_sets);
  QuadratureSettings settings;
  settings.tolerance = a.tolerance;
  std::vector<std::string> notes;
  if (!spectral) {
    notes.push_back(
        "non-spectral model (MODEL -p ...): values are for its constant parameters; the broadband "
        "values equal them");
  }

  // Black-sky per zenith, white-sky.
  std::vector<std::vector<double>> bs(zeniths.size()), bs_err(zeniths.size());
  bool converged = true;
  ProgressCounter progress(a.progress, zeniths.size() + 1);
  for (std::size_t z = 0; z < zeniths.size(); ++z) {
    const double theta = zeniths[z] * kDegree;
    SpectralIntegral r =
        (!isotropic && a.azimuth_mean && !a.sun_azimuth_deg)
            ? black_sky_azimuth_mean(model, params.data(), n_sets, theta, settings)
            : black_sky(model, params.data(), n_sets, theta, a.sun_azimuth_deg.value_or(0.0) * kDegree, settings);
    converged = converged && r.converged;
    bs[z] = std::move(r.value);
    bs_err[z] = std::move(r.error);
    progress.add();
  }
  SpectralIntegral ws = white_sky(model, params.data(), n_sets, settings);
  progress.add();
  converged = converged && ws.converged;
  if (!isotropic) {
    notes.push_back(
        a.azimuth_mean && !a.sun_azimuth_deg
            ? "anisotropic model: black-sky averaged over the sun azimuth"
            : fmt::format("anisotropic model: black-sky at sun azimuth {} deg", a.sun_azimuth_deg.value_or(0.0)));
  }
  if (!converged)
    notes.push_back("WARNING: the quadrature stopped before meeting the tolerance; see the error estimates");

  // Diffuse fraction and SPECTRL2 spectra per zenith.
  std::vector<std::vector<double>> diffuse;  // [zenith][set]
  std::vector<Spectrl2Output> atmospheres;
  std::optional<Spectrl2Input> atmosphere;
  if (!a.atmosphere.empty()) atmosphere = parse_spectrl2_spec(a.atmosphere);
  if (!a.diffuse_fraction.empty() || atmosphere) {
    diffuse.assign(zeniths.size(), std::vector<double>(n_sets, 0.0));
    std::optional<double> constant;
    SolarSpectrum table;
    if (!a.diffuse_fraction.empty()) {
      double v = 0.0;
      const auto& t = a.diffuse_fraction;
      if (parse_finite_double(t, v)) {
        if (!(v >= 0.0 && v <= 1.0)) throw InputError("--diffuse-fraction must be in [0, 1]");
        constant = v;
      } else {
        table = read_diffuse_table(t);
      }
    }
    for (std::size_t z = 0; z < zeniths.size(); ++z) {
      if (atmosphere) {
        Spectrl2Input in = *atmosphere;
        in.zenith_deg = zeniths[z];
        atmospheres.push_back(spectrl2(in));
      }
      for (std::size_t s = 0; s < n_sets; ++s) {
        if (constant) {
          diffuse[z][s] = *constant;
        } else if (atmosphere) {
          const auto& o = atmospheres.back();
          if (spectral) {
            const double dif = interpolate(o.wavelengths, o.diffuse, wavelengths[s], "SPECTRL2 (300-4000 nm)");
            const double glo = interpolate(o.wavelengths, o.global, wavelengths[s], "SPECTRL2 (300-4000 nm)");
            diffuse[z][s] = glo > 0.0 ? dif / glo : 1.0;
          } else {
            double dif = 0.0, glo = 0.0;
            for (std::size_t k = 1; k < o.wavelengths.size(); ++k) {
              const double dl = o.wavelengths[k] - o.wavelengths[k - 1];
              dif += 0.5 * (o.diffuse[k] + o.diffuse[k - 1]) * dl;
              glo += 0.5 * (o.global[k] + o.global[k - 1]) * dl;
            }
            diffuse[z][s] = dif / glo;
          }
        } else {
          if (!spectral) throw InputError("a diffuse-fraction table needs a fit file (a model has no wavelengths)");
          diffuse[z][s] = interpolate(table.wavelengths, table.irradiance, wavelengths[s], a.diffuse_fraction);
        }
      }
    }
  }
  std::vector<std::vector<double>> blue, blue_err;
  if (!diffuse.empty()) {
    blue.assign(zeniths.size(), std::vector<double>(n_sets));
    blue_err.assign(zeniths.size(), std::vector<double>(n_sets));
    for (std::size_t z = 0; z < zeniths.size(); ++z) {
      for (std::size_t s = 0; s < n_sets; ++s) {
        const double d = diffuse[z][s];
        blue[z][s] = (1.0 - d) * bs[z][s] + d * ws.value[s];
        blue_err[z][s] = (1.0 - d) * bs_err[z][s] + d * ws.error[s];
      }
    }
  }

  // Broadband values.
  bool broadband_formed = true;
  std::vector<double> bb_bs, bb_bs_err, bb_blue, bb_blue_err;
  double bb_ws = ws.value[0], bb_ws_err = ws.error[0], outside = 0.0;
  std::string weighting;
  // The broadband means' coefficients (WeightedValue::first/second), for their uncertainties.
  std::vector<WeightedValue> bb_bs_mean, bb_blue_mean;
  WeightedValue bb_ws_mean;
  if (!a.spectrum.empty() && (!spectral || wavelengths.size() < 2)) {
    // Nothing to weigh, but a spectrum that was asked for is still read and checked, never ignored.
    (void)solar_spectrum_from_name(a.spectrum);
    notes.push_back(fmt::format("spectrum {}: a {} has nothing to weigh, the weighting has no effect", a.spectrum,
                                spectral ? "single-band fit" : "non-spectral model"));
  }
  if (!spectral) {
    weighting = "none (non-spectral model)";
    for (std::size_t z = 0; z < zeniths.size(); ++z) {
      bb_bs.push_back(bs[z][0]);
      bb_bs_err.push_back(bs_err[z][0]);
      if (!blue.empty()) {
        bb_blue.push_back(blue[z][0]);
        bb_blue_err.push_back(blue_err[z][0]);
      }
    }
  } else if (wavelengths.size() < 2) {
    // A single band has no spectrum to weigh: its values are reported per wavelength only.
    broadband_formed = false;
    notes.push_back(
        fmt::format("single-band fit ({:g} nm): the broadband (solar-weighted) values need at least two "
                    "wavelengths and are omitted",
                    wavelengths.front()));
  } else {
    std::optional<SolarSpectrum> fixed;
    if (!a.spectrum.empty()) fixed = solar_spectrum_from_name(a.spectrum);
    if (!fixed && !atmosphere) fixed = astm_g173("global");
    weighting = fixed ? fixed->name : "spectrl2 (direct horizontal on black-sky, diffuse on white-sky)";
    for (std::size_t z = 0; z < zeniths.size(); ++z) {
      SolarSpectrum e_dir, e_dif, e_glo;
      if (!fixed) {
        const auto& o = atmospheres[z];
        e_dir = {"spectrl2-direct-horizontal", o.wavelengths, {}};
        for (double v : o.direct_normal) e_dir.irradiance.push_back(v * o.cos_zenith);
        e_dif = {"spectrl2-diffuse", o.wavelengths, o.diffuse};
        e_glo = {"spectrl2-global", o.wavelengths, o.global};
      }
      const SolarSpectrum& e = fixed ? *fixed : e_glo;
      const auto b = spectral_weighted_mean(wavelengths, bs[z], bs_err[z], e);
      bb_bs.push_back(b.value);
      bb_bs_err.push_back(b.error);
      bb_bs_mean.push_back(b);
      outside = b.fraction_outside;
      if (z == 0) {
        bb_ws_mean = spectral_weighted_mean(wavelengths, ws.value, ws.error, e);
        bb_ws = bb_ws_mean.value;
        bb_ws_err = bb_ws_mean.error;
      }
      if (!blue.empty()) {
        const auto u = fixed ? spectral_weighted_mean(wavelengths, blue[z], blue_err[z], e)
                             : spectral_weighted_mean2(wavelengths, bs[z], bs_err[z], e_dir, ws.value, ws.error, e_dif);
        bb_blue.push_back(u.value);
        bb_blue_err.push_back(u.error);
        bb_blue_mean.push_back(u);
      }
    }
    if (!fixed)
      notes.push_back("broadband white-sky is weighted by SPECTRL2's global spectrum at the first sun zenith");
    if (outside > 0.5) {
      notes.push_back(
          fmt::format("WARNING: the fit's wavelengths ({:g}-{:g} nm) hold only {:.0f}% of the solar energy: "
                      "the broadband values weigh that part only",
                      wavelengths.front(), wavelengths.back(), 100.0 * (1.0 - outside)));
    }
  }

  // Luminous reflectance.
  nlohmann::json luminous = nullptr;
  std::vector<double> lum_bs;
  double lum_ws = ws.value[0];
  if (!a.illuminant.empty()) {
    const photometry::TabulatedSpectrum illum = photometry::illuminant_from_name(a.illuminant);
    if (spectral && !luminous_possible(wavelengths, illum, notes)) {
      // omitted, with the note saying why
    } else if (spectral) {
      const std::vector<double> grid = photometry::photometric_grid(wavelengths.front(), wavelengths.back());
      const std::vector<double> w = photometry::photometric_weights(grid, illum);
      auto weigh = [&](const std::vector<double>& v) {
        double sum = 0.0;
        for (std::size_t k = 0; k < grid.size(); ++k) sum += w[k] * interpolate(wavelengths, v, grid[k], "albedo");
        return sum;
      };
      for (std::size_t z = 0; z < zeniths.size(); ++z) lum_bs.push_back(weigh(bs[z]));
      lum_ws = weigh(ws.value);
    } else {
      for (std::size_t z = 0; z < zeniths.size(); ++z) lum_bs.push_back(bs[z][0]);
    }
    if (!spectral || !lum_bs.empty()) {
      luminous = {{"illuminant", illum.name()}, {"black_sky", lum_bs}, {"white_sky", lum_ws}};
    }
  }

  // Standard uncertainties from the fit's parameter covariance (albedo/uncertainty.h), at the fit's
  // own wavelengths (an interpolated parameter set has no covariance of its own).
  nlohmann::json uncertainty = nullptr;
  const std::vector<double>& covariance = sm.parameter_covariance();
  if (!covariance.empty() && spectral && a.wavelengths.empty()) {
    progress.add_total(zeniths.size() + 1);
    QuadratureSettings tight = settings;
    tight.tolerance = kDerivativeTolerance;
    const SetIntegral white = [&](const std::vector<double>& p, std::size_t n) {
      return white_sky(model, p.data(), n, tight).value;
    };
    const std::vector<double> g_ws = albedo_gradient(model, params, n_sets, covariance, white);
    progress.add();
    const bool with_broadband = broadband_formed && !bb_bs_mean.empty();
    nlohmann::json bb_u_bs = nlohmann::json::array(), bb_u_blue = nlohmann::json::array();
    auto bb_json = [](const BroadbandUncertainty& b) {
      auto number = [](double x) { return std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x); };
      return nlohmann::json{{"independent", number(b.independent)}, {"correlated", number(b.correlated)}};
    };
    const bool mean_azimuth = !isotropic && a.azimuth_mean && !a.sun_azimuth_deg;
    const double phi_s = a.sun_azimuth_deg.value_or(0.0) * kDegree;
    std::vector<std::vector<double>> u_bs, u_blue;
    for (std::size_t z = 0; z < zeniths.size(); ++z) {
      const double theta = zeniths[z] * kDegree;
      const SetIntegral black = [&](const std::vector<double>& p, std::size_t n) {
        return (mean_azimuth ? black_sky_azimuth_mean(model, p.data(), n, theta, tight)
                             : black_sky(model, p.data(), n, theta, phi_s, tight))
            .value;
      };
      const std::vector<double> g_bs = albedo_gradient(model, params, n_sets, covariance, black);
      u_bs.push_back(propagate(g_bs, covariance, n_sets, n_params));
      if (with_broadband) {
        bb_u_bs.push_back(
            bb_json(broadband_uncertainty({&g_bs}, {&bb_bs_mean[z].first}, covariance, n_sets, n_params)));
      }
      if (!diffuse.empty()) {
        // blue = (1 - D) black + D white: its gradient is the same combination of theirs.
        std::vector<double> g_blue(g_bs.size());
        for (std::size_t k = 0; k < g_bs.size(); ++k) {
          const double d = diffuse[z][k / n_params];
          g_blue[k] = (1.0 - d) * g_bs[k] + d * g_ws[k];
        }
        u_blue.push_back(propagate(g_blue, covariance, n_sets, n_params));
        if (with_broadband && !bb_blue_mean.empty()) {
          const WeightedValue& m = bb_blue_mean[z];
          // SPECTRL2: direct-weighted black-sky plus diffuse-weighted white-sky; else one weight on blue.
          bb_u_blue.push_back(bb_json(
              m.second.empty()
                  ? broadband_uncertainty({&g_blue}, {&m.first}, covariance, n_sets, n_params)
                  : broadband_uncertainty({&g_bs, &g_ws}, {&m.first, &m.second}, covariance, n_sets, n_params)));
        }
      }
      progress.add();
    }
    // Undefined (NaN) uncertainties are JSON null, in the document itself and not only when dumped.
    auto with_nulls = [](const std::vector<double>& v) {
      nlohmann::json out = nlohmann::json::array();
      for (double x : v) out.push_back(std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x));
      return out;
    };
    auto rows_with_nulls = [&](const std::vector<std::vector<double>>& rows) {
      if (rows.empty()) return nlohmann::json(nullptr);
      nlohmann::json out = nlohmann::json::array();
      for (const auto& row : rows) out.push_back(with_nulls(row));
      return out;
    };
    uncertainty = {{"method", "linearised (GUM eq. 10) from the fit's parameter covariance at each wavelength"},
                   {"black_sky", rows_with_nulls(u_bs)},
                   {"white_sky", with_nulls(propagate(g_ws, covariance, n_sets, n_params))},
                   {"blue_sky", rows_with_nulls(u_blue)},
                   {"broadband", nullptr}};
    if (with_broadband) {
      uncertainty["broadband"] = {
          {"black_sky", bb_u_bs},
          {"white_sky", bb_json(broadband_uncertainty({&g_ws}, {&bb_ws_mean.first}, covariance, n_sets, n_params))},
          {"blue_sky", bb_u_blue.empty() ? nlohmann::json(nullptr) : bb_u_blue}};
    }
    notes.push_back(
        "standard uncertainties from the fit's parameter covariance, per wavelength; the broadband ones "
        "treat the wavelengths as independent ('independent') and give the bound for errors correlated "
        "across wavelengths ('correlated')");
  } else if (!covariance.empty()) {
    notes.push_back("standard uncertainties are given at the fit's own wavelengths only, not with --wavelengths");
  }
  progress.finish();

  // Non-physical values, and how much of the result the model extrapolates beyond the fit's data
  // (albedo/coverage.h; at the middle parameter set).
  flag_non_physical(zeniths, wavelengths, bs, ws.value, notes);
  nlohmann::json coverage = nullptr;
  if (sm.coverage()) {
    const std::size_t mid = n_sets / 2;
    coverage = albedo_coverage(model, params.data() + mid * n_params,
                               spectral ? wavelengths[mid] : std::numeric_limits<double>::quiet_NaN(), zeniths,
                               *sm.coverage(), notes);
  }

  nlohmann::json j;
  j["model"] = model.name();
  j["spectral"] = spectral;
  j["isotropic"] = isotropic;
  j["units"] = {{"wavelengths", "nm"},
                {"sun_zenith_deg", "deg"},
                {"black_sky", "1 (directional-hemispherical reflectance), [sun zenith][wavelength]"},
                {"white_sky", "1 (bi-hemispherical reflectance), [wavelength]"},
                {"blue_sky", "1, (1 - D) black_sky + D white_sky, [sun zenith][wavelength]"},
                {"diffuse_fraction", "1, D = diffuse / global horizontal irradiance, [sun zenith][wavelength]"},
                {"errors", "absolute error estimates of the same quantities"},
                {"broadband", "solar-weighted values; null when they cannot be formed (one wavelength; see notes)"},
                {"coverage",
                 "the fit's measured directions (deg) and the fractions (1) of the black-sky [sun zenith] "
                 "and white-sky integrals outside them; null when unknown"},
                {"uncertainty",
                 "standard uncertainties (1) of black_sky, white_sky and blue_sky from the fit's "
                 "parameter covariance, same shapes; null when unknown (a model, a mixture, "
                 "--wavelengths), null entries where the covariance is undefined; the table's "
                 "last columns *_u; broadband: {independent, correlated} per value (albedo/uncertainty.h)"}};
  j["sun_zenith_deg"] = zeniths;
  j["wavelengths"] = wavelengths;
  j["tolerance"] = a.tolerance;
  j["converged"] = converged;
  j["black_sky"] = bs;
  j["black_sky_error"] = bs_err;
  j["white_sky"] = ws.value;
  j["white_sky_error"] = ws.error;
  j["diffuse_fraction"] = nullable(diffuse);
  j["blue_sky"] = nullable(blue);
  j["blue_sky_error"] = nullable(blue_err);
  if (!broadband_formed) {
    j["broadband"] = nullptr;
  } else {
    j["broadband"] = {{"weighting", weighting},
                      {"black_sky", bb_bs},
                      {"black_sky_error", bb_bs_err},
                      {"white_sky", bb_ws},
                      {"white_sky_error", bb_ws_err},
                      {"blue_sky", bb_blue.empty() ? nlohmann::json(nullptr) : nlohmann::json(bb_blue)},
                      {"blue_sky_error", bb_blue.empty() ? nlohmann::json(nullptr) : nlohmann::json(bb_blue_err)},
                      {"solar_fraction_outside_range", outside}};
  }
  j["luminous"] = luminous;
  j["coverage"] = coverage;  // null: no coverage known (a model, a mixture, an older fit file)
  j["uncertainty"] = uncertainty;
  j["notes"] = notes;
  return j;
}

std::string albedo_table(const nlohmann::json& j) {
  const auto zeniths = j.at("sun_zenith_deg").get<std::vector<double>>();
  const auto wavelengths = j.at("wavelengths").get<std::vector<double>>();
  const bool spectral = j.at("spectral").get<bool>();
  const auto ws_value = j.at("white_sky").get<std::vector<double>>();
  const auto ws_error = j.at("white_sky_error").get<std::vector<double>>();
  const auto bs = j.at("black_sky").get<std::vector<std::vector<double>>>();
  const auto bs_err = j.at("black_sky_error").get<std::vector<std::vector<double>>>();
  std::vector<std::vector<double>> blue, blue_err, diffuse;
  if (!j.at("blue_sky").is_null()) {
    blue = j.at("blue_sky").get<std::vector<std::vector<double>>>();
    blue_err = j.at("blue_sky_error").get<std::vector<std::vector<double>>>();
    diffuse = j.at("diffuse_fraction").get<std::vector<std::vector<double>>>();
  }
  const auto& b = j.at("broadband");
  const bool with_broadband = !b.is_null();
  std::vector<double> bb_bs, bb_bs_err, bb_blue, bb_blue_err;
  double bb_ws = 0.0, bb_ws_err = 0.0, outside = 0.0;
  std::string weighting;
  if (with_broadband) {
    bb_bs = b.at("black_sky").get<std::vector<double>>();
    bb_bs_err = b.at("black_sky_error").get<std::vector<double>>();
    bb_ws = b.at("white_sky").get<double>();
    bb_ws_err = b.at("white_sky_error").get<double>();
    if (!b.at("blue_sky").is_null()) {
      bb_blue = b.at("blue_sky").get<std::vector<double>>();
      bb_blue_err = b.at("blue_sky_error").get<std::vector<double>>();
    }
    weighting = b.at("weighting").get<std::string>();
    outside = b.at("solar_fraction_outside_range").get<double>();
  }
  const std::size_t n_sets = ws_value.size();
  const double tolerance = j.at("tolerance").get<double>();
  const std::string model_name = j.at("model").get<std::string>();
  std::vector<double> lum_bs;
  double lum_ws = 0.0;
  std::string illuminant;
  if (!j.at("luminous").is_null()) {
    lum_bs = j.at("luminous").at("black_sky").get<std::vector<double>>();
    lum_ws = j.at("luminous").at("white_sky").get<double>();
    illuminant = j.at("luminous").at("illuminant").get<std::string>();
  }
  // Standard uncertainties (JSON "uncertainty"), as the last columns; "nan" where undefined.
  const auto& uncertainty = j.contains("uncertainty") ? j.at("uncertainty") : nlohmann::json(nullptr);
  const auto& u_text = u_text_of;
  std::ostringstream text;
  text << fmt::format("# albedo of {} ({}); dimensionless reflectances, absolute error estimates (tolerance {:g})\n",
                      model_name, spectral ? "fit file" : "constant parameters", tolerance);
  for (const auto& n : j.at("notes").get<std::vector<std::string>>()) text << "# " << n << '\n';
  text << (spectral ? "wavelength_nm" : "set") << ",white_sky,white_sky_error";
  for (double z : zeniths) {
    text << fmt::format(",black_sky_{0:g}deg,black_sky_error_{0:g}deg", z);
    if (!blue.empty()) text << fmt::format(",diffuse_fraction_{0:g}deg,blue_sky_{0:g}deg,blue_sky_error_{0:g}deg", z);
  }
  if (!uncertainty.is_null()) {
    text << ",white_sky_u";
    for (double z : zeniths) {
      text << fmt::format(",black_sky_u_{:g}deg", z);
      if (!blue.empty()) text << fmt::format(",blue_sky_u_{:g}deg", z);
    }
  }
  text << '\n';
  for (std::size_t s = 0; s < n_sets; ++s) {
    text << (spectral ? fmt::format("{:g}", wavelengths[s]) : std::string("-"));
    text << fmt::format(",{:.8f},{:.2e}", ws_value[s], ws_error[s]);
    for (std::size_t z = 0; z < zeniths.size(); ++z) {
      text << fmt::format(",{:.8f},{:.2e}", bs[z][s], bs_err[z][s]);
      if (!blue.empty()) text << fmt::format(",{:.6f},{:.8f},{:.2e}", diffuse[z][s], blue[z][s], blue_err[z][s]);
    }
    if (!uncertainty.is_null()) {
      text << ',' << u_text(uncertainty.at("white_sky")[s]);
      for (std::size_t z = 0; z < zeniths.size(); ++z) {
        text << ',' << u_text(uncertainty.at("black_sky")[z][s]);
        if (!blue.empty()) text << ',' << u_text(uncertainty.at("blue_sky")[z][s]);
      }
    }
    text << '\n';
  }
  if (with_broadband) {
    text << fmt::format("# broadband (weighting: {}; solar energy outside the model's wavelength range: {:.4f})\n",
                        weighting, outside);
    // "u ..." after a value: its standard uncertainty (independent wavelengths; the correlated bound).
    const nlohmann::json bb_u = uncertainty.is_null() || !uncertainty.contains("broadband") ? nlohmann::json(nullptr)
                                                                                            : uncertainty["broadband"];
    auto bb_u_text = [](const nlohmann::json& u) {
      return u.is_null()
                 ? std::string()
                 : fmt::format(" u {} (correlated {})", u_text_of(u.at("independent")), u_text_of(u.at("correlated")));
    };
    text << fmt::format("# white_sky {:.6f} +- {:.1e}{}\n", bb_ws, bb_ws_err,
                        bb_u.is_null() ? "" : bb_u_text(bb_u.at("white_sky")));
    for (std::size_t z = 0; z < zeniths.size(); ++z) {
      text << fmt::format("# sun zenith {:g} deg: black_sky {:.6f} +- {:.1e}{}", zeniths[z], bb_bs[z], bb_bs_err[z],
                          bb_u.is_null() ? "" : bb_u_text(bb_u.at("black_sky")[z]));
      if (!bb_blue.empty()) {
        text << fmt::format("  blue_sky {:.6f} +- {:.1e}{}", bb_blue[z], bb_blue_err[z],
                            bb_u.is_null() || bb_u.at("blue_sky").is_null() ? "" : bb_u_text(bb_u.at("blue_sky")[z]));
      }
      text << '\n';
    }
  }
  if (!lum_bs.empty()) {
    text << fmt::format("# luminous (V(lambda) x {}): white_sky {:.6f}", illuminant, lum_ws);
    for (std::size_t z = 0; z < zeniths.size(); ++z)
      text << fmt::format("  black_sky_{:g}deg {:.6f}", zeniths[z], lum_bs[z]);
    text << '\n';
  }
  return text.str();
}

}  // namespace roadbrdf::albedo
