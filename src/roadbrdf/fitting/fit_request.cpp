#include "roadbrdf/fitting/fit_request.h"

#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/geometry_selection.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {

namespace {

// Does `model` declare option `key` (directly, or for a component when `key` is a plain name)?
bool declares_option(const ModelDescription& d, const std::string& key) {
  for (const auto& o : d.options) {
    if (o.name == key) return true;
    if (o.name.size() > key.size() + 1 &&
        o.name.compare(o.name.size() - key.size() - 1, std::string::npos, "." + key) == 0) {
      return true;
    }
  }
  return false;
}

std::vector<std::string> plain_and_full_option_names(const std::vector<std::shared_ptr<const Model>>& models) {
  std::vector<std::string> names;
  for (const auto& m : models) {
    for (const auto& o : m->description().options) {
      names.push_back(o.name);
      const auto dot = o.name.find('.');
      if (dot != std::string::npos) names.push_back(o.name.substr(dot + 1));
    }
  }
  return names;
}

std::vector<std::string> parameter_names(const std::vector<std::shared_ptr<const Model>>& models) {
  std::vector<std::string> names;
  for (const auto& m : models) {
    for (const auto& p : m->description().parameters) names.push_back(p.name);
  }
  return names;
}

FitOptions settings_of(const FitRequest& r) {
  FitOptions o;
  o.loss = fit_loss_from_string(r.loss, "loss");
  robust_loss_from_string(r.robust, o.robust, o.robust_scale, "robust");
  check_fit_counts(r.multistart, r.threads, r.max_iterations);
  o.use_sigma = r.use_sigma;
  if (r.sigma_from_duplicates && !r.use_sigma) {
    throw FieldError("sigma_from_duplicates", "with `use_sigma` off the sigma from the duplicates would not be used");
  }
  o.solid_angle_weights = r.solid_angle_weights;
  o.multistart = r.multistart;
  if (r.seed < 0) throw FieldError("seed", fmt::format("{} is negative (a seed is 0 or more)", r.seed));
  o.seed = static_cast<unsigned>(r.seed);
  o.threads = r.threads;
  o.max_iterations = r.max_iterations;
  o.compute_covariance = r.covariance;
  o.warm_start = r.warm_start;
  o.solve_linear = r.solve_amplitudes;
  o.joint_solver = parse_name<JointSolver>(r.joint_solver, "joint_solver");
  return o;
}

void check_finite(const std::map<std::string, double>& values, const std::string& field) {
  for (const auto& [name, v] : values) {
    if (!std::isfinite(v)) throw FieldError(field + "." + name, fmt::format("{} is not a finite number", v));
  }
}

}  // namespace

namespace {

// The checks of the request that need no model (after settings_of): finite values, intervals, bands, the selection
// grammar, model names given once.
void check_request(const FitRequest& r) {
  check_finite(r.fixed, "fixed");
  check_finite(r.start, "start");
  for (const auto& [name, range] : r.bounds) {
    if (!std::isfinite(range.first) || !std::isfinite(range.second) || !(range.first < range.second)) {
      throw FieldError("bounds." + name,
                       fmt::format("[{}, {}] is not an interval lower < upper", range.first, range.second));
    }
  }
  if (!r.bands.empty() && !r.wavelengths.empty()) {
    throw FieldError("bands", "give wavelengths or bands, not both");
  }
  for (std::size_t b = 0; b < r.bands.size(); ++b) {
    const auto [lower, upper] = r.bands[b];
    if (!std::isfinite(lower) || !std::isfinite(upper) || !(lower > 0.0) || !(lower < upper)) {
      throw FieldError("bands", fmt::format("{}:{} nm is not a band 0 < lower < upper", lower, upper));
    }
    for (std::size_t c = 0; c < b; ++c) {
      if (lower < r.bands[c].second && r.bands[c].first < upper) {
        throw FieldError("bands",
                         fmt::format("{}:{} nm overlaps {}:{} nm", lower, upper, r.bands[c].first, r.bands[c].second));
      }
    }
  }
  if (!r.where.empty()) (void)parse_geometry_selection(r.where, "where");
  (void)group_geometries({}, r.group_by, "group_by");  // the column names
  std::set<std::string> names_seen;
  for (const auto& name : r.models) {
    if (!names_seen.insert(name).second) throw FieldError("models", "'" + name + "' is given twice");
  }
}

// The model `name` made with the options it declares (a plain name reaches every component that
// declares it); a refused option is named.
std::shared_ptr<const Model> model_with_options(const std::string& name, const Model& probe, const OptionSet& options,
                                                std::set<std::string>& used_options) {
  OptionSet mine;
  for (const auto& [k, v] : options) {
    if (declares_option(probe.description(), k)) {
      mine[k] = v;
      used_options.insert(k);
    }
  }
  try {
    return make_model(name, mine);
  } catch (const InputError& e) {
    // Say which option: try them one at a time.
    for (const auto& [k, v] : mine) {
      try {
        make_model(name, {{k, v}});
      } catch (const InputError& one) {
        throw FieldError("options." + k, one.what());
      }
    }
    throw FieldError("options", e.what());
  }
}

// The entries of `values` that name a parameter of the model, into `out`; each recorded as used
// ("fixed.roughness").
template <class Value>
void take_parameters(const std::map<std::string, Value>& values, const ModelDescription& desc, const std::string& field,
                     std::map<std::string, Value>& out, std::set<std::string>& used) {
  for (const auto& [k, v] : values) {
    if (desc.parameter_index(k)) {
      out[k] = v;
      used.insert(field + "." + k);
    }
  }
}

// The shared parameters of one model: "auto" = its spectral-independent (non-spectral) free ones.
void take_shared(const std::vector<std::string>& shared, const ModelDescription& desc, FitOptions& options,
                 std::set<std::string>& used) {
  auto add = [&](const std::string& name) {
    if (std::find(options.shared.begin(), options.shared.end(), name) == options.shared.end()) {
      options.shared.push_back(name);
    }
  };
  for (const auto& k : shared) {
    if (k == "auto") {
      for (const auto& q : desc.parameters) {
        if (!q.spectral && !options.fixed.count(q.name)) add(q.name);
      }
      used.insert("shared.auto");
    } else if (desc.parameter_index(k)) {
      add(k);
      used.insert("shared." + k);
    }
  }
}

// Every option and parameter name of the request must reach at least one model: a misspelt name is
// an error naming the nearest known one, never silently ignored.
void check_all_used(const FitRequest& r, const std::vector<std::shared_ptr<const Model>>& probes,
                    const std::set<std::string>& used_options, const std::set<std::string>& used_parameters) {
  for (const auto& [k, v] : r.options) {
    if (!used_options.count(k)) {
      throw FieldError("options." + k,
                       "no model to fit has this option" + did_you_mean(k, plain_and_full_option_names(probes)));
    }
  }
  const std::vector<std::string> known = parameter_names(probes);
  auto check_used = [&](const std::string& field, const std::string& k) {
    if (!used_parameters.count(field + "." + k)) {
      throw FieldError(field + "." + k,
                       "no model to fit has this parameter" + did_you_mean(k, known) + " (see `roadbrdf models`)");
    }
  };
  for (const auto& [k, v] : r.fixed) check_used("fixed", k);
  for (const auto& [k, v] : r.start) check_used("start", k);
  for (const auto& [k, v] : r.bounds) check_used("bounds", k);
  for (const auto& k : r.shared) {
    if (k != "auto") check_used("shared", k);
  }
}

}  // namespace

std::vector<PlannedFit> plan_fits(const FitRequest& r) {
  if (r.models.empty()) throw FieldError("models", "give at least one model");
  const FitOptions base = settings_of(r);
  check_request(r);
  // The models without options, to see who declares what.
  std::vector<std::shared_ptr<const Model>> probes;
  for (const auto& name : r.models) {
    try {
      probes.push_back(make_model(name));
    } catch (const InputError& e) {
      throw FieldError("models", e.what());
    }
  }
  std::set<std::string> used_options, used_parameters;
  std::vector<PlannedFit> plan;
  for (std::size_t i = 0; i < r.models.size(); ++i) {
    PlannedFit p;
    p.model = model_with_options(r.models[i], *probes[i], r.options, used_options);
    const ModelDescription& desc = p.model->description();
    p.options = base;
    take_parameters(r.fixed, desc, "fixed", p.options.fixed, used_parameters);
    take_parameters(r.start, desc, "start", p.options.start, used_parameters);
    take_parameters(r.bounds, desc, "bounds", p.options.bounds, used_parameters);
    take_shared(r.shared, desc, p.options, used_parameters);
    plan.push_back(std::move(p));
  }
  check_all_used(r, probes, used_options, used_parameters);
  return plan;
}

void FitRequest::validate() const { (void)plan_fits(*this); }

std::string FitSummary::table() const {
  std::string out;
  const std::size_t M = wavelengths.size();
  out += fmt::format("# {} geometries x {} wavelengths ({}-{} nm), loss {}{}{}\n", geometry_count, M,
                     M ? wavelengths.front() : 0.0, M ? wavelengths.back() : 0.0, loss,
                     robust.empty() || robust == "none" ? "" : ", robust " + robust,
                     sigma_weights ? ", weights 1/sigma^2" : "");
  for (const auto& note : notes) out += "# note: " + note + "\n";
  if (!where.empty()) {
    out += fmt::format("# where {}: {} of {} geometries\n", where, geometry_count, dataset_geometries);
  }
  if (!group_by.empty()) {
    out += fmt::format("# grouped by {}: {} groups, each fitted separately; ranks are within a group\n",
                       fmt::join(group_by, ","), group_count);
  }
  if (missing_values > 0) {
    out += fmt::format("# {} of {} values missing (masked out of the fit at their wavelength)\n", missing_values,
                       geometry_count * M);
  }
  const bool grouped = !group_by.empty();
  out += fmt::format("{:<4} {}{:<36} {:>6} {:>12} {:>9} {:>9} {:>14} {:>14} {:>9} {:>8} {:>8}\n", "rank",
                     grouped ? fmt::format("{:<24} ", "group") : "", "model", "k", "RMSE[sr^-1]", "relRMSE%", "maxrel%",
                     "AIC", "BIC", "converged", "atbound", "time[s]");
  auto number_or_dash = [](double x, const char* format) {
    return std::isfinite(x) ? fmt::format(fmt::runtime(format), x) : std::string("-");
  };
  std::size_t rank = 0;
  for (std::size_t r = 0; r < ranking.size(); ++r) {
    const FitResult& f = fits[ranking[r]];
    rank = r > 0 && fits[ranking[r - 1]].group == f.group ? rank + 1 : 1;
    GeometryGroup group;
    group.key = f.group;
    out += fmt::format("{:<4} {}{:<36} {:>6} {:>12} {:>9} {:>9} {:>14} {:>14} {:>9} {:>8} {:>8.2f}\n", rank,
                       grouped ? fmt::format("{:<24} ", group.label()) : "", f.model, f.free_parameters_total,
                       number_or_dash(f.rmse_total, "{:.4g}"), number_or_dash(100.0 * f.relative_rmse_total, "{:.3g}"),
                       number_or_dash(100.0 * f.max_relative_error_total, "{:.3g}"),
                       number_or_dash(f.aic_total, "{:.2f}"), number_or_dash(f.bic_total, "{:.2f}"),
                       fmt::format("{}/{}", f.converged_count, M), f.at_bound_count, f.seconds);
  }
  for (const FitResult& f : fits) {
    for (const std::string& simpler : f.worse_than_nested) {
      const auto other = std::find_if(fits.begin(), fits.end(),
                                      [&](const FitResult& x) { return x.model == simpler && x.group == f.group; });
      out += fmt::format(
          "# flag: {} fits worse (RMSE {:.4g}) than {} (RMSE {:.4g}), a model it contains: its fit missed the "
          "optimum (try `multistart` or `start`)\n",
          f.model, f.rmse_total, simpler, other == fits.end() ? std::nan("") : other->rmse_total);
    }
  }
  if (!ranking.empty()) {
    out += grouped ? fmt::format("best (lowest BIC summed over the groups): {}\n", fits[best_fit_index(fits)].model)
                   : fmt::format("best (lowest total BIC): {}\n", best().model);
  }
  return out;
}

std::vector<std::string> FitSummary::warnings(const std::string& where) const {
  std::vector<std::string> out;
  const std::size_t M = wavelengths.size();
  for (const auto& f : fits) {
    // The model's name, with its group when grouped ("oren-nayar [theta_i=40]").
    std::string name = f.model;
    if (!f.group.empty()) {
      GeometryGroup group;
      group.key = f.group;
      name += " [" + group.label() + "]";
    }
    if (f.converged_count < M) {
      out.push_back(fmt::format("{}: {} of {} wavelengths did not converge (see 'status' in {})", name,
                                M - f.converged_count, M, where));
    }
    if (f.at_bound_count > 0) {
      out.push_back(fmt::format("{}: parameters on a bound at {} of {} wavelengths (see 'at_bounds')", name,
                                f.at_bound_count, M));
    }
    if (f.stayed_at_start_count > 0) {
      std::string names;
      for (std::size_t k = 0; k < f.parameter_names.size(); ++k) {
        const bool fixed = std::find(f.fixed.begin(), f.fixed.end(), f.parameter_names[k]) != f.fixed.end();
        if (!fixed) names += (names.empty() ? "" : ", ") + f.parameter_names[k];
      }
      out.push_back(
          fmt::format("{}: at {} of {} wavelengths the fit reports convergence but its nonlinear parameters "
                      "never left their starting values: the data may not constrain them (look at the "
                      "geometries with `roadbrdf check`, fix them with `fixed`, or try `start`/`multistart`; "
                      "free parameters: {})",
                      name, f.stayed_at_start_count, M, names));
    }
    if (f.settings.compute_covariance && f.covariance_failures > 0) {
      out.push_back(fmt::format("{}: no standard errors at {} of {} wavelengths (see 'covariance_message')", name,
                                f.covariance_failures, M));
    }
  }
  return out;
}

namespace {

// The dataset's geometries selected by `where` and grouped by `group_by` (one group of all without).
std::vector<GeometryGroup> fit_groups(const FitRequest& request, const SpectralDataset& data) {
  const GeometrySelection selection =
      request.where.empty() ? GeometrySelection{} : parse_geometry_selection(request.where, "where");
  std::vector<std::size_t> selected;
  std::vector<Geometry> geometries;
  for (std::size_t g = 0; g < data.geometry_count(); ++g) {
    if (!selection.matches(data.geometries[g])) continue;
    selected.push_back(g);
    geometries.push_back(data.geometries[g]);
  }
  if (selected.empty()) {
    throw FieldError("where",
                     fmt::format("'{}' selects none of the {} geometries", request.where, data.geometry_count()));
  }
  std::vector<GeometryGroup> groups = group_geometries(geometries, request.group_by, "group_by");
  for (auto& group : groups) {
    for (auto& index : group.indices) index = selected[index];
  }
  return groups;
}

}  // namespace

namespace {

std::vector<std::string> components_of(const std::string& name) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t plus = name.find('+', start);
    out.push_back(name.substr(start, plus == std::string::npos ? std::string::npos : plus - start));
    if (plus == std::string::npos) return out;
    start = plus + 1;
  }
}

// Whether the registered model `richer` equals `simpler` or reduces to it (ModelDescription::reduces_to).
bool component_contains(const std::string& richer, const std::string& simpler) {
  if (richer == simpler) return true;
  try {
    const std::unique_ptr<Model> model = make_model(richer);  // outlives the loop over its description
    for (const auto& [name, values] : model->description().reduces_to) {
      if (name == simpler) return true;
    }
  } catch (const InputError&) {
  }
  return false;
}

// Assign each of simpler[k...] to a distinct unused component of `richer` that contains it.
bool assign_components(const std::vector<std::string>& simpler, std::size_t k, const std::vector<std::string>& richer,
                       std::vector<bool>& used) {
  if (k == simpler.size()) return true;
  for (std::size_t r = 0; r < richer.size(); ++r) {
    if (used[r] || !component_contains(richer[r], simpler[k])) continue;
    used[r] = true;
    if (assign_components(simpler, k + 1, richer, used)) return true;
    used[r] = false;
  }
  return false;
}

}  // namespace

bool model_contains(const std::string& richer, const std::string& simpler) {
  if (richer == simpler) return false;
  const std::vector<std::string> r = components_of(richer), s = components_of(simpler);
  if (s.size() > r.size()) return false;
  std::vector<bool> used(r.size(), false);
  return assign_components(s, 0, r, used);
}

void flag_worse_than_nested(std::vector<FitResult>& fits, std::size_t first) {
  for (std::size_t i = first; i < fits.size(); ++i) {
    for (std::size_t j = first; j < fits.size(); ++j) {
      if (i == j || !model_contains(fits[i].model, fits[j].model)) continue;
      // The richer model can always reproduce the simpler fit, so a worse fit missed its optimum. The
      // margin (0.1 % of the simpler fit's relative RMSE, plus 1e-6 of the data) keeps the convergence
      // tolerance of two near-perfect fits from being flagged.
      if (fits[i].relative_rmse_total > fits[j].relative_rmse_total * (1.0 + 1e-3) + 1e-6) {
        fits[i].worse_than_nested.push_back(fits[j].model);
      }
    }
  }
}

FitSummary run_fit(const FitRequest& request, const SpectralDataset& dataset, const FitProgress& progress) {
  std::vector<PlannedFit> plan = plan_fits(request);
  const SpectralDataset* data = &dataset;
  SpectralDataset subset;
  std::vector<std::string> notes;
  if (request.sigma_from_duplicates) {
    const auto source = dataset.metadata.find("sigma_from_duplicates");
    if (source == dataset.metadata.end()) {
      throw FieldError("sigma_from_duplicates",
                       "needs the dataset's file (`data`): the repeatability comes from its duplicate rows, which "
                       "a dataset in memory holds averaged already");
    }
    notes.push_back("sigma from the repeatability of duplicate rows: " + source->second);
  }
  if (!request.wavelengths.empty() || !request.bands.empty() || !grazing_geometries(dataset).empty()) {
    subset = fitted_spectra(request, dataset, &notes);
    data = &subset;
  }
  const std::vector<GeometryGroup> groups = fit_groups(request, *data);
  const bool grouped = !request.group_by.empty();
  FitSummary s;
  s.dataset_geometries = data->geometry_count();
  s.notes = notes;
  s.where = request.where;
  s.group_by = request.group_by;
  s.group_count = groups.size();
  s.wavelengths = data->wavelengths;
  s.loss = name_of(plan.front().options.loss);
  s.robust = name_of(plan.front().options.robust);
  s.sigma_weights = data->has_sigma() && request.use_sigma;
  const std::size_t total = groups.size() * plan.size();
  for (const GeometryGroup& group : groups) {
    const bool everything = group.indices.size() == data->geometry_count();
    const SpectralDataset part = everything ? SpectralDataset{} : subset_geometries(*data, group.indices);
    const SpectralDataset& fitted = everything ? *data : part;
    s.geometry_count += fitted.geometry_count();
    s.missing_values += missing_value_count(fitted);
    const std::size_t first = s.fits.size();
    for (std::size_t i = 0; i < plan.size(); ++i) {
      FitOptions o = plan[i].options;
      if (progress) {
        o.progress = progress(fmt::format("fit {}{} ({}/{})", plan[i].model->description().name,
                                          grouped ? fmt::format(" {}", group.label()) : std::string(),
                                          s.fits.size() + 1, total));
      }
      try {
        s.fits.push_back(fit_model(*plan[i].model, fitted, o));
      } catch (const FieldError&) {
        throw;
      } catch (const InputError& e) {
        if (!grouped) throw;
        throw FieldError("group_by",
                         fmt::format("group {} ({} geometries): {}", group.label(), fitted.geometry_count(), e.what()));
      }
      s.fits.back().group = group.key;
      s.models.push_back(plan[i].model);
    }
    flag_worse_than_nested(s.fits, first);
    std::vector<std::size_t> ranks(plan.size());
    for (std::size_t i = 0; i < ranks.size(); ++i) ranks[i] = first + i;
    std::stable_sort(ranks.begin(), ranks.end(),
                     [&](std::size_t x, std::size_t y) { return s.fits[x].bic_total < s.fits[y].bic_total; });
    s.ranking.insert(s.ranking.end(), ranks.begin(), ranks.end());
  }
  return s;
}

}  // namespace roadbrdf
