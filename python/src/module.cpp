// pybind11 module `roadbrdf._roadbrdf`: the C++ core exposed to Python. The public, documented API
// is the pure-Python package `roadbrdf` (python/roadbrdf/__init__.py), which wraps these functions.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "binding.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/data_path.h"
#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/formulation/formulation.h"
#include "roadbrdf/io/manifest.h"
#include "roadbrdf/modelfile/model_source.h"
#include "roadbrdf/models/description_json.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/models/spectral_model.h"

namespace py = pybind11;
using namespace roadbrdf;

namespace {

// Metadata as a Python dict, through the same JSON as `roadbrdf models --json`.
py::object description_dict(const ModelDescription& md) {
  return py::module_::import("json").attr("loads")(roadbrdf::dump_json(description_to_json(md)));
}

using Array = roadbrdf::python::DoubleArray;

// Evaluate a model at flattened, already-broadcast angles in degrees (n values each), with the
// parameter set of element k given by parameters_at(k). One C++ loop without the GIL, no Python per
// element. `extra` names the other input and its required length, for the error.
template <typename ParametersAt>
Array evaluate_at_angles(const Model& model, const Array& theta_i, const Array& phi_i, const Array& theta_r,
                         const Array& phi_r, py::ssize_t extra_size, py::ssize_t extra_per_element, const char* extra,
                         ParametersAt&& parameters_at) {
  const py::ssize_t n = theta_i.size();
  if (phi_i.size() != n || theta_r.size() != n || phi_r.size() != n || extra_size != n * extra_per_element) {
    throw InputError(std::string("evaluate_flat: the angle arrays need one length and the ") + extra);
  }
  Array out(n);
  const double* ti = theta_i.data();
  const double* pi = phi_i.data();
  const double* tr = theta_r.data();
  const double* pr = phi_r.data();
  double* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t k = 0; k < n; ++k) {
      o[k] = model.evaluate(parameters_at(k), geometry_from_degrees(ti[k], pi[k], tr[k], pr[k]));
    }
  }
  return out;
}

// A model at a parameter matrix n x P (row k for element k).
Array evaluate_flat(const Model& model, const Array& theta_i, const Array& phi_i, const Array& theta_r,
                    const Array& phi_r, const Array& parameters) {
  const auto P = static_cast<py::ssize_t>(model.parameter_count());
  const double* p = parameters.data();
  return evaluate_at_angles(model, theta_i, phi_i, theta_r, phi_r, parameters.size(), P,
                            "parameters that length x parameter count", [p, P](py::ssize_t k) { return p + k * P; });
}

// A spectral model at wavelengths in nm (one per element); the parameters are interpolated once per
// run of equal wavelengths.
Array evaluate_spectral_flat(const SpectralModel& model, const Array& theta_i, const Array& phi_i, const Array& theta_r,
                             const Array& phi_r, const Array& wavelength) {
  const double* wl = wavelength.data();
  double last = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> p;
  return evaluate_at_angles(model.model(), theta_i, phi_i, theta_r, phi_r, wavelength.size(), 1,
                            "wavelengths that length", [&](py::ssize_t k) {
                              if (!(wl[k] == last)) {
                                p = model.parameters_at(wl[k]);
                                last = wl[k];
                              }
                              return p.data();
                            });
}

}  // namespace

PYBIND11_MODULE(_roadbrdf, m) {
  m.doc() = "roadbrdf C++ core (use the `roadbrdf` package instead of this module)";
  // Warnings of readers called without a sink of their own (core/diagnostics.h) become Python warnings;
  // a reader may run while the GIL is released, so the sink takes it.
  set_front_end_warning_sink([](const std::string& message) {
    const py::gil_scoped_acquire gil;
    py::module_::import("roadbrdf.core").attr("warn_at_caller")(message);
  });

  // InputError and FileError become roadbrdf.InputError (a ValueError) with the CLI's message.
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  // pybind11's translator type is void (*)(std::exception_ptr): the pointer is taken by value.
  py::register_exception_translator([](std::exception_ptr p) {  // NOLINT(performance-unnecessary-value-param)
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      input_error(e.what());
    }
  });

  m.def("model_names", &model_names, "Names of the single (non-composite) models.");
  m.def(
      "model_aliases",
      [] {
        py::list out;
        for (const auto& a : model_aliases()) out.append(python::json_to_python(alias_to_json(a)));
        return out;
      },
      "Other names of models with some options fixed (e.g. cook-torrance).");
  m.def("data_directory", &data_directory, "Folder of the bundled data tables (share/roadbrdf/data).");
  m.attr("__version__") = version();

  // The check every command makes before it works (core/atomic_file.h): inputs and outputs as
  // (role, path) pairs.
  m.def("check_distinct_files", [](const std::vector<std::pair<std::string, std::string>>& inputs,
                                   const std::vector<std::pair<std::string, std::string>>& outputs) {
    std::vector<FileArgument> in, out;
    for (const auto& [role, path] : inputs) in.push_back({role, path});
    for (const auto& [role, path] : outputs) out.push_back({role, path});
    check_distinct_files(in, out);
  });
  // The files a formulation or a run manifest refers to, as (role, path) pairs for check_distinct_files.
  auto pairs = [](const std::vector<FileArgument>& files) {
    std::vector<std::pair<std::string, std::string>> out;
    for (const FileArgument& f : files) out.emplace_back(f.role, f.path);
    return out;
  };
  m.def(
      "formulation_input_files",
      [pairs](const std::string& path) { return pairs(formulation_input_files(read_formulation(path, false))); },
      py::arg("path"), "Every fit file a formulation refers to, as (role, path) pairs.");
  m.def(
      "manifest_input_files",
      [pairs](const std::string& path) { return pairs(manifest_input_files(read_manifest(path))); }, py::arg("path"),
      "Every instrument file a run manifest lists, as (role, path) pairs.");

  py::class_<Model, std::shared_ptr<Model>>(m, "Model")
      .def_property_readonly("name", &Model::name)
      .def_property_readonly("description", [](const Model& model) { return description_dict(model.description()); })
      .def_property_readonly("parameter_names",
                             [](const Model& model) {
                               std::vector<std::string> names;
                               for (const auto& p : model.description().parameters) names.push_back(p.name);
                               return names;
                             })
      .def("evaluate_flat", &evaluate_flat)
      .def("check_parameters",
           [](const Model& model, const std::vector<double>& values) { check_parameters(model.description(), values); })
      .def("delta_reflectance", [](const Model& model, const std::vector<double>& p, double cos_theta_i) {
        check_parameters(model.description(), p);  // the model reads parameter_count() values
        if (!(cos_theta_i >= 0.0 && cos_theta_i <= 1.0)) throw InputError("cos_theta_i must be in [0, 1]");
        return model.delta_reflectance(p.data(), cos_theta_i);
      });

  m.def(
      "make_model",
      [](const std::string& name, const OptionSet& options) {
        return std::shared_ptr<Model>(make_model(name, options));
      },
      py::arg("name"), py::arg("options") = OptionSet{});

  py::class_<SpectralModel>(m, "SpectralModel")
      .def_property_readonly("model",
                             [](const SpectralModel& s) { return std::const_pointer_cast<Model>(s.model_ptr()); })
      .def_property_readonly("wavelengths", &SpectralModel::wavelengths)
      .def_property_readonly("is_spectral", &SpectralModel::is_spectral)
      .def("parameters_at", &SpectralModel::parameters_at)
      .def("evaluate_flat", &evaluate_spectral_flat);
  m.def("read_fit_file", &read_fit_file, py::arg("path"), py::arg("model") = "");
  m.def("parse_fit_file", &parse_fit_file, py::arg("json_text"), py::arg("name"), py::arg("model") = "");
  m.def("read_fit_file_models", &read_fit_file_models, py::arg("path"), py::arg("models"));
  // The one resolver of a model argument (modelfile/model_source.h): (SpectralModel, kind, entry),
  // kind "fit", "mix" or "model", entry the fit or mixing method chosen or the model's name.
  m.def(
      "resolve_model",
      [](const std::string& source, const std::vector<std::string>& parameters, const std::vector<std::string>& options,
         const std::string& fit) {
        ResolvedModel resolved = resolve_model(source, parameters, options, fit);
        return py::make_tuple(std::move(resolved.model), resolved.kind, resolved.entry);
      },
      py::arg("source"), py::arg("parameters") = std::vector<std::string>{},
      py::arg("options") = std::vector<std::string>{}, py::arg("fit") = "");
  // A plain model with one parameter set, as the wavelength-independent spectral model the
  // command line makes of `MODEL -p ...`.
  m.def(
      "constant_spectral_model",
      [](const std::shared_ptr<Model>& model, const std::vector<double>& parameters) {
        check_parameters(model->description(), parameters);
        return SpectralModel(model, parameters);
      },
      py::arg("model"), py::arg("parameters"));

  m.def("road_to_zenith_azimuth", [](double gamma, double alpha, double beta, double delta) {
    const Geometry g = geometry_from_road_angles({gamma, alpha, beta, delta});
    return py::make_tuple(rad_to_deg(g.theta_i), rad_to_deg(g.phi_i), rad_to_deg(g.theta_r), rad_to_deg(g.phi_r));
  });

  roadbrdf::python::register_interrupted();
  roadbrdf::python::bind_extensions(m);
  roadbrdf::python::bind_surface(m);
  roadbrdf::python::bind_marking(m);
  roadbrdf::python::bind_lighting(m);
  roadbrdf::python::bind_lighting_calc(m);
  roadbrdf::python::bind_output(m);
  roadbrdf::python::bind_requests(m);
}
