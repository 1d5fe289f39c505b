#include "roadbrdf/fitting/params_table.h"

#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/input_file.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/models/registry.h"

namespace roadbrdf {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A per-wavelength array of a fit (it must have `m` elements), read once for all its rows. The usual
// element is read directly; any other goes through its node, whose error names the key path.
JsonNode per_wavelength(const JsonNode& fit, const std::string& key, std::size_t m) {
  const JsonNode a = fit.at(key);
  if (a.size() != m) a.fail(fmt::format("expected {} values (one per wavelength), found {}", m, a.size()));
  return a;
}

// Numbers, null read as NaN (no value: a fixed parameter's standard error, an undefined covariance).
std::vector<double> numbers_or_nan(const JsonNode& fit, const std::string& key, std::size_t m) {
  const JsonNode a = per_wavelength(fit, key, m);
  std::vector<double> out(m, kNaN);
  for (std::size_t w = 0; w < m; ++w) {
    const Json& x = a.json()[w];
    if (x.is_null()) continue;
    const double v = x.is_number() ? x.get<double>() : kNaN;
    out[w] = std::isfinite(v) ? v : a[w].number();
  }
  return out;
}

std::vector<bool> booleans(const JsonNode& fit, const std::string& key, std::size_t m) {
  const JsonNode a = per_wavelength(fit, key, m);
  std::vector<bool> out(m);
  for (std::size_t w = 0; w < m; ++w) {
    const Json& x = a.json()[w];
    out[w] = x.is_boolean() ? x.get<bool>() : a[w].boolean();
  }
  return out;
}

// Lists of strings ("at_bounds": mostly empty).
std::vector<std::vector<std::string>> string_lists(const JsonNode& fit, const std::string& key, std::size_t m) {
  const JsonNode a = per_wavelength(fit, key, m);
  std::vector<std::vector<std::string>> out(m);
  for (std::size_t w = 0; w < m; ++w) {
    const Json& x = a.json()[w];
    if (!(x.is_array() && x.empty())) out[w] = a[w].strings();
  }
  return out;
}

// The indices of the fitted wavelengths answering the wanted ones (all when none are wanted): the
// nearest band, with a note for every answer that is not exact (select_wavelengths, fitting/fit.h).
std::vector<std::size_t> answer_wavelengths(const std::vector<double>& fitted, const std::vector<double>& wanted,
                                            std::vector<std::string>& notes) {
  std::vector<std::size_t> out;
  if (wanted.empty()) {
    for (std::size_t w = 0; w < fitted.size(); ++w) out.push_back(w);
    return out;
  }
  std::vector<std::string> mine;
  out = select_wavelengths(fitted, wanted, &mine);
  for (const auto& n : mine) {
    if (std::find(notes.begin(), notes.end(), n) == notes.end()) notes.push_back(n);
  }
  return out;
}

std::string plus_minus(double value, double stderr_value, ParamsFormat format) {
  if (!std::isfinite(value)) return "";
  std::string v = fmt::format("{:.4g}", value);
  if (!std::isfinite(stderr_value)) return v;
  const std::string e = fmt::format("{:.2g}", stderr_value);
  if (format == ParamsFormat::kLatex) return "$" + v + " \\pm " + e + "$";
  return v + " ± " + e;
}

std::string cell(double x, const char* spec) {
  return std::isfinite(x) ? fmt::format(fmt::runtime(spec), x) : std::string("");
}

std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string latex_text(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '_' || c == '%' || c == '&' || c == '#') out += '\\';
    out += c;
  }
  return out;
}

// Rows of display cells (header first) for the text, Markdown and LaTeX formats: the rows [begin, end)
// of the table, without its section columns.
std::vector<std::vector<std::string>> display_cells(const ParamsTable& t, ParamsFormat format, std::size_t begin,
                                                    std::size_t end) {
  std::vector<std::vector<std::string>> cells;
  std::vector<std::string> header = {"model"};
  for (const auto& c : t.group_columns) header.push_back(c + " [deg]");
  header.push_back("wavelength [nm]");
  for (std::size_t k = 0; k < t.parameter_names.size(); ++k) {
    header.push_back(t.parameter_names[k] + " [" + t.parameter_units[k] + "]");
  }
  for (const char* h : {"RMSE [sr^-1]", "rel. RMSE [%]", "max rel. err. [%]", "AIC", "BIC", "converged", "on bound"}) {
    header.emplace_back(h);
  }
  cells.push_back(header);
  for (std::size_t i = begin; i < end; ++i) {
    const ParamsRow& r = t.rows[i];
    std::vector<std::string> row = {r.model};
    for (double g : r.group) row.push_back(fmt::format("{:g}", g));
    row.push_back(fmt::format("{:g}", r.wavelength));
    for (std::size_t k = 0; k < t.parameter_names.size(); ++k) {
      std::string v = plus_minus(r.values[k], r.standard_errors[k], format);
      if (r.fixed[k] && !v.empty()) v += " (fixed)";
      row.push_back(v);
    }
    row.push_back(cell(r.rmse, "{:.4g}"));
    row.push_back(cell(100.0 * r.relative_rmse, "{:.3g}"));
    row.push_back(cell(100.0 * r.max_relative_error, "{:.3g}"));
    row.push_back(cell(r.aic, "{:.2f}"));
    row.push_back(cell(r.bic, "{:.2f}"));
    row.push_back(r.converged ? "yes" : "no");
    row.push_back(r.at_bounds.empty() ? "-" : r.at_bounds);
    if (format == ParamsFormat::kLatex) {
      for (auto& c : row) {
        if (c.empty() || c.front() != '$') c = latex_text(c);
      }
    }
    cells.push_back(row);
  }
  if (format == ParamsFormat::kLatex) {
    for (auto& c : cells.front()) c = latex_text(c);
  }
  std::vector<std::size_t> hidden = t.section_columns;
  std::sort(hidden.rbegin(), hidden.rend());
  for (auto& row : cells) {
    for (std::size_t c : hidden) row.erase(row.begin() + static_cast<std::ptrdiff_t>(c));
  }
  return cells;
}

// The value of display column `column` (see ParamsTable::section_columns) of a row, for sections.
std::string section_value(const ParamsTable& t, const ParamsRow& r, std::size_t column) {
  if (column == 0) return r.model;
  if (column <= t.group_columns.size()) return fmt::format("{:g}", r.group[column - 1]);
  return fmt::format("{:g}", r.wavelength);
}

// "theta_i = 40 deg, model = lambert": the heading of the section holding row `r`.
std::string section_heading(const ParamsTable& t, const ParamsRow& r) {
  std::vector<std::string> parts;
  parts.reserve(t.section_columns.size());
  for (std::size_t c : t.section_columns) {
    if (c == 0) {
      parts.push_back("model = " + r.model);
    } else if (c <= t.group_columns.size()) {
      parts.push_back(t.group_columns[c - 1] + " = " + section_value(t, r, c) + " deg");
    } else {
      parts.push_back("wavelength = " + section_value(t, r, c) + " nm");
    }
  }
  return fmt::format("{}", fmt::join(parts, ", "));
}

// The sections as row ranges [begin, end) (one range of every row without section columns).
std::vector<std::pair<std::size_t, std::size_t>> section_ranges(const ParamsTable& t) {
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    if (ranges.empty() || section_heading(t, t.rows[i]) != section_heading(t, t.rows[ranges.back().first])) {
      ranges.emplace_back(i, i + 1);
    } else {
      ranges.back().second = i + 1;
    }
  }
  return ranges;
}

// Display width in characters (UTF-8 continuation bytes do not count: "±" is one column).
std::size_t display_width(const std::string& s) {
  return static_cast<std::size_t>(
      std::count_if(s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

}  // namespace

std::span<const RequestField<ParamsRequest>> ParamsRequest::fields() {
  using R = ParamsRequest;
  static const std::string format_help = "Table format: " + described_names_text<ParamsFormat>() + " (default table)";
  static const RequestField<R> rows[] = {
      {"fit_file", "FIT", "", "Fit file (JSON) written by `roadbrdf fit`", &R::fit_file, FileRole::input, true},
      {"wavelengths", "--wavelengths,--wavelength", "nm",
       "Wavelengths to show: START:STOP:STEP or a list; one not fitted is answered by the nearest fitted band, "
       "with a note (default: every fitted wavelength)",
       &R::wavelengths},
      {"models", "-m,--model", "", "Show only this model's fits (repeatable)", &R::models},
      {"group_by", "--group-by", "",
       "One table per value of these columns (comma-separated: model, wavelength, or a group column of the fit "
       "file such as theta_i), each headed e.g. 'theta_i = 40 deg'; CSV stays one table in that order",
       &R::group_by, FileRole::none, false, true},
      {"format", "--format", "", format_help, &R::format},
      {"output", "-o,--output", "", "Write the table to this file (atomically; default: standard output)", &R::output,
       FileRole::output},
  };
  return rows;
}

ParamsFormat ParamsRequest::table_format() const { return parse_name<ParamsFormat>(format, "format"); }

void ParamsRequest::validate() const {
  if (fit_file.empty()) throw FieldError("fit_file", "give the fit file");
  table_format();
  for (std::size_t i = 0; i < group_by.size(); ++i) {
    if (std::find(group_by.begin(), group_by.begin() + static_cast<std::ptrdiff_t>(i), group_by[i]) !=
        group_by.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw FieldError("group_by", "column '" + group_by[i] + "' is given twice");
    }
  }
  for (double w : wavelengths) {
    if (!std::isfinite(w) || w <= 0.0) throw FieldError("wavelengths", fmt::format("{} is not a wavelength", w));
  }
}

std::vector<std::string> ParamsTable::csv_columns() const {
  std::vector<std::string> c = {"model"};
  for (const auto& g : group_columns) c.push_back(g + "_deg");
  c.emplace_back("wavelength_nm");
  for (const auto& p : parameter_names) {
    c.push_back(p);
    c.push_back(p + "_stderr");
  }
  for (const char* s :
       {"rmse_per_sr", "relative_rmse_percent", "max_relative_error_percent", "aic", "bic", "converged", "at_bounds"}) {
    c.emplace_back(s);
  }
  return c;
}

std::vector<ParamsTable::Cell> ParamsTable::csv_cells(const ParamsRow& r) const {
  std::vector<Cell> c = {r.model};
  c.reserve(r.group.size() + 2 * parameter_names.size() + 9);
  for (double g : r.group) c.emplace_back(g);
  c.emplace_back(r.wavelength);
  for (std::size_t k = 0; k < parameter_names.size(); ++k) {
    c.emplace_back(r.values[k]);
    c.emplace_back(r.standard_errors[k]);
  }
  for (double x : {r.rmse, 100.0 * r.relative_rmse, 100.0 * r.max_relative_error, r.aic, r.bic}) c.emplace_back(x);
  c.emplace_back(r.converged);
  c.emplace_back(r.at_bounds);
  return c;
}

namespace {

std::string render_csv(const ParamsTable& t) {
  std::string out = "# roadbrdf params of " + t.source +
                    ": angles in degrees, wavelength in nm, RMSE in sr^-1, relative errors in percent; "
                    "parameter units:";
  for (std::size_t k = 0; k < t.parameter_names.size(); ++k) {
    out += fmt::format(" {} {}", t.parameter_names[k], t.parameter_units[k]);
  }
  out += "\n";
  for (const auto& n : t.notes) out += "# note: " + n + "\n";
  out += fmt::format("{}\n", fmt::join(t.csv_columns(), ","));
  for (const ParamsRow& r : t.rows) {
    std::vector<std::string> c;
    for (const ParamsTable::Cell& value : t.csv_cells(r)) {
      if (const auto* text = std::get_if<std::string>(&value)) {
        c.push_back(csv_text(*text));
      } else if (const auto* number = std::get_if<double>(&value)) {
        c.push_back(cell(*number, "{:.10g}"));
      } else {
        c.emplace_back(std::get<bool>(value) ? "true" : "false");
      }
    }
    out += fmt::format("{}\n", fmt::join(c, ","));
  }
  return out;
}

// Display cells padded to their column's width (UTF-8 aware).
struct PaddedCells {
  std::vector<std::vector<std::string>> cells;  // header first
  std::vector<std::size_t> width;
  std::string at(std::size_t r, std::size_t c) const {
    return cells[r][c] + std::string(width[c] - display_width(cells[r][c]), ' ');
  }
};

PaddedCells padded_cells(const ParamsTable& t, ParamsFormat format, std::size_t begin, std::size_t end) {
  PaddedCells p;
  p.cells = display_cells(t, format, begin, end);
  p.width.assign(p.cells.front().size(), 0);
  for (const auto& row : p.cells) {
    for (std::size_t c = 0; c < row.size(); ++c) p.width[c] = std::max(p.width[c], display_width(row[c]));
  }
  return p;
}

std::string latex_tabular(const ParamsTable& t, std::size_t begin, std::size_t end) {
  const PaddedCells p = padded_cells(t, ParamsFormat::kLatex, begin, end);
  std::string out = "\\begin{tabular}{" + std::string(p.width.size(), 'l') + "}\n\\hline\n";
  for (std::size_t r = 0; r < p.cells.size(); ++r) {
    for (std::size_t c = 0; c < p.cells[r].size(); ++c) out += fmt::format("{}{}", c ? " & " : "", p.at(r, c));
    out += r == 0 ? " \\\\\n\\hline\n" : " \\\\\n";
  }
  return out + "\\hline\n\\end{tabular}\n";
}

std::string markdown_table(const ParamsTable& t, std::size_t begin, std::size_t end) {
  const PaddedCells p = padded_cells(t, ParamsFormat::kMarkdown, begin, end);
  std::string out;
  for (std::size_t r = 0; r < p.cells.size(); ++r) {
    out += "|";
    for (std::size_t c = 0; c < p.cells[r].size(); ++c) out += fmt::format(" {} |", p.at(r, c));
    out += "\n";
    if (r > 0) continue;
    out += "|";
    for (std::size_t w : p.width) out += std::string(w + 2, '-') + "|";
    out += "\n";
  }
  return out;
}

std::string text_table(const ParamsTable& t, std::size_t begin, std::size_t end) {
  const PaddedCells p = padded_cells(t, ParamsFormat::kTable, begin, end);
  std::string out;
  for (std::size_t r = 0; r < p.cells.size(); ++r) {
    std::string line;
    for (std::size_t c = 0; c < p.cells[r].size(); ++c) line += fmt::format("{}{}", c ? "  " : "", p.at(r, c));
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}

// One table per section, each under its heading (none without sections).
std::string render_sections(const ParamsTable& t, ParamsFormat format) {
  std::string out;
  for (const auto& [begin, end] : section_ranges(t)) {
    const std::string heading = t.section_columns.empty() ? "" : section_heading(t, t.rows[begin]);
    if (!out.empty()) out += "\n";
    switch (format) {
      case ParamsFormat::kLatex:
        if (!heading.empty()) out += "\\par\\textbf{" + latex_text(heading) + "}\n\n";
        out += latex_tabular(t, begin, end);
        break;
      case ParamsFormat::kMarkdown:
        if (!heading.empty()) out += "**" + heading + "**\n\n";
        out += markdown_table(t, begin, end);
        break;
      default:
        if (!heading.empty()) out += "## " + heading + "\n";
        out += text_table(t, begin, end);
        break;
    }
  }
  if (t.rows.empty())
    out = format == ParamsFormat::kLatex      ? latex_tabular(t, 0, 0)
          : format == ParamsFormat::kMarkdown ? markdown_table(t, 0, 0)
                                              : text_table(t, 0, 0);
  return out;
}

// A fit's model, options, fixed parameters and the physical range of its parameters (from the model the
// registry builds with the file's options, as the fit file reader builds it).
ParamsFit fit_of(const JsonNode& fit, const std::string& model, const std::vector<double>& group,
                 const std::vector<std::string>& fixed, const std::vector<std::string>& parameter_names) {
  ParamsFit f;
  f.model = model;
  f.group = group;
  f.fixed = fixed;
  if (const auto o = fit.find("options")) f.options = o->string_map();
  std::unique_ptr<Model> built;
  try {
    built = make_model(model, f.options);
  } catch (const FileError&) {
    throw;
  } catch (const InputError& e) {
    fit.at("model").fail(e.what());
  }
  f.lower.assign(parameter_names.size(), kNaN);
  f.upper.assign(parameter_names.size(), kNaN);
  for (const ParameterInfo& p : built->description().parameters) {
    const auto k = static_cast<std::size_t>(std::find(parameter_names.begin(), parameter_names.end(), p.name) -
                                            parameter_names.begin());
    if (k == parameter_names.size()) continue;  // a parameter the file does not list has no rows either
    f.lower[k] = p.lower;
    f.upper[k] = p.upper;
  }
  return f;
}

}  // namespace

std::string ParamsTable::render(ParamsFormat format) const {
  std::string notes_text;
  switch (format) {
    case ParamsFormat::kCsv:
      return render_csv(*this);
    case ParamsFormat::kLatex:
      for (const auto& n : notes) notes_text += "% note: " + n + "\n";
      return "% roadbrdf params of " + latex_text(source) + "\n" + notes_text + render_sections(*this, format);
    case ParamsFormat::kMarkdown:
      for (const auto& n : notes) notes_text += "\nNote: " + n + "\n";
      return render_sections(*this, format) + notes_text;
    case ParamsFormat::kTable:
      break;
  }
  for (const auto& n : notes) notes_text += "# note: " + n + "\n";
  return "# " + source + "\n" + notes_text + render_sections(*this, format);
}

ParamsTable read_params_table(const ParamsRequest& request) {
  request.validate();
  check_request_files(request);
  const Json document = parse_json_file(request.fit_file);
  const JsonNode root(document, input_display_name(request.fit_file));
  if (!root.is_object() || root.string_or("format", "") != "roadbrdf-fit") {
    throw FileError(root.file(), 0, 0, "not a roadbrdf fit file (format key)");
  }
  ParamsTable t;
  t.source = root.file();
  if (const auto g = root.find("group_by")) t.group_columns = g->strings();
  std::vector<std::string> columns = {"model"};
  columns.insert(columns.end(), t.group_columns.begin(), t.group_columns.end());
  columns.emplace_back("wavelength");
  for (const auto& c : request.group_by) {
    const auto k = std::find(columns.begin(), columns.end(), c);
    if (k == columns.end()) {
      throw FieldError("group_by", fmt::format("unknown column '{}'{}; the columns of {} are {}", c,
                                               did_you_mean(c, columns), t.source, fmt::join(columns, ", ")));
    }
    t.section_columns.push_back(static_cast<std::size_t>(k - columns.begin()));
  }
  const std::vector<JsonNode> fits = root.at("fits").elements();
  std::vector<std::string> models;
  models.reserve(fits.size());
  for (const JsonNode& fit : fits) models.push_back(fit.at("model").string());
  for (const auto& m : request.models) {
    if (std::find(models.begin(), models.end(), m) == models.end()) {
      throw FieldError("models", "no fit of model '" + m + "' in " + t.source + did_you_mean(m, models));
    }
  }
  for (const JsonNode& fit : fits) {
    const std::string model = fit.at("model").string();
    if (!request.models.empty() &&
        std::find(request.models.begin(), request.models.end(), model) == request.models.end()) {
      continue;
    }
    const std::vector<std::string> order = fit.at("parameter_order").strings();
    const JsonNode units = fit.at("parameter_units");
    for (const auto& p : order) {
      if (std::find(t.parameter_names.begin(), t.parameter_names.end(), p) == t.parameter_names.end()) {
        t.parameter_names.push_back(p);
        t.parameter_units.push_back(units.at(p).string());
      }
    }
  }
  for (const JsonNode& fit : fits) {
    const std::string model = fit.at("model").string();
    if (!request.models.empty() &&
        std::find(request.models.begin(), request.models.end(), model) == request.models.end()) {
      continue;
    }
    std::vector<double> group;
    for (const auto& c : t.group_columns) group.push_back(fit.at("group").at(c).number());
    const std::vector<double> wavelengths = fit.at("wavelengths").numbers();
    const std::size_t m = wavelengths.size();
    if (m == 0) fit.at("wavelengths").fail("no wavelengths");
    const std::vector<std::string> fixed = fit.at("fixed").strings();
    t.fits.push_back(fit_of(fit, model, group, fixed, t.parameter_names));
    // Each per-wavelength array read once (a fit of a few thousand wavelengths has as many rows).
    const std::vector<std::string> order = fit.at("parameter_order").strings();
    std::vector<std::size_t> column(order.size());
    std::vector<std::vector<double>> values(order.size()), errors(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
      column[i] = static_cast<std::size_t>(std::find(t.parameter_names.begin(), t.parameter_names.end(), order[i]) -
                                           t.parameter_names.begin());
      values[i] = numbers_or_nan(fit.at("parameters"), order[i], m);
      errors[i] = numbers_or_nan(fit.at("stderr"), order[i], m);
    }
    const std::vector<double> rmse = numbers_or_nan(fit, "rmse", m);
    const std::vector<double> relative_rmse = numbers_or_nan(fit, "relative_rmse", m);
    const std::vector<double> max_relative_error = numbers_or_nan(fit, "max_relative_error", m);
    const std::vector<double> aic = numbers_or_nan(fit, "aic", m), bic = numbers_or_nan(fit, "bic", m);
    const std::vector<bool> converged = booleans(fit, "converged", m);
    const std::vector<std::vector<std::string>> at_bounds = string_lists(fit, "at_bounds", m);
    for (std::size_t w : answer_wavelengths(wavelengths, request.wavelengths, t.notes)) {
      ParamsRow r;
      r.model = model;
      r.group = group;
      r.wavelength = wavelengths[w];
      r.values.assign(t.parameter_names.size(), kNaN);
      r.standard_errors.assign(t.parameter_names.size(), kNaN);
      r.fixed.assign(t.parameter_names.size(), false);
      for (std::size_t i = 0; i < order.size(); ++i) {
        r.values[column[i]] = values[i][w];
        r.standard_errors[column[i]] = errors[i][w];
        r.fixed[column[i]] = std::find(fixed.begin(), fixed.end(), order[i]) != fixed.end();
      }
      r.rmse = rmse[w];
      r.relative_rmse = relative_rmse[w];
      r.max_relative_error = max_relative_error[w];
      r.aic = aic[w];
      r.bic = bic[w];
      r.converged = converged[w];
      for (const auto& b : at_bounds[w]) {
        r.at_bounds += (r.at_bounds.empty() ? "" : ";") + b;
        // A parameter on a bound of its physical range: the linearised covariance assumes a free minimum
        // and its standard error (b0 = 1 +- 53 on [0, 1]) describes nothing, so none is given.
        const std::string name = b.substr(0, b.find('='));  // "sigma=upper"
        const auto k = static_cast<std::size_t>(std::find(t.parameter_names.begin(), t.parameter_names.end(), name) -
                                                t.parameter_names.begin());
        if (k < r.standard_errors.size()) r.standard_errors[k] = kNaN;
      }
      t.rows.push_back(r);
    }
  }
  // Rows in section order: stable, the sections in order of first appearance (each row's heading made
  // once; without sections the rows stay as they are).
  if (t.section_columns.empty()) return t;
  std::map<std::string, std::size_t> section;             // heading -> its rank of first appearance
  std::vector<std::pair<std::size_t, std::size_t>> rank;  // (section, row)
  rank.reserve(t.rows.size());
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const auto k = section.try_emplace(section_heading(t, t.rows[i]), section.size()).first;
    rank.emplace_back(k->second, i);
  }
  std::sort(rank.begin(), rank.end());
  std::vector<ParamsRow> rows;
  rows.reserve(t.rows.size());
  for (const auto& [section, i] : rank) rows.push_back(std::move(t.rows[i]));
  t.rows = std::move(rows);
  return t;
}

void write_params_output(const ParamsRequest& request, const ParamsTable& table) {
  AtomicFile out(request.output.empty() ? std::string("-") : request.output);
  out.stream() << table.render(request.table_format());
  out.commit();
}

}  // namespace roadbrdf
