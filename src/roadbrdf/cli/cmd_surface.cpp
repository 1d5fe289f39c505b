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

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/geometry_file.h"
#include "roadbrdf/surface/render.h"
#include "roadbrdf/surface/render_request.h"
#include "roadbrdf/surface/surface_request.h"
#include "roadbrdf/surface/surface_task.h"
#include "roadbrdf/surface/virtual_albedo.h"

namespace roadbrdf::cli {

namespace {

struct SurfaceArgs {
  surface::SurfaceRequest request;
  bool quiet = false;
};

void run_surface(const SurfaceArgs& a) {
  ProgressBar bar("surface: packing grains", stderr, ProgressBar::stderr_style(a.quiet));
  const surface::SurfaceResult result = surface::make_surface(a.request, bar.callback());
  bar.finish();
  print_diagnostics<surface::SurfaceRequest>(result.diagnostics);
  fmt::print(report_stream(a.request.output), "{}", result.summary_text());
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
  add_request_options(c, args.request);
  c->get_option("--output")->required();
  refuse_fit_model_flag(c);
  add_quiet_flag(c, args.quiet);
  c->callback([] { run_request<surface::SurfaceRequest>([] { run_surface(args); }); });

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
