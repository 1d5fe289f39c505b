// roadbrdf resample DATA.csv --wavelengths 400:1000:10 [--drop A:B]... [--drop-noisy] -o OUT.csv
// Made by the request contract (cli/request_options.h; the request's table is ResampleRequest::fields,
// io/resample_request.cpp).
#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/request_options.h"
#include "roadbrdf/io/resample_request.h"

namespace roadbrdf::cli {

void register_resample_command(CLI::App& app) {
  static ResampleRequest request;
  auto* c = app.add_subcommand("resample",
                               "Band-average a dataset onto new wavelength intervals (not point picks); drop bands");
  add_request_options(c, request);
  c->callback([] {
    run_request<ResampleRequest>([] { warn_missing_values(resample(with_standard_output(request)), request.output); });
  });
}

}  // namespace roadbrdf::cli
