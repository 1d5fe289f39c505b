// The options of the instrument readers that every request reading instrument files shares (the
// manifests of `calibrate`, the instrument inputs of `convert`), as one table of request fields
// (core/request_fields.h): a request derives from InstrumentOptions and appends
// instrument_fields<Request>() to its own table, so the command line's --overlap and Python's
// `overlap` keyword are declared once.
#pragma once

#include <string>
#include <vector>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/io/manifest.h"

namespace roadbrdf {

struct InstrumentOptions {
  // SVC .sig detector overlap: a name of OverlapRule (io/instrument.h).
  std::string overlap = "upper";

  static RequestFields<InstrumentOptions> fields();
  // The readers' options, validated (FieldError naming `overlap`); warnings go to the front end's
  // sink (core/diagnostics.h route_warning).
  ManifestOptions manifest_options() const;
};

// The rows of InstrumentOptions::fields() in the table of a Request derived from InstrumentOptions.
template <class Request>
std::vector<RequestField<Request>> instrument_fields() {
  return fields_of_base<Request, InstrumentOptions>();
}

}  // namespace roadbrdf
