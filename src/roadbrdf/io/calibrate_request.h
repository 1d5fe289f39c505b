// Calibration against a reference panel as the front ends ask for it (`roadbrdf calibrate`,
// roadbrdf.calibrate and roadbrdf.calibrate_manifest in Python): the request with its field table
// (core/request_fields.h) and the task, which reads the radiance datasets (or a run manifest of
// instrument files) and the panel files and calibrates them (io/calibration.h, io/manifest.h).
#pragma once

#include <optional>
#include <string>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/dataset_runs.h"
#include "roadbrdf/io/instrument_options.h"

namespace roadbrdf {

struct CalibrateRequest : DatasetReadFields, InstrumentOptions {
  std::string sample;                     // sample radiances, dataset CSV (any units)
  std::string reference;                  // reference-panel radiances: same geometries, or one row for all
  std::string manifest;                   // a run of instrument files (replaces sample, reference and dark)
  std::string dark;                       // dark signal: same geometries, or one row ("" = none)
  std::string panel_reflectance;          // rho_ref spectrum file (required)
  std::string panel_brf;                  // measured BRF of the panel ("" = none)
  std::optional<double> panel_brf_start;  // first wavelength of a one-column panel_brf file [nm]
  std::optional<double> panel_brf_step;   // its wavelength step [nm]
  std::string format = "wide";            // a name of DatasetFormat (io/dataset_io.h)
  std::string output;                     // where the dataset is written ("" or "-" = standard output)

  static RequestFields<CalibrateRequest> fields();
};

// The task of `roadbrdf calibrate`: the calibrated BRDF [sr^-1], after check_distinct_files over the
// request's files (a manifest's listed files among the inputs). Either `sample` and `reference`
// (with `dark`), or `manifest`. Written to `output` in `format` when given (write_dataset_output).
// Throws FieldError / InputError / FileError.
SpectralDataset calibrate(const CalibrateRequest& request);

}  // namespace roadbrdf
