// An r-table as the front ends ask for it (`roadbrdf rtable`, roadbrdf.rtable in Python): the
// request with its one validation and its field table (core/request_fields.h: the command's options
// and Python's keywords are made from it), the task (rtable_task.cpp) and the report with the table,
// its summary figures, the class, their uncertainties from a fit's covariance (rtable_uncertainty.h),
// the coverage of the fit behind it, and the notes and warnings that go with them. The command line
// and the Python module only print or return the report; neither decides a rule of its own.
//
// Errors are FieldError with the field names below ("wavelength", "band", "alpha", ...), which are
// also the Python keywords; the command line spells them as the table's flags.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/modelfile/model_source_fields.h"
#include "roadbrdf/models/spectral_model.h"
#include "roadbrdf/photometry/rtable.h"
#include "roadbrdf/photometry/rtable_coverage.h"
#include "roadbrdf/photometry/rtable_io.h"
#include "roadbrdf/photometry/rtable_uncertainty.h"

namespace roadbrdf::photometry {

struct RTableRequest : ModelSourceFields {
  // Where the table comes from: a model (ModelSourceFields, the one resolver of
  // modelfile/model_source.h: a model name with `parameters` and `options`, or a FIT.json or MIX.json
  // with `fit` choosing an entry), or an r-table file (`import_file`, read as `import_format` when its
  // extension does not tell, its values `scale` times r). Exactly one of `model` and `import_file`.
  std::string import_file, import_format;
  double scale = kRScale;
  // How a spectral model is reduced to one BRDF per geometry (SpectralWeighting): photometrically
  // with V(lambda) x illuminant ("" = CIE A, "A", "D65" or a lamp CSV), or at one wavelength, or as
  // the unweighted mean over a band [lo, hi]. At most one of the three may be given. A
  // wavelength-independent model ignores them (with a note); a single-band model is used at its band.
  std::string illuminant;
  std::optional<double> wavelength;               // [nm]
  std::optional<std::pair<double, double>> band;  // [lo, hi] [nm]
  double alpha = 1.0;                             // observation angle above the road plane, (0, 90) [deg]
  std::string q0_region = "standard";             // a name of kQ0RegionNames (rtable.h)
  std::string class_system = "R";                 // R | N | C: the class reported as "class"
  std::string compare;                            // a reference r-table file to compare with ("" = none)
  std::string output;                             // where the table is written, atomically ("" = nowhere)
  std::string format;  // a name of RTableFormat for `output` ("" = from its extension, else csv)

  static std::span<const RequestField<RTableRequest>> fields();

  // Throws FieldError.
  void validate() const;
  // An imported table has no spectrum to reduce: throws FieldError if a weighting field is set.
  void validate_for_import() const;
  Q0Region region() const;
  ClassSystem system() const;
  // The format of `output`: `format`, else the output's extension, else csv. Throws FieldError.
  RTableFormat output_format() const;
};

struct RTableReport {
  RTable table;
  RTableSummary summary;
  RoadClass chosen;  // in the request's class system
  std::string q0_region, class_system;
  RTableCoverage coverage;            // the fit's coverage (none for an imported table)
  std::optional<double> declared_q0;  // an imported RTB file's own q0 line
  nlohmann::json weighting;           // what reduced the spectrum (null for an imported table)
  std::vector<std::string> notes;     // one line each ("the fit has a single band...")
  std::vector<std::string> warnings;  // one line each (mostly extrapolated, implausible Q0...)
  std::optional<RTableComparison> comparison;
  // From a fit's parameter covariance (rtable_uncertainty.h; none for a model given by its
  // parameters, a mixture, an imported table): u of the figures, and the probability of every class
  // of the request's system (in increasing S1; empty when u(S1) is undefined or unknown, or when the
  // standard region is all extrapolated: coverage.extrapolated()).
  std::optional<RTableUncertainty> uncertainty;
  std::vector<ClassProbability> class_probabilities;
  std::string compared_with;  // the reference's name, when compared
  // Where the table came from ({"model": name, "fit_file": path} or {"import": path, "format", "scale"};
  // null when not set) and where it was written ({"file", "format"}; null when not written).
  nlohmann::json source, output;

  // Compare with a reference table (`b` of compare()): fills `comparison`.
  void compare_with(const RTable& reference, const std::string& name);
  // The document `roadbrdf rtable --json` prints (plain r in sr^-1, null = missing; units listed).
  nlohmann::json to_json() const;
  // The classes of class_probabilities worth reporting (probability >= kReportedClassProbability).
  std::vector<ClassProbability> reported_classes() const;
  // The JSON "uncertainty" object: {method, Q0, S1, S2, Qd, correlated: {Q0, S1, S2, Qd},
  // class_probabilities: [{class, probability}...]} (null entries where undefined); null without an
  // uncertainty.
  nlohmann::json uncertainty_json() const;
  // The summary lines `roadbrdf rtable` prints (Q0, S1, S2, Qd, r(0,0), class, cells...).
  std::string summary_text() const;
};

// The r-table of a spectral model (a fit file, a mixture, or a plain model as a constant spectral
// model) at the request's weighting. Throws FieldError / InputError.
RTableReport rtable_report(const SpectralModel& model, const RTableRequest& request);
// How rtable_report evaluates a spectral model at the r-table geometries under a weighting: the
// per-geometry weighted BRDF, as weighted_brdf (rtable.h) computes it. A caller with a faster way to the
// same numbers supplies its own (mixing/end_member_cache.h: a mixture from its end-members' values at
// the table's geometries, computed once for many mixtures).
using WeightedBrdf = std::function<std::vector<double>(const SpectralModel& model, const SpectralWeighting& weighting,
                                                       const std::vector<Geometry>& geometries)>;
RTableReport rtable_report(const SpectralModel& model, const RTableRequest& request, const WeightedBrdf& brdf);
// The report of an r-table read from a file (read_rtable). Throws FieldError / InputError.
RTableReport rtable_report(RTableFile imported, const RTableRequest& request);

// The task of `roadbrdf rtable` and roadbrdf.rtable: the report of the request's model or imported
// file, compared with `compare` and written to `output` when they are given, after
// check_distinct_files over the request's files. Throws FieldError / InputError / FileError.
RTableReport rtable(const RTableRequest& request);
// The same for a model the caller holds already (Python's Model and SpectralModel objects): the
// request's source fields (`model`, `parameters`, `options`, `fit`, `import_file`, ...) stay empty.
RTableReport rtable(const SpectralModel& model, const RTableRequest& request);

}  // namespace roadbrdf::photometry
