// The fitted parameters of a fit file as a table (`roadbrdf params`, roadbrdf.params in Python): one
// row per fit (model and geometry group) and wavelength, with each parameter and its standard error,
// RMSE, relative RMSE, maximum relative error, AIC, BIC, convergence and the parameters on a bound.
// These are the report's tables (chapters 5 and 6: per-incidence fits at 600 nm), ready to paste as
// text, CSV, Markdown or LaTeX.
//
// A wavelength asked for that was not fitted is answered by the nearest fitted one, with a note
// ("600 nm: nearest band 610 nm"); two wavelengths answered by the same band give one row.
#pragma once

#include <map>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/request_fields.h"

namespace roadbrdf {

enum class ParamsFormat { kTable, kCsv, kMarkdown, kLatex };
inline constexpr EnumName<ParamsFormat> kParamsFormatNames[] = {
    {ParamsFormat::kTable, "table", "aligned text"},
    {ParamsFormat::kCsv, "csv", "every number, separate stderr columns"},
    {ParamsFormat::kMarkdown, "markdown", ""},
    {ParamsFormat::kLatex, "latex", ""},
};
constexpr std::span<const EnumName<ParamsFormat>> enum_names(ParamsFormat) { return kParamsFormatNames; }

struct ParamsRequest {
  std::string fit_file;
  std::vector<double> wavelengths;  // [nm]; empty: every fitted wavelength
  std::vector<std::string> models;  // models to show; empty: all
  // Sections: one table per value of these columns ("model", "wavelength" or a group_by column of the
  // file, e.g. "theta_i"), headed "theta_i = 40 deg"; the columns leave the tables' bodies. CSV (and the
  // DataFrame) stay one table, its rows in section order. Checked against the file by read_params_table.
  std::vector<std::string> group_by;
  std::string format = "table";  // a name of kParamsFormatNames
  std::string output;            // the table's text file; "" or "-": standard output

  // The format named by `format`; throws FieldError("format").
  ParamsFormat table_format() const;
  // Throws FieldError ("fit_file", "wavelengths", "models", "group_by", "format").
  void validate() const;
  // One row per field (core/request_fields.h): `roadbrdf params` and roadbrdf.params are made of it.
  static std::span<const RequestField<ParamsRequest>> fields();
};

struct ParamsRow {
  std::string model;
  std::vector<double> group;  // values [deg] of ParamsTable::group_columns
  double wavelength = 0.0;    // nm
  // Indexed like ParamsTable::parameter_names; NaN where the model has no such parameter, and
  // standard errors NaN for fixed parameters, parameters on a bound (at_bounds) or an undefined
  // covariance.
  std::vector<double> values, standard_errors;
  std::vector<bool> fixed;
  double rmse = 0.0;                // sr^-1
  double relative_rmse = 0.0;       // 1
  double max_relative_error = 0.0;  // 1
  double aic = 0.0, bic = 0.0;
  bool converged = false;
  std::string at_bounds;  // "name=lower;name=upper" or ""
};

// A fit of the table (in file order, the models asked for): what the file says about it beyond the rows, read
// from the same parse, so that a front end never reads the fit file again.
struct ParamsFit {
  std::string model;
  std::vector<double> group;                   // values [deg] of ParamsTable::group_columns
  std::map<std::string, std::string> options;  // the model's options as the file gives them
  std::vector<std::string> fixed;              // the parameters held fixed, as the file lists them
  // The physical range of each parameter (ParameterInfo::lower/upper of the model built with `options`),
  // indexed like ParamsTable::parameter_names; NaN for a parameter the model does not have.
  std::vector<double> lower, upper;
};

struct ParamsTable {
  std::string source;                        // the fit file as named in messages
  std::vector<std::string> group_columns;    // the file's group_by columns (degrees)
  std::vector<std::string> parameter_names;  // every model's parameters, in order of first appearance
  std::vector<std::string> parameter_units;  // aligned with parameter_names
  std::vector<ParamsRow> rows;
  std::vector<ParamsFit> fits;
  std::vector<std::string> notes;  // nearest-wavelength answers
  // The section columns (ParamsRequest::group_by) as display-column indices: 0 the model, 1..G the
  // group columns, G+1 the wavelength. The rows are in section order (first appearance).
  std::vector<std::size_t> section_columns;

  // The table in a format. Text, Markdown and LaTeX show "value ± stderr" with 4 significant digits;
  // CSV gives every number to 10 significant digits in separate columns (see csv_columns()).
  std::string render(ParamsFormat format) const;
  // The CSV / DataFrame column names: model, <group>_deg..., wavelength_nm, then per parameter NAME and
  // NAME_stderr, rmse_per_sr, relative_rmse_percent, max_relative_error_percent, aic, bic, converged,
  // at_bounds.
  std::vector<std::string> csv_columns() const;
  // One row's cells in the order of csv_columns(): text, numbers (relative errors in percent; NaN where
  // there is none) and the convergence flag. The CSV and Python's DataFrame are both made of them.
  using Cell = std::variant<std::string, double, bool>;
  std::vector<Cell> csv_cells(const ParamsRow& row) const;
};

// Reads the fit file and builds the table. Throws FileError (with the JSON key path; a model or options
// no model of the registry accepts fail at the fit's "model" key) / FieldError, and InputError when
// `output` is the fit file.
ParamsTable read_params_table(const ParamsRequest& request);

// The table in the request's format, written atomically to `output` (standard output when "" or "-").
void write_params_output(const ParamsRequest& request, const ParamsTable& table);

}  // namespace roadbrdf
