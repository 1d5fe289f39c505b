// roadbrdf eval (MODEL -p NAME=VALUE ... | FIT.json | MIX.json [--fit NAME] [--wavelength NM])
//   (--theta-i D --phi-i D --theta-r D --phi-r D | --geometry FILE.csv)
#include <fmt/core.h>

#include <iostream>
#include <optional>
#include <sstream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/io/geometry_file.h"

namespace roadbrdf::cli {

namespace {

struct EvalArgs {
  std::string model;
  std::vector<std::string> parameters;
  std::vector<std::string> options;
  std::optional<double> theta_i, phi_i, theta_r, phi_r;
  std::string fit_model;
  std::optional<double> wavelength;
  std::string geometry_file;
  std::string output;
};

// The parameter set to evaluate: a model's constant parameters, or a fit/MIX file's at one
// wavelength (its only band when it has one, else --wavelength).
std::vector<double> parameters_to_evaluate(const SpectralModel& sm, const EvalArgs& a) {
  if (!sm.is_spectral()) {
    if (a.wavelength) throw InputError("--wavelength needs a fit file or a MIX.json: MODEL -p ... has no spectrum");
    return sm.parameter_table();
  }
  const auto& wl = sm.wavelengths();
  if (!a.wavelength && wl.size() > 1) {
    throw InputError(fmt::format("{} holds {} wavelengths ({:g}-{:g} nm): choose one with --wavelength NM", a.model,
                                 wl.size(), wl.front(), wl.back()));
  }
  return sm.parameters_at(a.wavelength.value_or(wl.front()));
}

void run(const EvalArgs& a) {
  check_distinct_files({{"MODEL", a.model}, {"--geometry", a.geometry_file}}, {{"-o", a.output}});
  if (!a.fit_model.empty() && !is_fit_file_argument(a.model)) throw InputError("--fit needs a fit file or a MIX.json");
  const SpectralModel sm = spectral_model_from_command_line(a.model, a.parameters, a.options, a.fit_model);
  struct {
    const Model* model;
    std::vector<double> parameters;
  } m{&sm.model(), parameters_to_evaluate(sm, a)};
  if (!a.geometry_file.empty()) {
    if (a.theta_i || a.phi_i || a.theta_r || a.phi_r) {
      throw InputError("give either --geometry or the four angles, not both");
    }
    const GeometryTable table = read_geometry_file(a.geometry_file);
    for (const auto& name : table.header) {
      if (name == "brdf") {
        throw FileError(a.geometry_file, 0, 0,
                        "already has a 'brdf' column (an eval output?): a second one would be added");
      }
    }
    std::vector<double> brdf(table.geometries.size());
    m.model->evaluate_batch(table.geometries.data(), table.geometries.size(), m.parameters.data(), 1, brdf.data());
    AtomicFile out(a.output.empty() ? std::string("-") : a.output);
    write_geometry_table_with_column(out.stream(), table, "brdf", brdf);
    out.commit();
    return;
  }
  if (!a.theta_i || !a.phi_i || !a.theta_r || !a.phi_r) {
    throw InputError("give --theta-i, --phi-i, --theta-r and --phi-r (degrees), or --geometry FILE.csv");
  }
  const Geometry g = geometry_from_degrees(*a.theta_i, *a.phi_i, *a.theta_r, *a.phi_r);
  fmt::print("{:.10g}\n", m.model->evaluate(m.parameters.data(), g));
}

}  // namespace

void register_eval_command(CLI::App& app) {
  static EvalArgs args;
  auto* command =
      app.add_subcommand("eval", "Evaluate a model's BRDF [sr^-1] at one geometry or at every row of a file");
  command
      ->add_option("model", args.model,
                   "Model name (e.g. oren-nayar or lambert+torrance-sparrow, with -p), FIT.json or MIX.json")
      ->required();
  add_model_flags(command, args.parameters, args.options);
  add_fit_flag(command, args.fit_model);
  command->add_option("--wavelength", args.wavelength,
                      "Wavelength [nm] at which a fit file is evaluated (needed unless it has a single band)");
  command->add_option("--theta-i", args.theta_i, "Incidence zenith angle [deg]");
  command->add_option("--phi-i", args.phi_i, "Incidence azimuth [deg]");
  command->add_option("--theta-r", args.theta_r, "Reflection (viewing) zenith angle [deg]");
  command->add_option("--phi-r", args.phi_r, "Reflection azimuth [deg]");
  command->add_option("--geometry", args.geometry_file,
                      "CSV with columns theta_i,phi_i,theta_r,phi_r or gamma,alpha,beta,delta [deg]; "
                      "the same table is written with a 'brdf' column added");
  command->add_option("-o,--output", args.output, "Output CSV (default: standard output)");
  command->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
