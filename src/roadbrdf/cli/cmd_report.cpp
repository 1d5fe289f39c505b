// roadbrdf report DATA.csv [--model M ...] [--formulation F.json] -o REPORT.html: the report of one
// sample as a self-contained HTML page, made by the Python package's roadbrdf.report module
// (docs/report.md) with Debian's interpreter (override with $ROADBRDF_PYTHON).
#include <cstdlib>
#include <string>
#include <vector>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/python_module.h"

namespace roadbrdf::cli {

namespace {

void run(const std::vector<std::string>& arguments) {
  if (std::getenv("MPLBACKEND") == nullptr) setenv("MPLBACKEND", "Agg", 1);
  exec_python_module("roadbrdf.report", arguments, "the report", "numpy, pandas and matplotlib");
}

}  // namespace

void register_report_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "report",
      "The report of one sample: report DATA.csv [--model M ...] [--formulation F.json] -o REPORT.html, one "
      "self-contained HTML page (provenance, quality check, coverage, figures, per-incidence fits, model ranking, "
      "albedo, r-table, mixing; see `roadbrdf report --help`)");
  command->prefix_command();
  command->set_help_flag();  // --help goes to the Python module
  command->callback([command] {
    std::vector<std::string> remaining = command->remaining();
    if (remaining.empty()) remaining.push_back("--help");
    run(remaining);
  });
}

}  // namespace roadbrdf::cli
