// roadbrdf report DATA.csv [--model M ...] [--formulation F.json] -o REPORT.html: the report of one
// sample as a self-contained HTML page, made by the Python package's roadbrdf.report module
// (docs/report.md) with Debian's interpreter (override with $ROADBRDF_PYTHON).
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/python_module.h"

namespace roadbrdf::cli {

void register_report_command(CLI::App& app) {
  add_python_command(
      app, PythonCommand{"report",
                         "The report of one sample: report DATA.csv [--model M ...] [--formulation F.json] -o "
                         "REPORT.html, one self-contained HTML page (provenance, quality check, coverage, figures, "
                         "per-incidence fits, model ranking, albedo, r-table, mixing; see `roadbrdf report --help`)",
                         "roadbrdf.report", "the report", "numpy, pandas and matplotlib", true});
}

}  // namespace roadbrdf::cli
