#include "roadbrdf/io/eval_request.h"

#include <fmt/core.h>

#include <ostream>

#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"

namespace roadbrdf {

RequestFields<EvalRequest> EvalRequest::fields() {
  using R = EvalRequest;
  static const std::vector<RequestField<R>> rows = [] {
    std::vector<RequestField<R>> all = model_source_fields<R>();
    const RequestField<R> own[] = {
        {"wavelength", "--wavelength", "nm",
         "Wavelength at which a fit file is evaluated (needed unless it has a single band)", &R::wavelength},
        {"theta_i", "--theta-i", "deg", "Incidence zenith angle", &R::theta_i},
        {"phi_i", "--phi-i", "deg", "Incidence azimuth", &R::phi_i},
        {"theta_r", "--theta-r", "deg", "Reflection (viewing) zenith angle", &R::theta_r},
        {"phi_r", "--phi-r", "deg", "Reflection azimuth", &R::phi_r},
        {"geometry", "--geometry", "",
         "CSV with columns theta_i,phi_i,theta_r,phi_r or gamma,alpha,beta,delta [deg]; the same table is written "
         "with a 'brdf' column added",
         &R::geometry, FileRole::input},
        {"output", "-o,--output", "", "Output CSV (default: standard output)", &R::output, FileRole::output},
    };
    all.insert(all.end(), std::begin(own), std::end(own));
    return all;
  }();
  return rows;
}

namespace {

// The parameter set to evaluate: a model's constant parameters, or a fit/MIX file's at one
// wavelength (its only band when it has one, else `wavelength`).
std::vector<double> parameters_to_evaluate(const SpectralModel& sm, const EvalRequest& r) {
  if (!sm.is_spectral()) {
    if (r.wavelength) {
      throw FieldError("wavelength", "needs a fit file or a MIX.json as `model`: a model name has no spectrum");
    }
    return sm.parameter_table();
  }
  const auto& wl = sm.wavelengths();
  if (!r.wavelength && wl.size() > 1) {
    throw InputError(fmt::format("{} holds {} wavelengths ({:g}-{:g} nm): choose one with `wavelength`", r.model,
                                 wl.size(), wl.front(), wl.back()));
  }
  return sm.parameters_at(r.wavelength.value_or(wl.front()));
}

}  // namespace

EvalResult evaluate(const EvalRequest& request) {
  if (request.model.empty()) throw FieldError("model", "give a model name, a FIT.json or a MIX.json");
  check_request_files(request);
  const SpectralModel sm = request.resolve().model;
  const std::vector<double> parameters = parameters_to_evaluate(sm, request);
  const bool any_angle = request.theta_i || request.phi_i || request.theta_r || request.phi_r;
  EvalResult result;
  if (!request.geometry.empty()) {
    if (any_angle) throw InputError("give either `geometry` or the four angles, not both");
    GeometryTable table = read_geometry_file(request.geometry);
    for (const auto& name : table.header) {
      if (name == "brdf") {
        throw FileError(request.geometry, 0, 0,
                        "already has a 'brdf' column (an eval output?): a second one would be added");
      }
    }
    result.brdf.resize(table.geometries.size());
    sm.model().evaluate_batch(table.geometries.data(), table.geometries.size(), parameters.data(), 1,
                              result.brdf.data());
    result.table = std::move(table);
    if (!request.output.empty()) {
      AtomicFile out(request.output);
      write_eval_table(out.stream(), result);
      out.commit();
    }
    return result;
  }
  if (!request.theta_i || !request.phi_i || !request.theta_r || !request.phi_r) {
    throw InputError("give `theta_i`, `phi_i`, `theta_r` and `phi_r` (degrees), or `geometry` (a CSV file)");
  }
  if (!request.output.empty()) throw FieldError("output", "is the table of a `geometry` file: give one");
  const Geometry g = geometry_from_degrees(*request.theta_i, *request.phi_i, *request.theta_r, *request.phi_r);
  result.brdf = {sm.model().evaluate(parameters.data(), g)};
  return result;
}

void write_eval_table(std::ostream& out, const EvalResult& result) {
  if (result.table) write_geometry_table_with_column(out, *result.table, "brdf", result.brdf);
}

}  // namespace roadbrdf
