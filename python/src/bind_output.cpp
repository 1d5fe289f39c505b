// Python's outputs written by the library's AtomicFile (core/atomic_file.h): a temporary file in
// the target's folder, synced, given the mode of the file it replaces and renamed over it, links
// followed, devices written directly, the target untouched on any error. And the request tables
// (core/request_fields.h) as rows, so tests and docs can list every field of a request.
#include <pybind11/pybind11.h>

#include <string>
#include <variant>

#include "binding.h"
#include "roadbrdf/albedo/report.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/fitting/fit_request.h"
#include "roadbrdf/fitting/params_table.h"
#include "roadbrdf/io/calibrate_request.h"
#include "roadbrdf/io/check_request.h"
#include "roadbrdf/io/convert_request.h"
#include "roadbrdf/io/eval_request.h"
#include "roadbrdf/io/model_export.h"
#include "roadbrdf/io/resample_request.h"
#include "roadbrdf/io/simulate_request.h"
#include "roadbrdf/lighting/lighting_request.h"
#include "roadbrdf/lighting/luminaire_request.h"
#include "roadbrdf/mixing/calibration.h"
#include "roadbrdf/mixing/mix_request.h"
#include "roadbrdf/photometry/marking_request.h"
#include "roadbrdf/photometry/rtable_request.h"
#include "roadbrdf/surface/render_request.h"
#include "roadbrdf/surface/surface_request.h"

namespace py = pybind11;

namespace roadbrdf::python {

namespace {

void write_atomic(const std::string& path, const std::string& content) {
  AtomicFile out(path);
  out.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  out.commit();
}

// What a field holds, in the words of request_kwargs.h: the Python value it takes.
template <class Request>
std::string kind_of(const RequestField<Request>& field) {
  static const char* const kinds[] = {"number",
                                      "integer",
                                      "switch",
                                      "text",
                                      "optional number",
                                      "list of texts",
                                      "list of numbers",
                                      "dict of texts",
                                      "dict of numbers",
                                      "dict of intervals",
                                      "list of intervals",
                                      "file or value",
                                      "optional interval",
                                      "integer",
                                      "optional integer",
                                      "integer",
                                      "optional integer",
                                      "optional length"};
  return kinds[field.member.index()];
}

template <class Request>
py::list rows() {
  py::list out;
  for (const RequestField<Request>& field : Request::fields()) {
    py::dict row;
    row["name"] = std::string(field.name);
    row["flag"] = std::string(field.flag);
    row["long_flag"] = std::string(field.long_flag());
    row["unit"] = std::string(field.unit);
    row["help"] = std::string(field.help);
    row["kind"] = kind_of(field);
    row["file"] = field.file == FileRole::none ? "" : field.file == FileRole::input ? "input" : "output";
    row["required"] = field.required;
    row["positional"] = field.positional();
    out.append(row);
  }
  return out;
}

}  // namespace

void bind_output(py::module_& m) {
  m.def(
      "write_text_atomic", [](const std::string& path, const std::string& text) { write_atomic(path, text); },
      py::arg("path"), py::arg("text"), "Write `text` (UTF-8) to `path` with the library's AtomicFile.");
  m.def(
      "write_bytes_atomic",
      [](const std::string& path, const py::bytes& content) { write_atomic(path, std::string(content)); },
      py::arg("path"), py::arg("content"), "Write `content` (bytes) to `path` with the library's AtomicFile.");
}

void bind_requests(py::module_& m) {
  m.def(
      "request_fields",
      [](const std::string& command) -> py::list {
        if (command == "fit") return rows<FitRequest>();
        if (command == "mix") return rows<mixing::MixRequest>();
        if (command == "albedo") return rows<albedo::AlbedoRequest>();
        if (command == "rtable") return rows<photometry::RTableRequest>();
        if (command == "render") return rows<surface::RenderRequest>();
        if (command == "surface") return rows<surface::SurfaceRequest>();
        if (command == "luminaire") return rows<lighting::LuminaireRequest>();
        if (command == "lighting") return rows<lighting::LightingRequest>();
        if (command == "marking") return rows<photometry::MarkingRequest>();
        if (command == "export") return rows<ExportRequest>();
        if (command == "params") return rows<ParamsRequest>();
        if (command == "mix-calibrate") return rows<mixing::CrossSectionRequest>();
        if (command == "eval") return rows<EvalRequest>();
        if (command == "simulate") return rows<SimulateRequest>();
        if (command == "calibrate") return rows<CalibrateRequest>();
        if (command == "convert") return rows<ConvertRequest>();
        if (command == "check") return rows<CheckRequest>();
        if (command == "resample") return rows<ResampleRequest>();
        throw InputError("request_fields: no request table of '" + command + "'");
      },
      py::arg("command"),
      "The field table of a command's request: one dict per field (name, flag, long_flag, unit, help, kind, "
      "file, required, positional).");
}

}  // namespace roadbrdf::python
