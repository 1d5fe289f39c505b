// The dataset-reading options as request fields, one group for every request that reads a dataset
// file: the request derives from DatasetReadFields (io/dataset_runs.h, whose one table declares the
// fields) and appends dataset_read_fields<Request>() to its own table, so the command line's
// --delimiter, --decimal, --average-duplicates, --quantity, --column, --set and Python's keywords of
// the same names are declared once. The reader's options are DatasetReadFields::options_for(file).
#pragma once

#include <variant>
#include <vector>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/io/dataset_runs.h"

namespace roadbrdf {

// The rows of DatasetReadFields::fields() in the table of a Request derived from DatasetReadFields:
// the same rows, each member pointer converted to one of Request (a base's member is the derived's).
template <class Request>
std::vector<RequestField<Request>> dataset_read_fields() {
  std::vector<RequestField<Request>> rows;
  for (const RequestField<DatasetReadFields>& f : DatasetReadFields::fields()) {
    const FieldMember<Request> member = std::visit([](auto m) -> FieldMember<Request> { return m; }, f.member);
    rows.push_back({f.name, f.flag, f.unit, f.help, member, f.file, f.required, f.comma_separated});
  }
  return rows;
}

}  // namespace roadbrdf
