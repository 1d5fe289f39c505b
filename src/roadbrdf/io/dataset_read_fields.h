// The dataset-reading options as request fields, one group for every request that reads a dataset
// file: the request derives from DatasetReadFields and appends dataset_read_fields<Request>() to its
// table, so the command line's --delimiter, --decimal, --average-duplicates and Python's keywords
// of the same names are declared here once.
#pragma once

#include <string>
#include <vector>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/io/dataset_dialect.h"
#include "roadbrdf/io/dataset_io.h"

namespace roadbrdf {

struct DatasetReadFields {
  std::string delimiter = "auto";  // io/dataset_dialect.h names: auto, ',', ';', tab
  std::string decimal = "auto";    // auto, '.', ','
  bool average_duplicates = false;

  // The reader's options, validated. Throws FieldError naming `delimiter` or `decimal`.
  DatasetReadOptions read_options() const {
    DatasetReadOptions options;
    options.delimiter = delimiter_from_name(delimiter, "delimiter");
    options.decimal = decimal_from_name(decimal, "decimal");
    options.average_duplicates = average_duplicates;
    validate_read_options(options);
    return options;
  }
};

// The rows of DatasetReadFields in the table of a Request derived from it.
template <class Request>
std::vector<RequestField<Request>> dataset_read_fields() {
  using Text = std::string Request::*;
  return {
      {"delimiter", "--delimiter", "", "Dataset cell delimiter: auto (from the header line), ',', ';' or tab",
       static_cast<Text>(&DatasetReadFields::delimiter)},
      {"decimal", "--decimal", "", "Dataset decimal separator: auto (from the numbers), '.' or ',' (with ';' or tab)",
       static_cast<Text>(&DatasetReadFields::decimal)},
      {"average_duplicates", "--average-duplicates", "", "Average dataset rows with the same geometry (else an error)",
       static_cast<bool Request::*>(&DatasetReadFields::average_duplicates)},
  };
}

}  // namespace roadbrdf
