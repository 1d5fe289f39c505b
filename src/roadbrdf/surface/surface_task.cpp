// The `surface` task (surface_task.h).
#include "roadbrdf/surface/surface_task.h"

#include <fmt/core.h>

#include <filesystem>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/formulation/formulation.h"

namespace roadbrdf::surface {

SurfaceResult make_surface(const SurfaceRequest& request, const ProgressCallback& progress) {
  request.validate();
  if (!request.preview.empty() && request.output.empty()) {
    throw FieldError("preview", "is written next to the SURFACE file: give `output` too");
  }
  std::vector<FileArgument> inputs, outputs;
  file_arguments(request, SurfaceRequest::fields(), inputs, outputs);
  check_distinct_files(inputs, outputs);
  SurfaceResult result;
  if (request.kind() != SurfaceRequest::Kind::formulation) {
    result.field = validation_surface(request);
  } else {
    if (!request.input.in_memory()) {
      // Fit files are needed only to render: they may not exist yet (warned below), but they are never
      // written over.
      const std::vector<FileArgument> fits = formulation_input_files(read_formulation(request.input.path, false));
      inputs.insert(inputs.end(), fits.begin(), fits.end());
      check_distinct_files(inputs, outputs);
    }
    const SampleRecipe recipe = sample_recipe(request);
    GeneratorSettings settings = request.generator_settings();
    settings.progress = progress;
    GeneratedSample sample = generate_sample(recipe, settings);
    result.field = std::move(sample.field);
    sample.field = HeightField{};
    sample.grains.clear();
    for (const auto& c : recipe.classes) result.classes.push_back(c.material.name);
    for (const std::string& note : sample.notes) result.diagnostics.note("packing", note);
    for (const auto& m : result.field.materials) {
      if (!m.fit_path.empty() && !std::filesystem::exists(m.fit_path)) {
        result.diagnostics.warn("fit_file_missing", fmt::format("fit file of '{}' does not exist yet: {} (needed "
                                                                "to render the surface)",
                                                                m.name, m.fit_path));
      }
    }
    result.sample = std::move(sample);
    result.requested_mastic_fraction = request.mastic_fraction;
  }
  result.statistics = texture_statistics(result.field);
  if (!request.output.empty()) {
    write_surface(result.field, request.output, &result.statistics);
    result.written.push_back(request.output);
    if (!request.preview.empty()) {
      write_preview_png(result.field, request.preview);
      result.written.push_back(request.preview);
    }
  }
  return result;
}

std::string SurfaceResult::summary_text() const {
  const HeightField& f = field;
  const TextureStatistics& s = statistics;
  std::string out;
  if (sample) {
    out += f.description + "\n";
    if (requested_mastic_fraction) {
      out += fmt::format("exposed mastic fraction {:.4f} (requested {}, tolerance {:.4g}) at mastic level {:.4f} mm\n",
                         sample->mastic_fraction, *requested_mastic_fraction, sample->mastic_fraction_tolerance,
                         sample->matrix_level_mm);
    }
  }
  out += fmt::format("surface {}: {} x {} cells of {} mm (periodic {:.4g} x {:.4g} mm)\n", f.name, f.nx, f.ny,
                     f.cell_size_mm, f.size_x_mm(), f.size_y_mm());
  out += fmt::format(
      "MPD {:.3f} mm (ISO 13473-1 style, baseline = sample period), ETD {:.3f} mm, rms height {:.3f} mm, "
      "area ratio {:.3f}\n",
      s.mpd_mm, s.etd_mm, s.rms_height_mm, s.surface_area_ratio);
  out += fmt::format("{:<40} {:>12} {:>12}\n", "material", "area frac.", "true area");
  for (std::size_t k = 0; k < f.materials.size(); ++k) {
    out += fmt::format("{:<40} {:>12.4f} {:>12.4f}\n", f.materials[k].name, s.exposed_area_fraction[k],
                       s.exposed_true_area_fraction[k]);
  }
  // The SURFACE file last: the line a reader looks for.
  for (auto it = written.rbegin(); it != written.rend(); ++it) out += "wrote " + *it + "\n";
  return out;
}

nlohmann::json SurfaceResult::sample_report() const {
  if (!sample) return nullptr;
  nlohmann::json report = sample->to_json();
  report["classes"] = classes;
  return report;
}

}  // namespace roadbrdf::surface
