// roadbrdf command-line program.
#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/error.h"

int main(int argc, char** argv) {
  CLI::App app{
      "roadbrdf: spectral BRDF models, fitting, mixing, albedo and road photometry for road materials.\n"
      "Angles in degrees, BRDF in sr^-1, wavelengths in nm."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "roadbrdf " + roadbrdf::version());
  roadbrdf::cli::register_models_command(app);
  roadbrdf::cli::register_eval_command(app);
  roadbrdf::cli::register_rtable_command(app);
  roadbrdf::cli::register_fit_command(app);
  roadbrdf::cli::register_simulate_command(app);
  roadbrdf::cli::register_check_command(app);
  roadbrdf::cli::register_resample_command(app);
  roadbrdf::cli::register_calibrate_command(app);
  roadbrdf::cli::register_convert_command(app);
  roadbrdf::cli::register_mix_command(app);
  roadbrdf::cli::register_surface_command(app);
  roadbrdf::cli::register_albedo_command(app);
  roadbrdf::cli::register_plot_command(app);
  // [command-registrations]
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const roadbrdf::InputError& e) {
    fmt::print(stderr, "roadbrdf: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "roadbrdf: internal error: {}\n", e.what());
    return 3;
  }
  return 0;
}
