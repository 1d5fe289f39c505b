// End-members prepared once for many mixtures (end_member_cache.h).
#include "roadbrdf/mixing/end_member_cache.h"

#include <cmath>
#include <filesystem>
#include <system_error>

#include "roadbrdf/core/error.h"
#include "roadbrdf/modelfile/fit_file_read.h"

namespace roadbrdf::mixing {

namespace {

std::vector<double> geometry_key(const std::vector<Geometry>& geometries) {
  std::vector<double> key;
  key.reserve(geometries.size() * 11);
  for (const Geometry& g : geometries) {
    key.insert(key.end(), {g.wi.x, g.wi.y, g.wi.z, g.wr.x, g.wr.y, g.wr.z, g.theta_i, g.phi_i, g.theta_r, g.phi_r,
                           g.cos_delta_phi});
  }
  return key;
}

// End-member k's parameters in every set of the mixture's parameter rows (as evaluate_batch slices them).
std::vector<double> member_sets(const MixtureModel& mixture, std::size_t k, const double* params, std::size_t n_sets) {
  const std::size_t n = mixture.parameter_count();
  const std::size_t pk = mixture.component(k).parameter_count();
  const std::size_t offset = mixture.component_offset(k);
  std::vector<double> sets(n_sets * pk);
  for (std::size_t s = 0; s < n_sets; ++s) {
    std::copy(params + s * n + offset, params + s * n + offset + pk,
              sets.begin() + static_cast<std::ptrdiff_t>(s * pk));
  }
  return sets;
}

// The integrals of a linear mixture as the same combination of its end-members' (end_member_cache.h).
class LinearMixtureIntegrals final : public albedo::HemisphericalIntegrals {
 public:
  LinearMixtureIntegrals(const MixtureModel& mixture, EndMemberCache& cache) : mixture_(mixture), cache_(cache) {}

  albedo::SpectralIntegral black_sky(const Model& model, const double* params, std::size_t n_sets, double theta_s,
                                     double phi_s, bool azimuth_mean,
                                     const albedo::QuadratureSettings& settings) const override {
    if (&model != &mixture_) {
      return HemisphericalIntegrals::black_sky(model, params, n_sets, theta_s, phi_s, azimuth_mean, settings);
    }
    return combine(params, n_sets, false, theta_s, phi_s, azimuth_mean, settings);
  }

  albedo::SpectralIntegral white_sky(const Model& model, const double* params, std::size_t n_sets,
                                     const albedo::QuadratureSettings& settings) const override {
    if (&model != &mixture_) return HemisphericalIntegrals::white_sky(model, params, n_sets, settings);
    return combine(params, n_sets, true, 0.0, 0.0, false, settings);
  }

 private:
  albedo::SpectralIntegral combine(const double* params, std::size_t n_sets, bool white, double theta_s, double phi_s,
                                   bool azimuth_mean, const albedo::QuadratureSettings& settings) const {
    const std::size_t n = mixture_.parameter_count();
    albedo::SpectralIntegral out;
    out.value.assign(n_sets, 0.0);
    out.error.assign(n_sets, 0.0);
    for (std::size_t k = 0; k < mixture_.component_count(); ++k) {
      const albedo::SpectralIntegral member =
          cache_.integral(mixture_.component_ptr(k), member_sets(mixture_, k, params, n_sets), n_sets, white, theta_s,
                          phi_s, azimuth_mean, settings);
      for (std::size_t s = 0; s < n_sets; ++s) {
        const double a = params[s * n + mixture_.weight_index(k)];
        out.value[s] += a * member.value[s];
        out.error[s] += std::fabs(a) * member.error[s];
      }
      out.converged = out.converged && member.converged;
      out.geometries += member.geometries;
    }
    return out;
  }

  const MixtureModel& mixture_;
  EndMemberCache& cache_;
};

const MixtureModel& mixture_of(const MixResult& result) {
  if (!result.mixture || !result.model || result.model->model_ptr().get() != result.mixture.get()) {
    throw InputError("internal: a mixing result without its mixture model");
  }
  return *result.mixture;
}

}  // namespace

FitLoader EndMemberCache::loader(const std::map<std::string, std::string>& texts) {
  return [this, texts](const std::string& path, const std::string& fit_model) {
    std::error_code error;
    Fit now;
    const auto given = texts.find(path);
    if (given != texts.end()) {
      // A value: known again by its length and hash, as a file by its size and modification time.
      now.size = static_cast<long long>(given->second.size());
      now.modified = static_cast<long long>(std::hash<std::string>{}(given->second));
    } else {
      const auto size = std::filesystem::file_size(path, error);
      const auto modified = std::filesystem::last_write_time(path, error);
      if (!error) {
        now.size = static_cast<long long>(size);
        now.modified = static_cast<long long>(modified.time_since_epoch().count());
      }
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = fits_.find({path, fit_model});
      if (!error && it != fits_.end() && it->second.size == now.size && it->second.modified == now.modified) {
        return *it->second.model;
      }
    }
    now.model = std::make_shared<const SpectralModel>(
        given != texts.end() ? parse_fit_file(given->second, path, fit_model) : read_fit_file(path, fit_model));
    std::lock_guard<std::mutex> lock(mutex_);
    ++fits_read_;
    if (!error) fits_[{path, fit_model}] = now;
    return *now.model;
  };
}

albedo::SpectralIntegral EndMemberCache::integral(const std::shared_ptr<const Model>& model,
                                                  const std::vector<double>& params, std::size_t n_sets, bool white_sky,
                                                  double theta_s, double phi_s, bool azimuth_mean,
                                                  const albedo::QuadratureSettings& settings) {
  IntegralKey key{model.get(),
                  {white_sky ? 1.0 : 0.0, white_sky ? 0.0 : theta_s, white_sky ? 0.0 : phi_s,
                   !white_sky && azimuth_mean ? 1.0 : 0.0, settings.tolerance,
                   static_cast<double>(settings.max_geometries), static_cast<double>(n_sets)},
                  params};
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = integrals_.find(key);
    if (it != integrals_.end()) return it->second;
  }
  // Outside the lock: another thread may compute the same integral meanwhile (same result).
  const albedo::HemisphericalIntegrals quadrature;
  albedo::SpectralIntegral value =
      white_sky ? quadrature.white_sky(*model, params.data(), n_sets, settings)
                : quadrature.black_sky(*model, params.data(), n_sets, theta_s, phi_s, azimuth_mean, settings);
  std::lock_guard<std::mutex> lock(mutex_);
  models_.push_back(model);
  ++integrals_computed_;
  return integrals_.emplace(std::move(key), std::move(value)).first->second;
}

std::shared_ptr<const std::vector<double>> EndMemberCache::values(const std::shared_ptr<const Model>& model,
                                                                  const std::vector<Geometry>& geometries,
                                                                  const std::vector<double>& params,
                                                                  std::size_t n_sets) {
  ValuesKey key{model.get(), geometry_key(geometries), params};
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = values_.find(key);
    if (it != values_.end()) return it->second;
  }
  auto v = std::make_shared<std::vector<double>>(geometries.size() * n_sets);
  model->evaluate_batch(geometries.data(), geometries.size(), params.data(), n_sets, v->data());
  std::lock_guard<std::mutex> lock(mutex_);
  models_.push_back(model);
  ++values_computed_;
  return values_.emplace(std::move(key), std::move(v)).first->second;
}

nlohmann::json mixture_albedo(const MixResult& result, const albedo::AlbedoRequest& request, EndMemberCache& cache) {
  const MixtureModel& mixture = mixture_of(result);
  if (!method_is_linear(result.method)) return albedo::compute_albedo(*result.model, request);
  if (mixture.kind() != MixtureKind::kLinear) {
    throw InputError("internal: method '" + name_of(result.method) + "' is declared linear but its mixture is " +
                     name_of(mixture.kind()));
  }
  return albedo::compute_albedo(*result.model, request, LinearMixtureIntegrals(mixture, cache));
}

photometry::WeightedBrdf mixture_weighted_brdf(const MixResult& result, EndMemberCache& cache) {
  mixture_of(result);  // checked
  // What weighted_brdf (photometry/rtable.h) computes, with MixtureModel::evaluate_batch's end-member
  // values taken from the cache and combined the same way. The mixture is kept alive by the function.
  const std::shared_ptr<const MixtureModel> keep = result.mixture;
  return [keep, &cache](const SpectralModel& model, const photometry::SpectralWeighting& weighting,
                        const std::vector<Geometry>& geometries) {
    const MixtureModel& mixture = *keep;
    if (&model.model() != &mixture) return photometry::weighted_brdf(model, weighting, geometries);
    const std::size_t n = mixture.parameter_count();
    photometry::WeightedWavelengths w;
    std::vector<double> params;
    if (model.is_spectral()) {
      w = photometry::weighted_wavelengths(model, weighting);
      for (double wavelength : w.wavelengths) {
        const std::vector<double> p = model.parameters_at(wavelength);
        params.insert(params.end(), p.begin(), p.end());
      }
      if (params.size() != w.weights.size() * n) throw InputError("no wavelength to weight");
    } else {
      params = model.parameter_table();
    }
    const std::size_t n_sets = model.is_spectral() ? w.weights.size() : 1;
    const std::size_t K = mixture.component_count();
    std::vector<std::shared_ptr<const std::vector<double>>> member(K);
    for (std::size_t k = 0; k < K; ++k) {
      member[k] =
          cache.values(mixture.component_ptr(k), geometries, member_sets(mixture, k, params.data(), n_sets), n_sets);
    }
    std::vector<double> out(geometries.size(), 0.0), f(K);
    for (std::size_t g = 0; g < geometries.size(); ++g) {
      double sum = 0.0;
      for (std::size_t s = 0; s < n_sets; ++s) {
        for (std::size_t k = 0; k < K; ++k) f[k] = (*member[k])[g * n_sets + s];
        const double value = mixture.combine(params.data() + s * n, geometries[g], f.data(), nullptr);
        if (!model.is_spectral()) {
          sum = value;
        } else {
          sum += w.weights[s] * value;
        }
      }
      out[g] = sum;
    }
    return out;
  };
}

photometry::RTableReport mixture_rtable(const MixResult& result, const photometry::RTableRequest& request,
                                        EndMemberCache& cache) {
  return photometry::rtable_report(*result.model, request, mixture_weighted_brdf(result, cache));
}

}  // namespace roadbrdf::mixing
