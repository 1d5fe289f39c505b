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
  std::string surface;
  std::string grid;
  std::string albedo;       // sun zenith angles [deg] for the black-sky albedo (instead of --grid)
  int white_sky_nodes = 8;  // Gauss-Legendre nodes in cos(theta) for the white-sky albedo (0: none)
  std::string wavelengths;
  std::optional<long> samples;
  std::optional<double> target_error;
  long max_samples = 1L << 20;
  double error_floor = 1e-5;
  std::string sampling = "brdf";
  double acceptance = 1.0;
  std::uint64_t seed = 1;
  int threads = 0;
  int max_bounces = 0;
  std::string format = "wide";
  std::string output;
  bool quiet = false;
};

surface::RenderSettings render_settings(const RenderArgs& a);
void run_render_albedo(const RenderArgs& a, const surface::HeightField& field);

void run_render(const RenderArgs& a) {
  if (a.output.empty()) throw InputError("give the output file with -o DATA.csv");
  const surface::RenderSettings settings = render_settings(a);  // validated before any file is read
  (void)settings;
  const DatasetFormat format = parse_name<DatasetFormat>(a.format, "format");
  if (a.grid.empty() == a.albedo.empty()) throw InputError("give either --grid GRID.csv or --albedo ZENITHS");
  std::vector<FileArgument> inputs = {{"SURFACE", a.surface}, {"--grid", a.grid}};
  check_distinct_files(inputs, {{"-o", a.output}});
  const surface::HeightField field = surface::read_surface(a.surface);
  for (const auto& m : field.materials) inputs.push_back({"fit of material '" + m.name + "'", m.fit_path});
  check_distinct_files(inputs, {{"-o", a.output}});
  if (!a.albedo.empty()) return run_render_albedo(a, field);
  const GeometryTable grid = read_geometry_file(a.grid);
  const std::vector<double> wavelengths = a.wavelengths.empty()
                                              ? surface::default_wavelengths(field)
                                              : parse_range_list(a.wavelengths, "--wavelengths", wavelength_rules());
  surface::RenderSettings s = render_settings(a);
  ProgressBar bar("render: blocks of paths", stderr, ProgressBar::stderr_style(a.quiet));
  s.progress = bar.callback();
  std::vector<surface::Estimate> estimates;
  SpectralDataset data = surface::render_dataset(field, grid.geometries, wavelengths, s, &estimates);
  bar.finish();
  std::FILE* report = report_stream(a.output);
  data.convention = grid.convention;
  write_dataset(data, a.output, format);
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
             a.surface, data.geometry_count(), data.wavelength_count(), a.sampling, a.acceptance, total_paths);
  fmt::print(report,
             "per-geometry worst relative standard error over wavelengths: median {:.3g}, 90th percentile {:.3g}, "
             "max {:.3g}\n",
             quantile(0.5), quantile(0.9), worst.back());
  if (a.target_error) {
    fmt::print(report, "adaptive: target {} (or {} sr^-1 for values near 0), paths per geometry {}\n", *a.target_error,
               a.error_floor, data.metadata["paths_per_geometry"]);
    std::size_t missed = 0;
    for (std::size_t g = 0; g < estimates.size(); ++g) {
      if (estimates[g].converged) continue;
      ++missed;
      const Geometry& gg = grid.geometries[g];
      fmt::print(stderr,
                 "roadbrdf: warning: geometry {} ({:g},{:g},{:g},{:g} deg) reached --max-samples {} with relative "
                 "standard error {:.3g} > target {}\n",
                 g + 1, rad_to_deg(gg.theta_i), rad_to_deg(gg.phi_i), rad_to_deg(gg.theta_r), rad_to_deg(gg.phi_r),
                 a.max_samples, estimates[g].worst_relative_error(), *a.target_error);
    }
    if (missed > 0)
      fmt::print(stderr, "roadbrdf: warning: {} of {} geometries did not reach the target\n", missed, estimates.size());
  }
  fmt::print(report, "wrote {}\n", a.output);
}

surface::RenderSettings render_settings(const RenderArgs& a) {
  surface::RenderRequest r;
  r.samples = a.samples;
  r.target_error = a.target_error;
  r.max_samples = a.max_samples;
  r.error_floor = a.error_floor;
  r.acceptance_deg = a.acceptance;
  r.sampling = a.sampling;
  r.seed = a.seed;
  r.threads = a.threads;
  r.max_bounces = a.max_bounces;
  r.white_sky_nodes = a.white_sky_nodes;
  return surface::render_settings(r);
}

// Black-sky (and white-sky) albedo of the virtual sample, written like `roadbrdf albedo`'s CSV
// (columns wavelength_nm, white_sky, white_sky_error, black_sky_<Z>deg, black_sky_error_<Z>deg, ...),
// with Monte Carlo standard errors instead of quadrature error estimates.
void run_render_albedo(const RenderArgs& a, const surface::HeightField& field) {
  std::FILE* report = report_stream(a.output);
  const std::vector<double> zeniths = parse_range_list(a.albedo, "--albedo");
  const std::vector<double> wavelengths = a.wavelengths.empty()
                                              ? surface::default_wavelengths(field)
                                              : parse_range_list(a.wavelengths, "--wavelengths", wavelength_rules());
  surface::RenderSettings settings = render_settings(a);
  ProgressBar bar("render: albedo estimates", stderr, ProgressBar::stderr_style(a.quiet));
  settings.progress = bar.callback();
  const surface::VirtualAlbedo r = surface::render_albedo(field, zeniths, wavelengths, settings, a.white_sky_nodes);
  bar.finish();
  surface::write_virtual_albedo(a.output, r, a.surface);
  std::size_t missed = 0;
  for (bool c : r.converged) missed += c ? 0 : 1;
  fmt::print(report, "rendered the albedo of {}: {} sun zenith angles{}, {} wavelengths, {} paths in total\n",
             a.surface, zeniths.size(),
             r.white_sky_nodes > 0 ? fmt::format(" + white-sky ({} nodes)", r.white_sky_nodes) : "", wavelengths.size(),
             r.paths);
  if (missed > 0) {
    fmt::print(stderr, "roadbrdf: warning: {} albedo estimates reached --max-samples before the target error\n",
               missed);
  }
  fmt::print(report, "wrote {}\n", a.output);
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
  r->add_option("surface", rargs.surface, "SURFACE.json written by `roadbrdf surface`")->required();
  r->add_option("--grid", rargs.grid, "Geometry table (CSV, theta_i,phi_i,theta_r,phi_r or gamma,alpha,beta,delta)");
  r->add_option("--albedo", rargs.albedo,
                "Instead of --grid: black-sky albedo at these sun zenith angles [deg] (D, D1,D2,... or A:B:STEP) and "
                "the white-sky albedo; writes an albedo CSV like `roadbrdf albedo`");
  r->add_option("--white-sky-nodes", rargs.white_sky_nodes,
                "With --albedo: Gauss-Legendre nodes in cos(theta) for the white-sky albedo (default 8; 0 = none)");
  r->add_option("--wavelengths", rargs.wavelengths,
                "Wavelengths START:STOP:STEP [nm] (default: those of the materials' fits, or 550)");
  r->add_option("--samples", rargs.samples,
                "Paths per geometry, 2 to 2^30 (default 4096 when --target-error is not given)");
  r->add_option("--target-error", rargs.target_error,
                "Adaptive sampling: add paths until every wavelength's standard error is <= this fraction of |BRDF| "
                "(e.g. 0.01), at least 1024 paths");
  r->add_option("--max-samples", rargs.max_samples,
                "Adaptive sampling: at most this many paths per geometry (default 1048576); geometries stopped here "
                "are reported");
  r->add_option("--error-floor", rargs.error_floor,
                "Adaptive sampling: absolute standard error [sr^-1] accepted for BRDF values near 0 (default 1e-5)");
  r->add_option("--sampling", rargs.sampling,
                "Continuation directions: " + described_names_text<surface::Sampling>() + " (default brdf)");
  r->add_option("--acceptance", rargs.acceptance, "Detector acceptance half-angle [deg] (1 or 5 typical; default 1)");
  r->add_option("--seed", rargs.seed, "Random seed (default 1); each geometry has its own streams");
  r->add_option("--threads", rargs.threads, "Threads (default: all cores)");
  r->add_option("--max-bounces", rargs.max_bounces, "Limit the number of surface interactions (0 = unlimited)");
  r->add_option("--format", rargs.format, "Output CSV layout: " + names_text<DatasetFormat>() + " (default wide)");
  r->add_option("-o,--output", rargs.output, "Output dataset (CSV), or with --albedo the albedo table (CSV)")
      ->required();
  add_quiet_flag(r, rargs.quiet);
  r->callback([] { run_render(rargs); });
}

}  // namespace roadbrdf::cli
