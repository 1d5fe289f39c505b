#include "roadbrdf/io/simulate.h"

#include <fmt/core.h>

#include <cmath>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/random.h"
#include "roadbrdf/io/resample.h"

namespace roadbrdf {

double NoiseModel::shape(double wl) const {
  double s = 1.0;
  if (edge_factor != 1.0 && edge_width_nm > 0.0) {
    s += (edge_factor - 1.0) *
         (std::exp(-(wl - detector_min_nm) / edge_width_nm) + std::exp(-(detector_max_nm - wl) / edge_width_nm));
  }
  if (water_factor != 1.0) {
    s += (water_factor - 1.0) * (std::exp(-sqr((wl - 1400.0) / 50.0)) + std::exp(-sqr((wl - 1900.0) / 60.0)));
  }
  return s;
}

NoiseModel parse_noise_model(const std::string& spec) {
  NoiseModel n;
  if (spec.empty() || spec == "none") return n;
  std::size_t start = 0;
  while (start <= spec.size()) {
    const auto comma = spec.find(',', start);
    const std::string item = spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const auto eq = item.find('=');
    if (eq == std::string::npos) {
      throw FieldError("noise", fmt::format("'{}' is not NAME=VALUE (relative, absolute, edge, edge-width, water, "
                                            "detector-min, detector-max)",
                                            item));
    }
    const std::string name = item.substr(0, eq), text = item.substr(eq + 1);
    double v = 0.0;
    if (!parse_finite_double(text, v) || v < 0.0) {
      throw FieldError("noise." + name, fmt::format("'{}' is not a non-negative number", text));
    }
    if (name == "relative") {
      n.relative = v;
    } else if (name == "absolute") {
      n.absolute = v;
    } else if (name == "edge") {
      n.edge_factor = v;
    } else if (name == "edge-width") {
      n.edge_width_nm = v;
    } else if (name == "water") {
      n.water_factor = v;
    } else if (name == "detector-min") {
      n.detector_min_nm = v;
    } else if (name == "detector-max") {
      n.detector_max_nm = v;
    } else {
      throw FieldError("noise", fmt::format("unknown name '{}' (relative, absolute, edge, edge-width, water, "
                                            "detector-min, detector-max)",
                                            name));
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return n;
}

namespace {

using Overrides = std::vector<std::pair<std::size_t, const spectra::Spectrum*>>;

// The model's parameters replaced by spectra (SimulationInput::spectral_parameters), by index.
Overrides spectral_overrides(const SimulationInput& in, const ModelDescription& desc) {
  Overrides overrides;
  for (const auto& [name, spectrum] : in.spectral_parameters) {
    const auto idx = desc.parameter_index(name);
    if (!idx) {
      std::string list;
      for (const auto& p : desc.parameters) list += fmt::format("{}{}", list.empty() ? "" : ", ", p.name);
      throw InputError(fmt::format("model {} has no parameter '{}' (parameters: {})", desc.name, name, list));
    }
    overrides.emplace_back(*idx, &spectrum);
  }
  return overrides;
}

// The parameter table: one checked set per wavelength (m x np, row-major).
std::vector<double> parameter_table(const SimulationInput& in, const ModelDescription& desc,
                                    const Overrides& overrides) {
  const std::size_t m = in.wavelengths.size(), np = desc.parameters.size();
  std::vector<double> params(m * np);
  for (std::size_t j = 0; j < m; ++j) {
    const double wl = in.wavelengths[j];
    std::vector<double> p = in.model->parameters_at(wl);
    for (const auto& [idx, spectrum] : overrides) {
      p[idx] =
          spectrum->value(wl, fmt::format("spectral parameter {} ({})", desc.parameters[idx].name, spectrum->name()));
    }
    try {
      check_parameters(desc, p);
    } catch (const InputError& e) {
      throw InputError(fmt::format("at {} nm: {}", wl, e.what()));
    }
    std::copy(p.begin(), p.end(), params.begin() + static_cast<long>(j * np));
  }
  return params;
}

}  // namespace

SpectralDataset simulate_dataset(const SimulationInput& in) {
  if (!in.model) throw InputError("simulate: no model");
  if (in.geometries.empty()) throw InputError("simulate: the grid has no geometries");
  if (in.wavelengths.empty()) throw InputError("simulate: no wavelengths");
  for (std::size_t j = 1; j < in.wavelengths.size(); ++j) {
    if (!(in.wavelengths[j] > in.wavelengths[j - 1]))
      throw InputError("simulate: wavelengths must be strictly increasing");
  }
  const Model& model = in.model->model();
  const ModelDescription& desc = model.description();
  const std::size_t n = in.geometries.size(), m = in.wavelengths.size(), np = model.parameter_count();
  const Overrides overrides = spectral_overrides(in, desc);
  const std::vector<double> params = parameter_table(in, desc, overrides);
  SpectralDataset d;
  d.geometries = in.geometries;
  d.convention = in.convention;
  d.wavelengths = in.wavelengths;
  d.brdf.assign(n * m, 0.0);
  model.evaluate_batch(d.geometries.data(), n, params.data(), m, d.brdf.data());
  const bool noisy = !in.noise.is_zero();
  if (noisy && in.write_sigma) d.sigma.assign(n * m, 0.0);
  NormalStream normal(in.seed);
  if (noisy) {
    std::vector<double> shape(m);
    for (std::size_t j = 0; j < m; ++j) shape[j] = in.noise.shape(in.wavelengths[j]);
    for (std::size_t g = 0; g < n; ++g) {
      for (std::size_t j = 0; j < m; ++j) {
        const double f = d.brdf[g * m + j];
        const double s = std::sqrt(sqr(in.noise.relative * f) + sqr(in.noise.absolute)) * shape[j];
        d.brdf[g * m + j] = f + s * normal.next();
        if (in.write_sigma) d.sigma[g * m + j] = s;
      }
    }
  }
  if (in.significant_digits > 0) {
    auto round_to = [](double v, int digits) {
      if (v == 0.0 || !std::isfinite(v)) return v;
      const double e = std::floor(std::log10(std::fabs(v))) + 1 - digits;
      const double scale = std::pow(10.0, -e);
      return std::round(v * scale) / scale;
    };
    for (auto& v : d.brdf) v = round_to(v, in.significant_digits);
    for (auto& v : d.sigma) v = round_to(v, 2);
    d.metadata["digits"] = fmt::format("values rounded to {} significant digits, sigma to 2", in.significant_digits);
  }
  d.metadata["units"] = "sr^-1";
  d.metadata["synthetic"] = "yes: simulated by roadbrdf simulate (virtual gonioreflectometer), not a measurement";
  d.metadata["model"] = desc.name;
  std::string params_text;
  for (std::size_t k = 0; k < np; ++k) {
    bool spectral = false;
    for (const auto& [idx, sp] : overrides) spectral = spectral || idx == k;
    if (spectral) {
      params_text += fmt::format("{}{}=spectrum", params_text.empty() ? "" : " ", desc.parameters[k].name);
    } else if (!in.model->is_spectral()) {
      params_text += fmt::format("{}{}={}", params_text.empty() ? "" : " ", desc.parameters[k].name, params[k]);
    }
  }
  if (in.model->is_spectral()) params_text += fmt::format("{}(from a fit, spectral)", params_text.empty() ? "" : " ");
  d.metadata["parameters"] = params_text;
  for (const auto& [name, sp] : in.spectral_parameters) d.metadata["spectrum_" + name] = sp.name();
  d.metadata["noise"] =
      noisy ? fmt::format("relative={} absolute={} edge={} edge-width={} water={} detector={}-{} nm", in.noise.relative,
                          in.noise.absolute, in.noise.edge_factor, in.noise.edge_width_nm, in.noise.water_factor,
                          in.noise.detector_min_nm, in.noise.detector_max_nm)
            : "none";
  d.metadata["seed"] = std::to_string(in.seed);
  if (desc.has_delta) d.metadata["ideal_specular_part"] = "not sampled (a delta peak cannot be measured at a geometry)";
  return d;
}

}  // namespace roadbrdf
