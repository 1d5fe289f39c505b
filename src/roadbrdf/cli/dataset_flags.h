// The dataset-reading options every command that reads datasets offers, as one set of flags made from
// one table (io/dataset_runs.h DatasetReadFields::fields()): --delimiter, --decimal,
// --average-duplicates, --quantity, --column, --set.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/dataset_runs.h"

namespace roadbrdf::cli {

using DatasetReadFlags = DatasetReadFields;

// `with_quantity` false: the command has a --quantity of its own that it passes on (convert, whose
// instrument files have one too).
void add_dataset_read_flags(CLI::App* command, DatasetReadFlags& flags, bool with_quantity = true);

// The library's options from the flags for reading `file` (one of `files`, which per-file items may
// name), validated; errors spelt with the flags (InputError).
DatasetReadOptions dataset_read_options(const DatasetReadFlags& flags, const std::string& file = {},
                                        const std::vector<std::string>& files = {});

// A library message with the dataset-reading fields spelt as their flags.
std::string with_dataset_flags(const std::string& message);

}  // namespace roadbrdf::cli
