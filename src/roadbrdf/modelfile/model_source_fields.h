// The source of a BRDF as request fields, one group for every request that takes "MODEL with
// `parameters` and `options`, or FIT.json / MIX.json with `fit`" (the one resolver, model_source.h):
// the request derives from ModelSourceFields and puts model_source_fields<Request>() into its own
// table, so the command line's MODEL, -p/--parameter, --option, --fit and Python's keywords of the
// same names are declared once.
#pragma once

#include <string>
#include <vector>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/modelfile/model_source.h"

namespace roadbrdf {

struct ModelSourceFields {
  std::string model;  // a model name, a FIT.json or a MIX.json (required)
  std::vector<std::string> parameters, options;
  std::string fit;  // the entry of a fit file or a MIX.json ("" = its best)

  static RequestFields<ModelSourceFields> fields();
  // resolve_model over the four fields: FieldError naming one of them, FileError for a bad file.
  ResolvedModel resolve() const { return resolve_model(model, parameters, options, fit); }
};

// The rows of ModelSourceFields::fields() in the table of a Request derived from ModelSourceFields.
template <class Request>
std::vector<RequestField<Request>> model_source_fields() {
  return fields_of_base<Request, ModelSourceFields>();
}

}  // namespace roadbrdf
