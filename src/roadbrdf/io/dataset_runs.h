// Laboratory tables as they come: the dataset-reading fields every command and Python offer (one
// RequestField table, core/request_fields.h), and several runs of one sample (repeat scans, one file
// per illumination zenith) combined into one dataset.
//
// The per-file grammar of `columns` and `set`: an item is FIELD=VALUE for every input file, or
// FILE:FIELD=VALUE for the input named FILE (as given, or by its file name alone), e.g.
//   columns  theta_r=True_Average_View_Zenith   (the header name holding theta_r)
//   set      theta_i=30   north.csv:phi_i=0     (an angle the file has no column for, in degrees)
// An item for one file overrides the same field's item for every file.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/dataset_io.h"

namespace roadbrdf {

// The dataset-reading request fields (see DatasetReadOptions for their meaning).
struct DatasetReadFields {
  std::string delimiter = "auto";
  std::string decimal = "auto";
  bool average_duplicates = false;
  std::string quantity = "brdf";
  std::vector<std::string> columns;  // [FILE:]FIELD=HEADER_NAME
  std::vector<std::string> set;      // [FILE:]ANGLE=DEGREES

  static RequestFields<DatasetReadFields> fields();
  // The options for reading `file`, one of `files` (the inputs the FILE: prefixes may name), validated.
  // Throws FieldError naming the field.
  DatasetReadOptions options_for(const std::string& file, const std::vector<std::string>& files = {}) const;
};

// The dataset field names `columns` may map, and the angles `set` may fix.
const std::vector<std::string>& mappable_dataset_fields();

// One file's dataset in a combination.
struct DatasetRun {
  std::string path;
  SpectralDataset data;
};

// Several runs as one dataset: the same wavelengths in every run (else InputError), the geometries in
// order of first appearance. A geometry in several runs is an error naming both runs, or (with
// `average_duplicates`) averaged like duplicate rows of one file: the mean of the runs' values and
// sigma = sqrt(sum sigma^2)/n, each run weighing one (a run's own duplicates are averaged first);
// the repeatability of the combination goes to `repeatability`. Metadata: the first run's; a key
// another run gives a different value is reported through `warn` with both values, and `runs` lists
// the files (when there are several). One run alone is checked for repeated geometries the same way
// (a dataset made in memory).
SpectralDataset combine_runs(const std::vector<DatasetRun>& runs, bool average_duplicates,
                             const std::function<void(const std::string&)>& warn,
                             Repeatability* repeatability = nullptr);

// Read each file with its options (DatasetReadFields::options_for; `allow_missing` as in
// DatasetReadOptions) and combine them (combine_runs).
SpectralDataset read_dataset_runs(const std::vector<std::string>& paths, const DatasetReadFields& fields,
                                  const std::function<void(const std::string&)>& warn = {}, bool allow_missing = true);

}  // namespace roadbrdf
