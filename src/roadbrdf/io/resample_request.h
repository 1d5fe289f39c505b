// Spectral resampling as the front ends ask for it (`roadbrdf resample`, roadbrdf.resample in Python):
// the request with its field table (core/request_fields.h) and the task, which reads the dataset,
// band-averages it onto the new intervals (io/resample.h) and leaves out the bands asked for, or the
// noisy ones that the quality check (io/quality.h) finds.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/dataset_runs.h"

namespace roadbrdf {

struct ResampleRequest : DatasetReadFields {
  std::string data;                             // dataset file (required)
  std::vector<double> wavelengths;              // band edges [nm], increasing (required)
  std::vector<std::pair<double, double>> drop;  // bands overlapping these intervals [nm] are left out
  bool drop_noisy = false;                      // leave out the noisy bands of the quality check
  double snr_threshold = 20.0;                  // below it a band is noisy (QualityOptions::snr_threshold)
  std::string format = "wide";                  // a name of DatasetFormat (io/dataset_io.h)
  std::string output;                           // where the dataset is written ("" or "-" = standard output)

  static RequestFields<ResampleRequest> fields();
  // Throws FieldError ("data", "wavelengths", "drop", "snr_threshold", "format").
  void validate() const;
};

// The task of `roadbrdf resample`: the resampled dataset (the noisy bands left out listed in its metadata
// "noisy_bands_nm"), after check_distinct_files over the request's files; reading warnings go to `warn`
// (default: the front end's sink). Written to `output` in `format` when given (write_dataset_output).
// Throws FieldError / InputError / FileError.
SpectralDataset resample(const ResampleRequest& request, const std::function<void(const std::string&)>& warn = {});

}  // namespace roadbrdf
