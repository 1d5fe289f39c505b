// roadbrdf params FIT.json [--wavelengths 600] [--model M ...] [--group-by COLS] [--format table|csv|markdown|latex]
//                 [-o OUT]
// The fitted parameters with standard errors and fit statistics, one row per fit and wavelength
// (fitting/params_table.h): the report's parameter tables, ready to paste.
#include <fmt/core.h>

#include <cstdio>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/fitting/params_table.h"

namespace roadbrdf::cli {

namespace {

struct ParamsArgs {
  std::string fit;
  std::string wavelengths;
  std::vector<std::string> models;
  std::vector<std::string> group_by;
  std::string format = "table";
  std::string output;
};

void run(const ParamsArgs& a) {
  ParamsRequest request;
  request.fit_file = a.fit;
  if (!a.wavelengths.empty()) request.wavelengths = parse_range_list(a.wavelengths, "--wavelengths");
  request.models = a.models;
  request.group_by = split_commas(a.group_by);
  const ParamsFormat format = parse_name<ParamsFormat>(a.format, "format");
  request.validate();
  check_distinct_files({{"FIT", a.fit}}, {{"-o", a.output}});
  const ParamsTable table = read_params_table(request);
  for (const auto& note : table.notes) fmt::print(stderr, "roadbrdf: note: {}\n", note);
  const std::string text = table.render(format);
  if (a.output.empty() || a.output == "-") {
    fmt::print("{}", text);
    return;
  }
  AtomicFile out(a.output);
  out.stream() << text;
  out.commit();
}

}  // namespace

void register_params_command(CLI::App& app) {
  static ParamsArgs args;
  auto* c = app.add_subcommand("params",
                               "Print the fitted parameters of a fit file with standard errors, RMSE, relative "
                               "errors, AIC/BIC and convergence: one row per fit (model, group) and wavelength");
  c->add_option("fit", args.fit, "Fit file (JSON) written by `roadbrdf fit`")->required();
  c->add_option("--wavelengths,--wavelength", args.wavelengths,
                "Wavelengths to show: START:STOP:STEP or a list [nm]; one not fitted is answered by the nearest "
                "fitted band, with a note (default: every fitted wavelength)");
  c->add_option("-m,--model", args.models, "Show only this model's fits (repeatable)")->allow_extra_args(false);
  c->add_option("--group-by", args.group_by,
                "One table per value of these columns (comma-separated: model, wavelength, or a group column of "
                "the fit file such as theta_i), each headed e.g. 'theta_i = 40 deg'; CSV stays one table in that "
                "order")
      ->allow_extra_args(false);
  c->add_option("--format", args.format, "Table format: " + described_names_text<ParamsFormat>())
      ->capture_default_str();
  c->add_option("-o,--output", args.output, "Write the table to this file (atomically; default: standard output)");
  c->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
