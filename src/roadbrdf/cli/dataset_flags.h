// The dataset-reading options every command that reads datasets offers, as one set of flags:
// --delimiter, --decimal, --average-duplicates (io/dataset_io.h DatasetReadOptions).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "roadbrdf/io/dataset_io.h"

namespace roadbrdf::cli {

struct DatasetReadFlags {
  std::string delimiter = "auto";
  std::string decimal = "auto";
  bool average_duplicates = false;
};

void add_dataset_read_flags(CLI::App* command, DatasetReadFlags& flags);

// The library's options from the flags, validated (InputError).
DatasetReadOptions dataset_read_options(const DatasetReadFlags& flags);

}  // namespace roadbrdf::cli
