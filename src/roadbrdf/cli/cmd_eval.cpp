// roadbrdf eval MODEL -p NAME=VALUE ... (--theta-i D --phi-i D --theta-r D --phi-r D | --geometry FILE.csv)
#include <fmt/core.h>

#include <iostream>
#include <optional>
#include <sstream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/csv.h"
#include "roadbrdf/io/geometry_file.h"

namespace roadbrdf::cli {

namespace {

struct EvalArgs {
  std::string model;
  std::vector<std::string> parameters;
  std::vector<std::string> options;
  std::optional<double> theta_i, phi_i, theta_r, phi_r;
  std::string geometry_file;
  std::string output;
};

void run(const EvalArgs& a) {
  const ModelWithParameters m = model_from_command_line(a.model, a.parameters, a.options);
  if (!a.geometry_file.empty()) {
    if (a.theta_i || a.phi_i || a.theta_r || a.phi_r) {
      throw InputError("give either --geometry or the four angles, not both");
    }
    check_distinct_files({{"--geometry", a.geometry_file}}, {{"-o", a.output}});
    const GeometryTable table = read_geometry_file(a.geometry_file);
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
  auto* command = app.add_subcommand("eval", "Evaluate a model's BRDF [sr^-1] at one geometry or at every row of a file");
  command->add_option("model", args.model, "Model name, e.g. oren-nayar or lambert+torrance-sparrow")->required();
  add_model_flags(command, args.parameters, args.options);
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
