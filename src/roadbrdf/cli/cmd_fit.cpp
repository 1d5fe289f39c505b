// roadbrdf fit DATA.csv --model M [--model M2 ...] [...] -o FIT.json
// Fits each model to every wavelength of a measured spectral BRDF (fitting/fit_request.h), prints a
// ranking table and writes the fit file (fitting/fit_file.h), which every command accepts as a model.
// The options are FitRequest's table (cli/request_options.h).
#include <fmt/core.h>

#include <cstdio>
#include <memory>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/core/progress.h"
#include "roadbrdf/fitting/fit_request.h"

namespace roadbrdf::cli {

namespace {

void run(const FitRequest& request, bool quiet) {
  request.validate();  // before reading the data: a misspelt name fails at once
  check_request_files(request);
  const SpectralDataset data = read_fit_data(request);
  // One bar per model; the models are fitted one after the other, so a new bar ends the previous one.
  // core/progress.h: on standard error, a bar on a terminal, a heartbeat line in a log; none with --quiet.
  std::unique_ptr<ProgressBar> bar;
  const ProgressStyle show = ProgressBar::stderr_style(quiet);
  const FitSummary summary = run_fit(request, data, [&bar, show](const std::string& label) {
    bar.reset();  // ends the previous model's line
    bar = std::make_unique<ProgressBar>(label, stderr, show);
    return [current = bar.get()](std::size_t done, std::size_t total) { current->update(done, total); };
  });
  bar.reset();
  std::FILE* report = report_stream(request.output);
  for (const auto& note : summary.notes) fmt::print(stderr, "roadbrdf: note: {}\n", with_flags<FitRequest>(note));
  fmt::print(report, "{}", summary.table());
  for (const auto& w : summary.warnings(request.output)) {
    fmt::print(stderr, "roadbrdf: warning: {}\n", with_flags<FitRequest>(w));
  }
  write_fit_outputs(request, summary, data);
}

}  // namespace

void register_fit_command(CLI::App& app) {
  static FitRequest request;
  static bool quiet = false;
  auto* c = app.add_subcommand(
      "fit",
      "Fit models to a measured spectral BRDF (per wavelength, or jointly with --shared); rank them by BIC; "
      "write a fit file usable as a model");
  add_request_options(c, request);
  // Python may give the dataset as values and need not write a file; the command reads and writes one.
  c->get_option("DATA")->required();
  c->get_option("--output")->required();
  add_quiet_flag(c, quiet);
  c->callback([] { run_request<FitRequest>([] { run(request, quiet); }); });
}

}  // namespace roadbrdf::cli
