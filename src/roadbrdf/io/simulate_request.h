// The virtual gonioreflectometer as the front ends ask for it (`roadbrdf simulate`, roadbrdf.simulate
// in Python): the request with its field table (core/request_fields.h) and the task, which samples
// the model of the shared source rows (modelfile/model_source_fields.h) on a geometry grid with the
// noise of io/simulate.h and writes the dataset.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/modelfile/model_source_fields.h"

namespace roadbrdf {

struct SimulateRequest : ModelSourceFields {
  std::string grid;                   // geometry grid CSV (required)
  std::vector<double> wavelengths;    // [nm], increasing (empty: the fit's wavelengths)
  std::vector<std::string> spectral;  // NAME=FILE: a parameter given as a spectrum
  std::string noise = "none";         // parse_noise_model's grammar (io/simulate.h)
  std::uint64_t seed = 1;             // seed of the noise
  int digits = 0;                     // significant digits of the values, [0, 17] (0 = full precision)
  bool sigma = true;                  // write the noise standard deviation as sigma columns
  std::vector<std::string> metadata;  // KEY=VALUE written as '# key: value'
  std::string format = "wide";        // a name of DatasetFormat (io/dataset_io.h)
  std::string output;                 // where the dataset is written ("" or "-" = standard output)

  static RequestFields<SimulateRequest> fields();
};

// The task of `roadbrdf simulate`: the simulated dataset, after check_distinct_files over the
// request's files (the spectra of `spectral` among the inputs); written to `output` in `format` when
// given (write_dataset_output). Throws FieldError / InputError / FileError.
SpectralDataset simulate(const SimulateRequest& request);

}  // namespace roadbrdf
