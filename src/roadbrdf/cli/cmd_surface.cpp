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

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/io/geometry_file.h"
#include "roadbrdf/surface/render_request.h"
#include "roadbrdf/surface/render_task.h"
#include "roadbrdf/surface/surface_request.h"
#include "roadbrdf/surface/surface_task.h"

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

void run_render(const RenderArgs& a) {
  const surface::RenderRequest& r = a.request;
  surface::render_settings(r);  // validated before any file is read
  if (r.grid.empty() == r.sun_zenith.empty()) throw InputError("give either --grid GRID.csv or --albedo ZENITHS");
  check_request_files(r);
  const surface::HeightField field = surface::read_surface(r.surface);
  std::string summary;
  if (!r.sun_zenith.empty()) {
    ProgressBar bar("render: albedo estimates", stderr, ProgressBar::stderr_style(a.quiet));
    const surface::RenderAlbedoResult result = surface::render_surface_albedo(field, r.surface, r, bar.callback());
    bar.finish();
    print_diagnostics<surface::RenderRequest>(result.diagnostics);
    summary = result.summary_text();
  } else {
    const GeometryTable grid = read_geometry_file(r.grid);
    ProgressBar bar("render: blocks of paths", stderr, ProgressBar::stderr_style(a.quiet));
    const surface::RenderResult result =
        surface::render_grid(field, r.surface, grid.geometries, grid.convention, r, bar.callback());
    bar.finish();
    print_diagnostics<surface::RenderRequest>(result.diagnostics);
    summary = result.summary_text();
  }
  fmt::print(report_stream(r.output), "{}", summary);
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
