// A mix as the front ends ask for it (`roadbrdf mix`, roadbrdf.mix in Python): the request with its
// one validation, the run over the methods, and the result with its report.
//
// With method "all", a method that cannot be applied is skipped with a note (methods fitted to a
// measured mixture without --data / data, or a method that fails on this formulation); the notes
// are part of the result, and both front ends show them (the command line as warnings on standard
// error, Python as UserWarning). Nothing is dropped silently. A single method that fails is an
// error.
//
// Errors are FieldError with the field names of MixRequest ("folds", "method", "data", ...); the
// front ends spell them from the request's table (fields(), core/request_fields.h).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/dataset_read_fields.h"
#include "roadbrdf/mixing/end_member_cache.h"
#include "roadbrdf/mixing/mix_file.h"
#include "roadbrdf/mixing/mixing.h"
#include "roadbrdf/models/spectral_model.h"

namespace roadbrdf::mixing {

// The dataset-reading fields (DatasetReadFields: delimiter, decimal, average_duplicates, quantity,
// columns, set) read `data`.
struct MixRequest : DatasetReadFields {
  Source formulation;          // formulation JSON file, or its content
  std::string data;            // measured mixture (CSV); "" = none
  std::string method = "all";  // a method name (mixing.h) or "all"
  int folds = 5;               // cross-validation folds over the data's geometries
  int seed = 1;                // geometry shuffle of the folds, 0 or more
  bool per_wavelength = false;
  bool sum_to_one = false;
  bool use_sigma = true;
  std::optional<double> binder_coverage;  // overrides the formulation (areal), in [0, 1]
  std::optional<double> mastic_fraction;  // overrides the formulation (mastic), in [0, 1]
  std::string reference;                  // fit file or MIX.json of the measured mixture; needs data
  std::string output;                     // MIX.json to write (write_mix_outputs); "" = none
  std::string residuals;                  // held-out residuals CSV to write: needs data; "" = none
  // hapke: calibration file of `roadbrdf mix-calibrate` (calibration.h) with a cross-section factor
  // for every end-member of the formulation; "" = uncalibrated. Only with method hapke or all.
  std::string cross_sections;
  // areal, mastic, hapke: carry the end-members' parameter covariance into the mixture
  // (mixture_covariance.h), so that albedo and r-table of the MIX.json get uncertainties. Off by
  // default: the albedo uncertainty of a mixture differentiates every end-member parameter
  // (e.g. 21 for F1), which makes `roadbrdf albedo MIX.json` minutes instead of seconds.
  bool uncertainty = false;
  ProgressCallback progress;  // mixes done (every method, every fold); not kept in MixRun
  // Fit files given as values (not a field of the table; Python's `fits`): the JSON text of each by
  // the reference a formulation's "fit" gives ("sha256:..." in a study); a reference found here is
  // not read from disk. A formulation given as a value resolves its references as they are written.
  std::map<std::string, std::string> fits;
  // Fit files read once for many requests (a design study's candidates); null: read for this request.
  std::shared_ptr<EndMemberCache> end_member_cache;

  // The table of the fields: the command line's options and Python's keyword arguments.
  static RequestFields<MixRequest> fields();

  // Checks everything that needs no file. Throws FieldError.
  void validate() const;
};

struct MixRun {
  MixRequest request;
  std::unique_ptr<MixInputs> inputs;  // the formulation and its end-members
  std::optional<SpectralDataset> data;
  MixFileContent content;          // results (and comparisons with data), as written to MIX.json
  std::vector<std::string> notes;  // methods skipped, and why

  // The report `roadbrdf mix` prints: per method the held-out errors and albedo, or the albedo.
  std::string table() const;
};

// Validate, read the inputs (after check_distinct_files of the request's file fields and the
// formulation's fit files against its outputs), and run the methods. Throws FieldError / InputError / FileError.
MixRun run_mix(const MixRequest& request);
// Writes the request's `output` (MIX.json) and `residuals` (held-out residuals) of a run; a field
// left empty is not written.
void write_mix_outputs(const MixRun& run);

}  // namespace roadbrdf::mixing
