// Python bindings of the virtual road surfaces and the virtual gonioreflectometer
// (src/roadbrdf/surface/): the same library calls as `roadbrdf surface` and `roadbrdf render`
// (src/roadbrdf/cli/cmd_surface.cpp), with the same validation of the render options.
// The public API is roadbrdf.surface / read_surface / flat_surface / gaussian_slope_surface /
// render / render_albedo and the class roadbrdf.Surface (python/roadbrdf/__init__.py).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "binding.h"
#include "request_kwargs.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/geometry.h"
#include "roadbrdf/models/registry.h"
#include "roadbrdf/models/spectral_model.h"
#include "roadbrdf/surface/generate.h"
#include "roadbrdf/surface/height_field.h"
#include "roadbrdf/surface/materials.h"
#include "roadbrdf/surface/render.h"
#include "roadbrdf/surface/render_request.h"
#include "roadbrdf/surface/render_task.h"
#include "roadbrdf/surface/surface_request.h"
#include "roadbrdf/surface/surface_task.h"

namespace py = pybind11;

namespace roadbrdf::python {

namespace {

using Field = surface::HeightField;
using FieldPtr = std::shared_ptr<Field>;

// Fit paths made absolute, so that a surface held in Python still renders after os.chdir.
FieldPtr keep(Field field) {
  for (auto& m : field.materials) {
    if (!m.fit_path.empty()) m.fit_path = std::filesystem::absolute(m.fit_path).lexically_normal().string();
  }
  return std::make_shared<Field>(std::move(field));
}

// A node or cell array of the field as an ny x nx numpy array (row j = y index, column i = x index).
template <typename T, typename Source>
py::array_t<T> grid_array(const Field& f, const std::vector<Source>& values) {
  py::array_t<T> out({static_cast<py::ssize_t>(f.ny), static_cast<py::ssize_t>(f.nx)});
  T* o = out.mutable_data();
  for (std::size_t k = 0; k < values.size(); ++k) o[k] = static_cast<T>(values[k]);
  return out;
}

// The render request of a Python call (its field table, surface/render_request.h): the keywords of
// the settings; the surface and the geometries are the call's own, so the fields naming the command's
// files are refused but for those in `allowed`.
surface::RenderRequest render_request(const py::kwargs& kwargs, std::initializer_list<const char*> allowed = {}) {
  for (const char* field : {"surface", "grid", "sun_zenith", "format", "output"}) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || std::string(a) == field;
    if (!ok && kwargs.contains(field)) {
      throw FieldError(field, "does not apply here: the surface and the directions are the call's own arguments");
    }
  }
  return request_from_arguments<surface::RenderRequest>(py::args(), kwargs);
}

}  // namespace

void bind_surface(py::module_& m) {
  py::class_<Field, FieldPtr>(m, "HeightField")
      .def_readonly("name", &Field::name)
      .def_readonly("description", &Field::description)
      .def_readonly("cell_size_mm", &Field::cell_size_mm)
      .def_readonly("nx", &Field::nx)
      .def_readonly("ny", &Field::ny)
      .def_property_readonly("heights", [](const Field& f) { return grid_array<double>(f, f.heights); })
      .def_property_readonly("material", [](const Field& f) { return grid_array<int>(f, f.material); })
      .def_property_readonly("materials",
                             [](const Field& f) {
                               py::list out;
                               for (const auto& spec : f.materials) out.append(json_to_python(spec.to_json()));
                               return out;
                             })
      .def("statistics",
           [](const Field& f) {
             surface::TextureStatistics s;
             {
               SigintGuard interruptible;
               py::gil_scoped_release release;
               s = surface::texture_statistics(f);
             }
             return json_to_python(s.to_json());
           })
      .def("write",
           [](const Field& f, const std::string& path) {
             py::gil_scoped_release release;
             const surface::TextureStatistics s = surface::texture_statistics(f);
             surface::write_surface(f, path, &s);
           })
      .def("write_preview", [](const Field& f, const std::string& path) { surface::write_preview_png(f, path); });

  m.def("read_surface", [](const std::string& path) { return keep(surface::read_surface(path)); });

  // `roadbrdf surface INPUT`: the surface of a request (its table, surface/surface_request.h) and, for
  // a sample of a formulation, the generator's report (None otherwise). The formulation is a file or
  // its content (a dict), its fits read from files or given as values by reference (`fits`, a dict:
  // the one keyword outside the table, as the command reads files). With `output`, the SURFACE file
  // (and `preview`) are written as the command writes them.
  m.def(
      "surface",
      [](const py::args& args, py::kwargs kwargs) {
        py::object fits = py::none();
        if (kwargs.contains("fits")) fits = kwargs.attr("pop")("fits");
        surface::SurfaceRequest request = request_from_arguments<surface::SurfaceRequest>(args, kwargs);
        request_detail::assign(request.fits, fits, "fits");
        surface::SurfaceResult result;
        {
          SigintGuard interruptible;
          py::gil_scoped_release release;
          result = surface::make_surface(request);
        }
        issue_warnings(result.diagnostics);
        return py::make_tuple(keep(std::move(result.field)), json_to_python(result.sample_report()));
      },
      request_docstring<surface::SurfaceRequest>(
          "A virtual road sample of a formulation, or a flat or Gaussian-slope surface of one material "
          "(`roadbrdf surface`). fits: fit files as values, {reference: fit JSON text}.",
          "Returns (surface handle, generator report or None).")
          .c_str());

  // `roadbrdf render SURFACE --grid`: angles [deg] as flat arrays of one length.
  m.def("render_surface", [](const Field& f, const DoubleArray& theta_i, const DoubleArray& phi_i,
                             const DoubleArray& theta_r, const DoubleArray& phi_r, const py::kwargs& kwargs) {
    const surface::RenderRequest request = render_request(kwargs);
    surface::render_settings(request);  // validated before the angles
    const py::ssize_t n = theta_i.size();
    if (phi_i.size() != n || theta_r.size() != n || phi_r.size() != n) {
      throw InputError("internal: render angle arrays of different sizes");
    }
    std::vector<Geometry> geometries;
    for (py::ssize_t k = 0; k < n; ++k) {
      try {
        geometries.push_back(
            geometry_from_degrees(theta_i.data()[k], phi_i.data()[k], theta_r.data()[k], phi_r.data()[k]));
      } catch (const InputError& e) {
        throw InputError("geometry " + std::to_string(k + 1) + ": " + e.what());
      }
    }
    surface::RenderResult result;
    {
      SigintGuard interruptible;
      py::gil_scoped_release release;
      result = surface::render_grid(f, "", geometries, AngleConvention::kZenithAzimuth, request);
    }
    issue_warnings(result.diagnostics);
    return json_to_python(result.to_json());
  });

  // `roadbrdf render SURFACE --albedo`.
  m.def("render_surface_albedo", [](const Field& f, const std::string& surface_name, const py::kwargs& kwargs) {
    const surface::RenderRequest request = render_request(kwargs, {"sun_zenith", "output"});
    surface::RenderAlbedoResult result;
    {
      SigintGuard interruptible;
      py::gil_scoped_release release;
      result = surface::render_surface_albedo(f, surface_name, request);
    }
    issue_warnings(result.diagnostics);
    return json_to_python(result.albedo.to_json());
  });
}

}  // namespace roadbrdf::python
