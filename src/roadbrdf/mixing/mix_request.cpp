#include "roadbrdf/mixing/mix_request.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/mixing/calibration.h"
#include "roadbrdf/mixing/mixture_covariance.h"
#include "roadbrdf/mixing/residual_file.h"

namespace roadbrdf::mixing {

namespace {

std::string weights_text(const MixResult& r) {
  std::ostringstream s;
  for (std::size_t k = 0; k < r.end_members.size(); ++k) {
    if (k) s << ' ';
    s << r.end_members[k] << '=' << fmt::format("{:.3f}", r.weights[k]);
  }
  for (const auto& [key, value] : r.settings) {
    if (key == "shadowing") s << " s=" << fmt::format("{:.3g}", value);
  }
  if (std::isfinite(r.weight_distance)) s << fmt::format(" (dist {:.3f}, sum {:.3f})", r.weight_distance, r.weight_sum);
  return s.str();
}

// The values of MixRequest::method: a method, or every method.
std::vector<std::string> method_choices() {
  std::vector<std::string> names = names_of<Method>();
  names.push_back("all");
  return names;
}

}  // namespace

void MixRequest::validate() const {
  if (formulation.empty()) throw FieldError("formulation", "give the formulation file");
  const std::vector<std::string> choices = method_choices();
  if (std::find(choices.begin(), choices.end(), method) == choices.end()) {
    throw FieldError("method", not_one_of(method, choices));
  }
  if (folds < 2) throw FieldError("folds", "must be at least 2");
  if (seed < 0) throw FieldError("seed", fmt::format("{} is negative (a seed is 0 or more)", seed));
  for (const auto& [name, value] :
       {std::pair{"binder_coverage", binder_coverage}, std::pair{"mastic_fraction", mastic_fraction}}) {
    if (value && !(*value >= 0.0 && *value <= 1.0)) throw FieldError(name, fmt::format("{} is outside [0, 1]", *value));
  }
  if (!residuals.empty() && data.empty())
    throw FieldError("residuals", "needs data (the held-out residuals of a measured mixture)");
  if (!reference.empty() && data.empty()) {
    throw FieldError("reference", "needs data (the albedo is compared at the data's wavelengths)");
  }
  if (!cross_sections.empty() && method != "all" && method != name_of(Method::kHapke)) {
    throw FieldError("cross_sections", "only the hapke method uses cross-section factors (method is '" + method + "')");
  }
  if (method != "all" && data.empty() && method_needs_data(parse_name<Method>(method, "method"))) {
    throw FieldError("method", "'" + method + "' is fitted to a measured mixture: give data");
  }
}

MixRun run_mix(const MixRequest& request) {
  request.validate();
  std::vector<FileArgument> read, outputs;
  file_arguments(request, MixRequest::fields(), read, outputs);
  check_distinct_files(read, outputs);
  MixRun run;
  run.request = request;
  run.request.progress = nullptr;  // the caller's callback does not outlive this call
  const Source& given = request.formulation;
  // A formulation given as a value names fit files that may be values too: they are checked when loaded.
  const Formulation formulation =
      given.in_memory() ? parse_formulation(given.text, given.path, false) : read_formulation(given.path);
  for (const FileArgument& fit : formulation_input_files(formulation)) {
    if (request.fits.count(fit.path) == 0) read.push_back(fit);
  }
  check_distinct_files(read, outputs);
  run.inputs = std::make_unique<MixInputs>(
      load_mix_inputs(formulation, request.end_member_cache ? request.end_member_cache->loader(request.fits)
                                                            : fit_loader(request.fits)));
  MixSettings settings;
  settings.binder_coverage = request.binder_coverage;
  settings.mastic_area_fraction = request.mastic_fraction;
  settings.per_wavelength = request.per_wavelength;
  settings.sum_to_one = request.sum_to_one;
  settings.use_sigma = request.use_sigma;
  if (!request.cross_sections.empty()) {
    settings.cross_section_factors = read_cross_section_factors(request.cross_sections);
    for (std::size_t e = 0; e < run.inputs->end_members.size(); ++e) {
      const EndMember& em = run.inputs->end_members[e];
      if (em.components.empty() || settings.cross_section_factors.count(em.name)) continue;
      std::string known;
      for (const auto& [name, k] : settings.cross_section_factors) known += (known.empty() ? "" : ", ") + name;
      throw FieldError("cross_sections", request.cross_sections + " has no factor for end-member '" + em.name +
                                             "' of " + request.formulation.path + " (it has: " + known + ")");
    }
  }
  const bool all = request.method == "all";
  const std::vector<Method> methods =
      all ? values_of<Method>() : std::vector<Method>{parse_name<Method>(request.method, "method")};
  if (!request.data.empty()) run.data = read_dataset(request.data, request.options_for(request.data));
  std::optional<SpectralModel> reference;
  if (!request.reference.empty()) reference = read_spectral_model_file(request.reference);

  run.content.inputs = run.inputs.get();
  run.content.data_path = request.data;
  run.content.folds = request.folds;
  std::size_t mixes = 0;
  for (Method m : methods) {
    if (run.data) mixes += comparison_mixes(m, request.folds);
    if (!run.data && !method_needs_data(m)) ++mixes;
  }
  ProgressCounter progress(request.progress, mixes);
  for (Method m : methods) {
    if (!run.data && method_needs_data(m)) {
      run.notes.push_back(
          fmt::format("method '{}' skipped: it is fitted to a measured mixture (give data)", name_of(m)));
      continue;
    }
    try {
      if (run.data) {
        Comparison c = compare_method(*run.inputs, m, settings, *run.data, request.folds, request.seed,
                                      reference ? &*reference : nullptr, &progress);
        if (request.uncertainty) attach_parameter_covariance(*run.inputs, c.result);
        run.content.results.push_back(c.result);
        run.content.comparisons.push_back(std::move(c));
      } else {
        MixResult r = mix(*run.inputs, m, settings);
        if (request.uncertainty) attach_parameter_covariance(*run.inputs, r);
        run.content.results.push_back(std::move(r));
        progress.add();
      }
    } catch (const FieldError&) {
      throw;  // a bad request, not a method that does not apply
    } catch (const InputError& e) {
      if (!all) throw;
      run.notes.push_back(fmt::format("method '{}' skipped: {}", name_of(m), e.what()));
    }
  }
  progress.finish();
  if (run.content.results.empty()) throw InputError("no mixing method could be applied to " + request.formulation.path);
  return run;
}

void write_mix_outputs(const MixRun& run) {
  if (!run.request.output.empty()) write_mix_file(run.request.output, run.content);
  if (!run.request.residuals.empty()) write_residual_file(run.request.residuals, *run.data, run.content.comparisons);
}

std::string MixRun::table() const {
  std::string out;
  const MixInputs& in = *inputs;
  out += fmt::format("formulation {} ({} components, {} end-members)\n", in.formulation.name,
                     in.formulation.components.size(), in.end_members.size());
  if (data) {
    out += fmt::format("measured mixture {}: {} geometries x {} wavelengths; errors on held-out geometries ({}-fold)\n",
                       request.data, data->geometry_count(), data->wavelength_count(), request.folds);
    if (const std::size_t missing = missing_value_count(*data); missing > 0) {
      out += fmt::format("{} of {} measured-mixture values missing (left out of the fits and errors)\n", missing,
                         data->brdf.size());
    }
    if (data->has_sigma()) {
      out += fmt::format("fitted methods {} (sigma from the data); chi2/n: held-out reduced chi^2\n",
                         request.use_sigma ? "weighted by 1/sigma^2" : "unweighted");
    }
    out += fmt::format("{:<9} {:>12} {:>9} {:>8} {:>12} {:>8} {:>9}  {}\n", "method", "RMSE[sr-1]", "relRMSE", "chi2/n",
                       "RMSE(fit)", "albedo", "d_albedo", "weights");
    std::size_t best = 0;
    for (std::size_t i = 0; i < content.comparisons.size(); ++i) {
      const Comparison& c = content.comparisons[i];
      if (c.rmse < content.comparisons[best].rmse) best = i;
      out += fmt::format(
          "{:<9} {:>12.5g} {:>9.4f} {:>8} {:>12.5g} {:>8.4f} {:>9}  {}\n", name_of(c.method), c.rmse, c.relative_rmse,
          std::isfinite(c.chi2_reduced) ? fmt::format("{:.4g}", c.chi2_reduced) : std::string("n/a"), c.rmse_in_sample,
          c.albedo,
          std::isfinite(c.albedo_difference) ? fmt::format("{:+.4f}", c.albedo_difference) : std::string("n/a"),
          weights_text(c.result));
    }
    out += fmt::format("best method for {}: {} (held-out RMSE {:.5g} sr^-1)\n", in.formulation.name,
                       name_of(content.comparisons[best].method), content.comparisons[best].rmse);
  } else {
    out += fmt::format("{:<9} {:>8}  {}\n", "method", "albedo", "weights");
    for (const auto& r : content.results) {
      const std::vector<double> albedo = mixture_white_sky_albedo(in, r, r.model->wavelengths());
      double mean = 0.0;
      for (double x : albedo) mean += x / static_cast<double>(albedo.size());
      out += fmt::format("{:<9} {:>8.4f}  {}\n", name_of(r.method), mean, weights_text(r));
    }
  }
  return out;
}

}  // namespace roadbrdf::mixing
