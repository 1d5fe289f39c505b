// A BRDF evaluated as the front ends ask for it (`roadbrdf eval`, roadbrdf.evaluate in Python): the
// request with its field table (core/request_fields.h: the command's options and Python's keywords
// are made from it) and the task. The model comes from the shared source rows
// (modelfile/model_source_fields.h); the geometry is four angles or a geometry file.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/io/geometry_file.h"
#include "roadbrdf/modelfile/model_source_fields.h"

namespace roadbrdf {

struct EvalRequest : ModelSourceFields {
  // The wavelength [nm] at which a fit file or a MIX.json is evaluated (not given: its only band).
  std::optional<double> wavelength;
  // One geometry [deg], all four angles, or a geometry file (`geometry`: a CSV with theta_i, phi_i,
  // theta_r, phi_r or gamma, alpha, beta, delta), not both.
  std::optional<double> theta_i, phi_i, theta_r, phi_r;
  std::string geometry;
  // Where the geometry table with its added `brdf` column is written, atomically ("" = not written
  // by the task: the command line prints it).
  std::string output;

  static RequestFields<EvalRequest> fields();
};

struct EvalResult {
  // The BRDF [sr^-1] at the four angles, or one per row of `table` (the geometry file).
  std::vector<double> brdf;
  std::optional<GeometryTable> table;
};

// The task of `roadbrdf eval`: the model's BRDF at the request's geometry, the table written to
// `output` when given (after check_distinct_files over the request's files). Throws FieldError /
// InputError / FileError.
EvalResult evaluate(const EvalRequest& request);

// The geometry table of a result with its `brdf` column (CSV).
void write_eval_table(std::ostream& out, const EvalResult& result);

}  // namespace roadbrdf
