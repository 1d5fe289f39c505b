// Python binding of fitting: a FitRequest (fitting/fit_request.h) from the keyword arguments of
// roadbrdf.fit, and the FitSummary as an object with numpy arrays; the fit file is written by the
// same writer as `roadbrdf fit`.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <variant>

#include "binding.h"
#include "request_kwargs.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/fitting/fit_request.h"
#include "roadbrdf/fitting/params_table.h"
#include "roadbrdf/modelfile/fit_file_read.h"

namespace py = pybind11;

namespace roadbrdf::python {

namespace {

using Array = py::array_t<double>;

// The columns of the library's CSV cells (ParamsTable::csv_cells) as NumPy arrays, {name: array} in the order
// of csv_columns(): float64 numbers (NaN where there is none), bool flags and text as an object array. Each
// column holds one kind of cell; a blank row's cells say which (also for a table without rows).
py::dict params_columns(const ParamsTable& t) {
  ParamsRow blank;
  blank.group.assign(t.group_columns.size(), 0.0);
  blank.values.assign(t.parameter_names.size(), 0.0);
  blank.standard_errors.assign(t.parameter_names.size(), 0.0);
  const std::vector<ParamsTable::Cell> kinds = t.csv_cells(blank);
  const auto n = static_cast<py::ssize_t>(t.rows.size());
  std::vector<py::array_t<double>> numbers(kinds.size());
  std::vector<py::array_t<bool>> flags(kinds.size());
  std::vector<py::list> texts(kinds.size());
  for (std::size_t c = 0; c < kinds.size(); ++c) {
    if (std::holds_alternative<double>(kinds[c])) numbers[c] = py::array_t<double>(n);
    if (std::holds_alternative<bool>(kinds[c])) flags[c] = py::array_t<bool>(n);
  }
  for (py::ssize_t r = 0; r < n; ++r) {
    const auto cells = t.csv_cells(t.rows[static_cast<std::size_t>(r)]);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (const auto* x = std::get_if<double>(&cells[c])) {
        numbers[c].mutable_at(r) = *x;
      } else if (const auto* b = std::get_if<bool>(&cells[c])) {
        flags[c].mutable_at(r) = *b;
      } else {
        texts[c].append(std::get<std::string>(cells[c]));
      }
    }
  }
  const py::object as_array = py::module_::import("numpy").attr("array");
  const std::vector<std::string> names = t.csv_columns();
  py::dict data;
  for (std::size_t c = 0; c < kinds.size(); ++c) {
    if (std::holds_alternative<double>(kinds[c])) {
      data[py::str(names[c])] = numbers[c];
    } else if (std::holds_alternative<bool>(kinds[c])) {
      data[py::str(names[c])] = flags[c];
    } else {
      data[py::str(names[c])] = as_array(texts[c], py::arg("dtype") = "object");
    }
  }
  return data;
}

// Each fit of the table (ParamsTable::fits) as a dict: model, group {column: degrees}, options, fixed and
// bounds {parameter: (lower, upper)} of the parameters the model has.
py::list params_fits(const ParamsTable& t) {
  py::list fits;
  for (const ParamsFit& f : t.fits) {
    py::dict fit, group, bounds;
    fit["model"] = f.model;
    for (std::size_t g = 0; g < t.group_columns.size(); ++g) group[py::str(t.group_columns[g])] = f.group[g];
    fit["group"] = group;
    fit["options"] = f.options;
    fit["fixed"] = f.fixed;
    for (std::size_t k = 0; k < t.parameter_names.size(); ++k) {
      if (!std::isnan(f.lower[k])) bounds[py::str(t.parameter_names[k])] = py::make_tuple(f.lower[k], f.upper[k]);
    }
    fit["bounds"] = bounds;
    fits.append(fit);
  }
  return fits;
}

const FitResult& fit_at(const FitSummary& s, std::size_t i) {
  if (i >= s.fits.size()) throw InputError("fit index " + std::to_string(i) + " out of range");
  return s.fits[i];
}

// parameters x wavelengths of one vector member of WavelengthFit.
Array per_parameter(const FitResult& f, std::vector<double> WavelengthFit::*member) {
  const std::size_t p = f.parameter_names.size(), m = f.wavelengths.size();
  Array out({p, m});
  auto v = out.mutable_unchecked<2>();
  for (std::size_t w = 0; w < m; ++w) {
    const std::vector<double>& values = f.wavelengths[w].*member;
    for (std::size_t k = 0; k < p; ++k) {
      v(k, w) = k < values.size() ? values[k] : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return out;
}

py::dict statistics(const FitResult& f) {
  const std::size_t m = f.wavelengths.size();
  auto column = [&](auto getter) {
    Array a(static_cast<py::ssize_t>(m));
    auto v = a.mutable_unchecked<1>();
    for (std::size_t w = 0; w < m; ++w) v(w) = static_cast<double>(getter(f.wavelengths[w]));
    return a;
  };
  py::dict d;
  d["rmse"] = column([](const WavelengthFit& w) { return w.rmse; });
  d["relative_rmse"] = column([](const WavelengthFit& w) { return w.relative_rmse; });
  d["max_relative_error"] = column([](const WavelengthFit& w) { return w.max_relative_error; });
  d["r_squared"] = column([](const WavelengthFit& w) { return w.r_squared; });
  d["chi2"] = column([](const WavelengthFit& w) { return w.chi2; });
  d["aic"] = column([](const WavelengthFit& w) { return w.aic; });
  d["bic"] = column([](const WavelengthFit& w) { return w.bic; });
  d["cost"] = column([](const WavelengthFit& w) { return w.cost; });
  d["iterations"] = column([](const WavelengthFit& w) { return w.iterations; });
  d["points"] = column([](const WavelengthFit& w) { return w.points; });
  d["free_parameters"] = column([](const WavelengthFit& w) { return w.free_parameters; });
  std::vector<bool> converged, covariance_ok;
  std::vector<std::string> status, covariance_message;
  std::vector<std::vector<std::string>> at_bounds;
  for (const auto& w : f.wavelengths) {
    converged.push_back(w.converged);
    covariance_ok.push_back(w.covariance_ok);
    status.push_back(w.status);
    covariance_message.push_back(w.covariance_message);
    at_bounds.push_back(w.at_bounds);
  }
  d["converged"] = converged;
  d["covariance_ok"] = covariance_ok;
  d["status"] = status;
  d["covariance_message"] = covariance_message;
  d["at_bounds"] = at_bounds;
  return d;
}

py::dict totals(const FitResult& f) {
  py::dict d;
  d["rmse"] = f.rmse_total;
  d["relative_rmse"] = f.relative_rmse_total;
  d["max_relative_error"] = f.max_relative_error_total;
  d["chi2"] = f.chi2_total;
  d["aic"] = f.aic_total;
  d["bic"] = f.bic_total;
  d["points"] = f.points_total;
  d["missing_values"] = f.missing_values;
  d["free_parameters"] = f.free_parameters_total;
  d["converged_count"] = f.converged_count;
  d["at_bound_count"] = f.at_bound_count;
  d["covariance_failures"] = f.covariance_failures;
  d["stayed_at_start_count"] = f.stayed_at_start_count;
  d["worse_than_nested"] = f.worse_than_nested;
  // The angular coverage of the data (the fit file's "coverage").
  py::dict c;
  c["theta_i_deg"] = std::vector<double>{f.coverage.theta_i_min_deg, f.coverage.theta_i_max_deg};
  c["theta_r_deg"] = std::vector<double>{f.coverage.theta_r_min_deg, f.coverage.theta_r_max_deg};
  c["azimuth_planes_deg"] = f.coverage.azimuth_planes_deg;
  c["geometries"] = f.coverage.geometries;
  d["coverage"] = c;
  d["seconds"] = f.seconds;
  d["joint"] = f.joint;
  return d;
}

}  // namespace

void bind_fitting(py::module_& m) {
  py::class_<FitSummary, std::shared_ptr<FitSummary>>(m, "FitSummary")
      .def_property_readonly("count", [](const FitSummary& s) { return s.fits.size(); })
      .def_property_readonly("ranking", [](const FitSummary& s) { return s.ranking; })
      .def_property_readonly("wavelengths", [](const FitSummary& s) { return s.wavelengths; })
      .def_property_readonly("geometry_count", [](const FitSummary& s) { return s.geometry_count; })
      .def_property_readonly("missing_values", [](const FitSummary& s) { return s.missing_values; })
      .def_property_readonly("notes", [](const FitSummary& s) { return s.notes; })
      .def("model_name", [](const FitSummary& s, std::size_t i) { return fit_at(s, i).model; })
      .def("group",
           [](const FitSummary& s, std::size_t i) {
             py::dict g;  // column -> degrees, in grouping order (empty without groups)
             for (const auto& [column, value] : fit_at(s, i).group) g[py::str(column)] = value;
             return g;
           })
      .def("options", [](const FitSummary& s, std::size_t i) { return fit_at(s, i).options; })
      .def("parameter_names", [](const FitSummary& s, std::size_t i) { return fit_at(s, i).parameter_names; })
      .def("parameter_units", [](const FitSummary& s, std::size_t i) { return fit_at(s, i).parameter_units; })
      .def("fixed", [](const FitSummary& s, std::size_t i) { return fit_at(s, i).fixed; })
      .def("shared", [](const FitSummary& s, std::size_t i) { return fit_at(s, i).shared; })
      .def("parameters",
           [](const FitSummary& s, std::size_t i) { return per_parameter(fit_at(s, i), &WavelengthFit::parameters); })
      .def("standard_errors",
           [](const FitSummary& s, std::size_t i) {
             return per_parameter(fit_at(s, i), &WavelengthFit::standard_errors);
           })
      .def("correlation",
           [](const FitSummary& s, std::size_t i) {
             const FitResult& f = fit_at(s, i);
             const std::size_t p = f.parameter_names.size(), mw = f.wavelengths.size();
             Array out({mw, p, p});
             auto v = out.mutable_unchecked<3>();
             for (std::size_t w = 0; w < mw; ++w) {
               const std::vector<double>& c = f.wavelengths[w].correlation;
               for (std::size_t a = 0; a < p; ++a) {
                 for (std::size_t b = 0; b < p; ++b) {
                   v(w, a, b) = c.size() == p * p ? c[a * p + b] : std::numeric_limits<double>::quiet_NaN();
                 }
               }
             }
             return out;
           })
      .def("statistics", [](const FitSummary& s, std::size_t i) { return statistics(fit_at(s, i)); })
      .def("totals", [](const FitSummary& s, std::size_t i) { return totals(fit_at(s, i)); })
      .def("spectral_model",
           [](const FitSummary& s, std::size_t i) { return spectral_model_of(fit_at(s, i), s.models.at(i)); })
      .def(
          "file_content", [](const FitSummary& s) { return json_to_python(fit_file_json(s.fits, s.notes)); },
          "The fit file's content as Python objects (dicts, lists, numbers).")
      .def(
          "select",
          [](const FitSummary& s, const std::string& selection) {
            // The readers' rule (modelfile/fit_file_read.h select_fit) on the file this result writes.
            const nlohmann::json content = fit_file_json(s.fits, s.notes);
            return select_fit(JsonNode(content, "the fit result"), selection);
          },
          py::arg("selection"),
          "The index of the fit a selection (\"model,theta_i=40\") chooses, as `--fit` chooses in a fit file.")
      .def("table", &FitSummary::table, "The ranking table `roadbrdf fit` prints.")
      .def("warnings", &FitSummary::warnings, py::arg("where"))
      .def(
          "write", [](const FitSummary& s, const std::string& path) { write_fit_file(path, s.fits, s.notes); },
          py::arg("path"), "Write the fit file (JSON, atomically), as `roadbrdf fit -o` does.");

  m.def(
      "fit",
      [](const py::args& args, const py::kwargs& kwargs) {
        // The dataset: a roadbrdf.Dataset (its values) first, or its file (`data`, read with the
        // request's dataset-reading fields).
        std::optional<SpectralDataset> given;
        py::tuple rest = args;
        if (!args.empty() && py::hasattr(args[0], "brdf")) {
          const py::handle d = args[0];
          std::map<std::string, std::string> metadata;
          for (const auto& [key, value] : py::dict(d.attr("metadata"))) metadata[py::str(key)] = py::str(value);
          given = dataset_from_arrays(d.attr("angles").cast<DoubleArray>(), d.attr("wavelengths").cast<DoubleArray>(),
                                      d.attr("brdf").cast<DoubleArray>(), d.attr("sigma"), metadata,
                                      py::str(d.attr("convention")));
          rest = args[py::slice(1, static_cast<py::ssize_t>(args.size()), 1)];
        }
        const auto request = request_from_arguments<FitRequest>(py::args(rest), kwargs);
        request.validate();
        check_request_files(request);
        const SpectralDataset data = given ? std::move(*given) : read_fit_data(request);
        std::shared_ptr<FitSummary> summary;
        {
          SigintGuard interruptible;
          py::gil_scoped_release release;
          summary = std::make_shared<FitSummary>(run_fit(request, data));
        }
        write_fit_outputs(request, *summary, data);
        return summary;
      },
      request_docstring<FitRequest>(
          "Fit models to a measured spectral BRDF, as `roadbrdf fit` does: `data` is a roadbrdf.Dataset or its "
          "file.",
          "Returns the fit summary (roadbrdf.FitResult wraps it); `output` and `residuals` are written.")
          .c_str());
  // The request of `roadbrdf params` (its field table, fitting/params_table.cpp): the table as columns,
  // its text in the request's format, and the file `output` written as the command writes it.
  m.def(
      "params_table",
      [](const py::args& args, const py::kwargs& kwargs) {
        const auto request = request_from_arguments<ParamsRequest>(args, kwargs);
        const ParamsTable t = read_params_table(request);
        if (!request.output.empty()) write_params_output(request, t);
        py::dict out;
        out["notes"] = t.notes;
        out["units"] = py::dict();
        for (std::size_t k = 0; k < t.parameter_names.size(); ++k) {
          out["units"][py::str(t.parameter_names[k])] = t.parameter_units[k];
        }
        // The text only when asked for (a table of a few thousand rows takes as long to render as to read).
        if (kwargs.contains("format")) out["text"] = t.render(request.table_format());
        out["columns"] = t.csv_columns();
        out["data"] = params_columns(t);
        out["fits"] = params_fits(t);
        return out;
      },
      request_docstring<ParamsRequest>(
          "The fitted parameters of a fit file, as `roadbrdf params` prints them.",
          "Returns a dict: columns, data (the CSV cells by column as NumPy arrays: float64, bool for `converged`, "
          "object for text), text (in `format`, when `format` is given), notes, units, and fits: per fit shown, its "
          "model, group {column: "
          "degrees}, options, fixed (names) and bounds {parameter: (lower, upper)} of the model's metadata.")
          .c_str());
}

}  // namespace roadbrdf::python
