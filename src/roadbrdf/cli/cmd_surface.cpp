// roadbrdf surface FORMULATION.json [--size 60mm] [--cell 0.1] [--seed S]
//                  [--matrix-level F | --target-mpd MM | --mastic-fraction F]
//                  [--preview FILE.png] -o SURFACE.json
// roadbrdf surface MATERIAL (--flat | --gaussian-slopes SIGMA) [-p NAME=VALUE] [--option NAME=VALUE] -o SURFACE.json
// roadbrdf render SURFACE.json (--grid GRID.csv | --albedo ZENITHS [--white-sky-nodes N])
//                 [--wavelengths A:B:STEP] [--samples N | --target-error E
//                 [--max-samples N] [--error-floor F]] [--sampling brdf|cosine] [--acceptance DEG]
//                 [--seed S] [--threads T] [--max-bounces K] -o DATA.csv|ALBEDO.csv
// Virtual road samples and the virtual gonioreflectometer (src/roadbrdf/surface/).
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/length.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/formulation/formulation.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/geometry_file.h"
#include "roadbrdf/io/resample.h"
#include "roadbrdf/models/spectral_model.h"
#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/height_field.h"
#include "roadbrdf/surface/materials.h"
#include "roadbrdf/surface/render.h"
#include "roadbrdf/surface/render_request.h"
#include "roadbrdf/surface/surface_request.h"
#include "roadbrdf/surface/virtual_albedo.h"

namespace roadbrdf::cli {

namespace {

struct SurfaceArgs {
  std::string input;
  std::string size;  // empty: 60mm
  double cell = 0.1;
  std::uint64_t seed = 1;
  std::optional<double> matrix_level;
  std::optional<double> target_mpd;
  std::optional<double> mastic_fraction;
  std::string preview;
  bool flat = false;
  std::optional<double> gaussian_slopes;
  int cells = 0;
  std::vector<std::string> parameter_items, option_items;
  std::string fit;
  std::string output;
  bool quiet = false;
};

// The material argument: a fit file or a model name with -p/--option (checked by the library).
surface::MaterialSpec material_from_argument(const SurfaceArgs& a) {
  const std::map<std::string, double> parameters = parse_numeric_assignments(a.parameter_items, "-p");
  const OptionSet options = parse_option_assignments(a.option_items, "--option");
  if (is_fit_file_argument(a.input)) return surface::material_spec(a.input, a.fit, "", parameters, options);
  return surface::material_spec("", a.fit, a.input, parameters, options);
}

void print_statistics(std::FILE* report, const surface::HeightField& f, const surface::TextureStatistics& s) {
  fmt::print(report, "surface {}: {} x {} cells of {} mm (periodic {:.4g} x {:.4g} mm)\n", f.name, f.nx, f.ny,
             f.cell_size_mm, f.size_x_mm(), f.size_y_mm());
  fmt::print(report,
             "MPD {:.3f} mm (ISO 13473-1 style, baseline = sample period), ETD {:.3f} mm, rms height {:.3f} mm, "
             "area ratio {:.3f}\n",
             s.mpd_mm, s.etd_mm, s.rms_height_mm, s.surface_area_ratio);
  fmt::print(report, "{:<40} {:>12} {:>12}\n", "material", "area frac.", "true area");
  for (std::size_t k = 0; k < f.materials.size(); ++k) {
    fmt::print(report, "{:<40} {:>12.4f} {:>12.4f}\n", f.materials[k].name, s.exposed_area_fraction[k],
               s.exposed_true_area_fraction[k]);
  }
}

void run_surface(const SurfaceArgs& a) {
  if (a.output.empty()) throw InputError("give the output file with -o SURFACE.json");
  if (a.flat && a.gaussian_slopes) throw InputError("--flat and --gaussian-slopes exclude each other");
  std::vector<FileArgument> inputs = {{"INPUT", a.input}};
  const std::vector<FileArgument> outputs = {{"-o", a.output}, {"--preview", a.preview}};
  check_distinct_files(inputs, outputs);
  std::FILE* report = report_stream(a.output);
  // The flags translated into the library's request (surface/surface_request.h owns the rules).
  surface::SurfaceRequest request;
  using Kind = surface::SurfaceRequest::Kind;
  request.kind = a.flat ? Kind::flat : a.gaussian_slopes ? Kind::gaussian_slopes : Kind::formulation;
  request.cell_mm = a.cell;
  request.seed = a.seed;
  // A size given for a validation surface is refused by validate(), whatever its text.
  if (!a.size.empty()) request.size_mm = request.kind == Kind::formulation ? parse_length_mm(a.size, "size_mm") : 0.0;
  request.matrix_level = a.matrix_level;
  request.target_mpd = a.target_mpd;
  request.mastic_fraction = a.mastic_fraction;
  if (a.cells > 0) request.cells = a.cells;
  request.sigma_rad = a.gaussian_slopes;
  request.validate();
  surface::HeightField field;
  if (a.flat || a.gaussian_slopes) {
    const surface::MaterialSpec m = material_from_argument(a);
    const int n = request.cell_count();
    if (a.flat) {
      field = surface::make_flat(m, n, a.cell);
    } else {
      field = surface::make_gaussian_slope_surface(m, *a.gaussian_slopes, n, a.cell, a.seed);
    }
  } else {
    if (!a.parameter_items.empty() || !a.option_items.empty() || !a.fit.empty()) {
      throw InputError("-p/--option/--fit are for --flat and --gaussian-slopes surfaces");
    }
    // Fit files are needed only to render: they may not exist yet (warned below).
    const roadbrdf::Formulation formulation = roadbrdf::read_formulation(a.input, false);
    const std::vector<FileArgument> fits = roadbrdf::formulation_input_files(formulation);
    inputs.insert(inputs.end(), fits.begin(), fits.end());
    check_distinct_files(inputs, outputs);
    const surface::SampleRecipe recipe = surface::recipe_from_formulation(formulation);
    surface::GeneratorSettings s = request.generator_settings();
    ProgressBar bar("surface: packing grains", stderr, ProgressBar::stderr_style(a.quiet));
    s.progress = bar.callback();
    const surface::GeneratedSample sample = surface::generate_sample(recipe, s);
    bar.finish();
    field = sample.field;
    for (const auto& note : sample.notes) fmt::print(stderr, "roadbrdf: note: {}\n", note);
    for (const auto& m : field.materials) {
      if (!m.fit_path.empty() && !std::filesystem::exists(m.fit_path)) {
        fmt::print(stderr, "roadbrdf: warning: fit file of '{}' does not exist yet: {} (needed by render)\n", m.name,
                   m.fit_path);
      }
    }
    fmt::print(report, "{}\n", field.description);
    if (a.mastic_fraction) {
      fmt::print(report, "exposed mastic fraction {:.4f} (requested {}, tolerance {:.4g}) at mastic level {:.4f} mm\n",
                 sample.mastic_fraction, *a.mastic_fraction, sample.mastic_fraction_tolerance, sample.matrix_level_mm);
    }
  }
  const surface::TextureStatistics stats = surface::texture_statistics(field);
  surface::write_surface(field, a.output, &stats);
  print_statistics(report, field, stats);
  if (!a.preview.empty()) {
    surface::write_preview_png(field, a.preview);
    fmt::print(report, "wrote {}\n", a.preview);
  }
  fmt::print(report, "wrote {}\n", a.output);
}

struct RenderArgs {
  surface::RenderRequest request;
  bool quiet = false;
};

void run_render_albedo(const RenderArgs& a, const surface::HeightField& field);

void run_render(const RenderArgs& a) {
  const surface::RenderRequest& r = a.request;
  if (r.output.empty()) throw InputError("give the output file with -o DATA.csv");
  surface::RenderSettings s = surface::render_settings(r);  // validated before any file is read
  const DatasetFormat format = parse_name<DatasetFormat>(r.format, "format");
  if (r.grid.empty() == r.sun_zenith.empty()) throw InputError("give either --grid GRID.csv or --albedo ZENITHS");
  std::vector<FileArgument> inputs, outputs;
  file_arguments(r, surface::RenderRequest::fields(), inputs, outputs);
  check_distinct_files(inputs, outputs);
  const surface::HeightField field = surface::read_surface(r.surface);
  for (const auto& m : field.materials) inputs.push_back({"fit of material '" + m.name + "'", m.fit_path});
  check_distinct_files(inputs, outputs);
  if (!r.sun_zenith.empty()) return run_render_albedo(a, field);
  const GeometryTable grid = read_geometry_file(r.grid);
  const std::vector<double> wavelengths = surface::render_wavelengths(r, field);
  ProgressBar bar("render: blocks of paths", stderr, ProgressBar::stderr_style(a.quiet));
  s.progress = bar.callback();
  std::vector<surface::Estimate> estimates;
  SpectralDataset data = surface::render_dataset(field, grid.geometries, wavelengths, s, &estimates);
  bar.finish();
  std::FILE* report = report_stream(r.output);
  data.convention = grid.convention;
  write_dataset(data, r.output, format);
  long total_paths = 0;
  std::vector<double> worst;
  for (const auto& e : estimates) {
    total_paths += e.paths;
    worst.push_back(e.worst_relative_error());
  }
  std::sort(worst.begin(), worst.end());
  auto quantile = [&](double q) {
    return worst[static_cast<std::size_t>(std::lround(q * static_cast<double>(worst.size() - 1)))];
  };
  fmt::print(report, "rendered {}: {} geometries x {} wavelengths, {} sampling, acceptance {} deg, {} paths in total\n",
             r.surface, data.geometry_count(), data.wavelength_count(), r.sampling, r.acceptance_deg, total_paths);
  fmt::print(report,
             "per-geometry worst relative standard error over wavelengths: median {:.3g}, 90th percentile {:.3g}, "
             "max {:.3g}\n",
             quantile(0.5), quantile(0.9), worst.back());
  if (r.target_error) {
    fmt::print(report, "adaptive: target {} (or {} sr^-1 for values near 0), paths per geometry {}\n", *r.target_error,
               r.error_floor, data.metadata["paths_per_geometry"]);
    std::size_t missed = 0;
    for (std::size_t g = 0; g < estimates.size(); ++g) {
      if (estimates[g].converged) continue;
      ++missed;
      const Geometry& gg = grid.geometries[g];
      fmt::print(stderr,
                 "roadbrdf: warning: geometry {} ({:g},{:g},{:g},{:g} deg) reached --max-samples {} with relative "
                 "standard error {:.3g} > target {}\n",
                 g + 1, rad_to_deg(gg.theta_i), rad_to_deg(gg.phi_i), rad_to_deg(gg.theta_r), rad_to_deg(gg.phi_r),
                 r.max_samples, estimates[g].worst_relative_error(), *r.target_error);
    }
    if (missed > 0)
      fmt::print(stderr, "roadbrdf: warning: {} of {} geometries did not reach the target\n", missed, estimates.size());
  }
  fmt::print(report, "wrote {}\n", r.output);
}

// Black-sky (and white-sky) albedo of the virtual sample, written like `roadbrdf albedo`'s CSV
// (columns wavelength_nm, white_sky, white_sky_error, black_sky_<Z>deg, black_sky_error_<Z>deg, ...),
// with Monte Carlo standard errors instead of quadrature error estimates.
void run_render_albedo(const RenderArgs& a, const surface::HeightField& field) {
  const surface::RenderRequest& r = a.request;
  std::FILE* report = report_stream(r.output);
  const std::vector<double> wavelengths = surface::render_wavelengths(r, field);
  surface::RenderSettings settings = surface::render_settings(r);
  ProgressBar bar("render: albedo estimates", stderr, ProgressBar::stderr_style(a.quiet));
  settings.progress = bar.callback();
  const surface::VirtualAlbedo v =
      surface::render_albedo(field, r.sun_zenith, wavelengths, settings, r.white_sky_nodes);
  bar.finish();
  surface::write_virtual_albedo(r.output, v, r.surface);
  std::size_t missed = 0;
  for (bool c : v.converged) missed += c ? 0 : 1;
  fmt::print(report, "rendered the albedo of {}: {} sun zenith angles{}, {} wavelengths, {} paths in total\n",
             r.surface, r.sun_zenith.size(),
             v.white_sky_nodes > 0 ? fmt::format(" + white-sky ({} nodes)", v.white_sky_nodes) : "", wavelengths.size(),
             v.paths);
  if (missed > 0) {
    fmt::print(stderr, "roadbrdf: warning: {} albedo estimates reached --max-samples before the target error\n",
               missed);
  }
  fmt::print(report, "wrote {}\n", r.output);
}

}  // namespace

void register_surface_command(CLI::App& app) {
  static SurfaceArgs args;
  auto* c = app.add_subcommand(
      "surface",
      "Build a virtual road sample (periodic height field + material map) from a formulation, or a validation "
      "surface (--flat, --gaussian-slopes) of one material");
  c->add_option("input", args.input,
                "Formulation file (JSON), or with --flat/--gaussian-slopes the material: MODEL (with -p) or FIT.json")
      ->required();
  c->add_option("--size", args.size, "Side of the periodic sample, e.g. 60mm (default 60mm)");
  c->add_option("--cell", args.cell, "Grid spacing [mm], 0.005 to 10 (default 0.1)");
  c->add_option("--seed", args.seed, "Random seed (default 1)");
  c->add_option("--matrix-level", args.matrix_level,
                "Mastic level as a fraction of the slab thickness (largest grain size), 0 to 1, default 0.7");
  c->add_option("--target-mpd", args.target_mpd, "Choose the mastic level so that the MPD is this [mm]");
  c->add_option("--mastic-fraction", args.mastic_fraction,
                "Choose the mastic level so that the exposed (projected) area fraction of the mastic is this, in "
                "(0, 1), within max(0.001, 1/cells); an unreachable value is an error naming the reachable range");
  c->add_option("--preview", args.preview, "Write a PNG of the height map coloured by material");
  c->add_flag("--flat", args.flat, "Flat sample z = 0 of one material (validation)");
  c->add_option("--gaussian-slopes,--vgrooves", args.gaussian_slopes,
                "Isotropic random rough surface of one material with facet slope angle sigma [rad] (validation; "
                "compare with oren-nayar sigma)");
  c->add_option("--cells", args.cells,
                "Cells per side of a validation surface, 2 (32 rough) to 4096 (default 16 flat, 128 rough)");
  add_model_flags(c, args.parameter_items, args.option_items);
  add_fit_flag(c, args.fit);
  c->add_option("-o,--output", args.output, "Output SURFACE.json (format: src/roadbrdf/surface/height_field.h)")
      ->required();
  add_quiet_flag(c, args.quiet);
  c->callback([] { run_surface(args); });

  static RenderArgs rargs;
  auto* r = app.add_subcommand(
      "render",
      "Virtual gonioreflectometer: path-trace a SURFACE at the geometries of a grid; writes a dataset with the Monte "
      "Carlo standard error as sigma");
  add_request_options(r, rargs.request);
  r->get_option("SURFACE")->required();
  r->get_option("--output")->required();
  add_quiet_flag(r, rargs.quiet);
  r->callback([] { run_request<surface::RenderRequest>([] { run_render(rargs); }); });
}

}  // namespace roadbrdf::cli
