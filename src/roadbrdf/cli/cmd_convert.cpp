// roadbrdf convert INPUT... [--from SOURCE] [--to wide|long] -o OUT.csv
// (several dataset CSV files: runs of one sample combined into one dataset, io/dataset_runs.h;
// instrument files, manifests and USGS spectra: io/instrument.h, io/manifest.h, io/usgs.h). Made by
// the request contract (cli/request_options.h; the request's table is ConvertRequest::fields,
// io/convert_request.cpp).
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/io/convert_request.h"

namespace roadbrdf::cli {

void register_convert_command(CLI::App& app) {
  static ConvertRequest request;
  auto* command = app.add_subcommand("convert",
                                     "Convert a dataset between wide/long CSV, and from CUReT, ALTA, instrument (.asd, "
                                     ".sed, .sig), manifest and USGS splib07a files");
  add_request_options(command, request);
  command->callback([] {
    run_request<ConvertRequest>([] { warn_missing_values(convert(with_standard_output(request)), request.output); });
  });
}

}  // namespace roadbrdf::cli
