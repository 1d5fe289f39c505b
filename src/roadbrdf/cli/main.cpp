// roadbrdf command-line program.
#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <string_view>
#include <system_error>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/parse_errors.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"

int main(int argc, char** argv) {
  CLI::App app{
      "roadbrdf: spectral BRDF models, fitting, mixing, albedo and road photometry for road materials.\n"
      "Angles in degrees, BRDF in sr^-1, wavelengths in nm."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "roadbrdf " + roadbrdf::version());
  // Warnings of readers called without a sink of their own (core/diagnostics.h): the library never prints.
  roadbrdf::set_front_end_warning_sink(
      // Library warnings name request fields (`like_this`); the command line names its flags.
      [&app](const std::string& message) {
        fmt::print(stderr, "roadbrdf: warning: {}\n", roadbrdf::cli::name_flags(app, message));
      });
  roadbrdf::cli::register_models_command(app);
  roadbrdf::cli::register_eval_command(app);
  roadbrdf::cli::register_rtable_command(app);
  roadbrdf::cli::register_fit_command(app);
  roadbrdf::cli::register_params_command(app);
  roadbrdf::cli::register_simulate_command(app);
  roadbrdf::cli::register_check_command(app);
  roadbrdf::cli::register_resample_command(app);
  roadbrdf::cli::register_calibrate_command(app);
  roadbrdf::cli::register_convert_command(app);
  roadbrdf::cli::register_mix_command(app);
  roadbrdf::cli::register_mix_calibrate_command(app);
  roadbrdf::cli::register_surface_command(app);
  roadbrdf::cli::register_albedo_command(app);
  roadbrdf::cli::register_plot_command(app);
  roadbrdf::cli::register_study_command(app);
  roadbrdf::cli::register_report_command(app);
  roadbrdf::cli::register_marking_command(app);
  roadbrdf::cli::register_export_command(app);
  roadbrdf::cli::register_luminaire_command(app);
  roadbrdf::cli::register_lighting_command(app);
  // [command-registrations]
  int status = 0;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {
      status = app.exit(e);  // --help, --version
    } else {
      fmt::print(stderr, "roadbrdf: error: {}\n", roadbrdf::cli::explain_parse_error(app, argc, argv, e));
      status = 2;
    }
  } catch (const roadbrdf::FieldError& e) {
    // Library requests name their fields; the command line names its flags, as the tables the
    // running command was made from spell them (cli/common.h flag_for_field).
    fmt::print(stderr, "roadbrdf: error: {}: {}\n", roadbrdf::cli::flag_for_field(app, e.field()),
               roadbrdf::cli::name_flags(app, e.detail()));
    status = 2;
  } catch (const roadbrdf::InputError& e) {
    fmt::print(stderr, "roadbrdf: error: {}\n", roadbrdf::cli::name_flags(app, e.what()));
    status = 2;
  } catch (const std::system_error& e) {
    // fmt::print reports a failed write to standard output this way (e.g. a full disk).
    if (std::string_view(e.what()).rfind("cannot write to file", 0) == 0) {
      fmt::print(stderr, "roadbrdf: error: {}: write failed: {}\n", roadbrdf::kStandardOutputName, e.code().message());
      status = 2;
    } else {
      fmt::print(stderr, "roadbrdf: internal error: {}\n", e.what());
      status = 3;
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "roadbrdf: internal error: {}\n", e.what());
    status = 3;
  }
  // Whatever was printed must have reached standard output (e.g. not a full disk): check the
  // final flush and close, as the last thing the program does.
  try {
    roadbrdf::flush_standard_output();
    if (std::fclose(stdout) != 0) {
      throw roadbrdf::FileError(roadbrdf::kStandardOutputName, 0, 0,
                                std::string("close failed: ") + std::strerror(errno));
    }
  } catch (const roadbrdf::InputError& e) {
    fmt::print(stderr, "roadbrdf: error: {}\n", e.what());
    if (status == 0) status = 2;
  }
  return status;
}
