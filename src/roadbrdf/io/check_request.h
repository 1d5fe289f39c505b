// The quality check as the front ends ask for it (`roadbrdf check`, roadbrdf.check in Python): the
// request with its field table (core/request_fields.h) and the task, which reads the dataset (missing
// values are counted, not an error), runs the checks of io/quality.h and gives one report, as text
// and as JSON, for both front ends.
#pragma once

#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/dataset_runs.h"
#include "roadbrdf/io/quality.h"

namespace roadbrdf {

// The thresholds of the checks (QualityOptions) and the reference panel's reflectance file: the fields
// of a check of a dataset in memory too.
struct CheckOptions : QualityOptions {
  std::string panel_file;  // `panel_reflectance`: the dataset is a panel, compared with rho/pi

  static RequestFields<CheckOptions> fields();
  // The thresholds, validated, with the panel's reflectance read. Throws FieldError / FileError.
  QualityOptions quality_options() const;
};

// A check of a dataset file: its path, the dataset-reading fields and the options.
struct CheckRequest : DatasetReadFields, CheckOptions {
  std::string path;

  static RequestFields<CheckRequest> fields();
};

struct CheckResult {
  std::string file;  // the dataset file as named; empty for a dataset in memory
  SpectralDataset data;
  QualityReport report;

  // quality_report_json with the file (null in memory) and, for an OpenMATERIAL 3D file
  // (io/openmaterial3d.h), the receiver solid angles kept in its metadata.
  nlohmann::json to_json() const;
  // quality_report_text and the receiver solid angles, one line each (without the file's name).
  std::string summary_text() const;
};

// The check of `request.path`, after check_distinct_files over its files; reading warnings go to `warn`
// (default: the front end's sink). Throws FieldError / InputError / FileError.
CheckResult quality_check(const CheckRequest& request, const std::function<void(const std::string&)>& warn = {});
// The same check of a dataset in memory (no reading statistics).
CheckResult quality_check(const SpectralDataset& dataset, const CheckOptions& options);

}  // namespace roadbrdf
