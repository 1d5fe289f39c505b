// Hooks for the bindings of the other parts of the library (datasets, fitting, albedo,
// photometry, mixing), each in its own bind_*.cpp file.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include <vector>

#include "roadbrdf/core/error.h"
#include "roadbrdf/core/range.h"
#include "roadbrdf/io/dataset.h"

namespace roadbrdf::python {

void bind_extensions(pybind11::module_& m);

// Ctrl-C during a long call (bind_interrupt.cpp): constructed with the GIL held, before the GIL is
// released for the work, and destroyed after it is taken back. While it lives on the main thread,
// SIGINT (and SIGTERM when Python handles it) requests the library's interrupt (core/progress.h): the
// work stops with Interrupted, and register_interrupted() raises what Python's handler raises
// (KeyboardInterrupt for Ctrl-C).
class SigintGuard {
 public:
  SigintGuard();
  ~SigintGuard();
  SigintGuard(const SigintGuard&) = delete;
  SigintGuard& operator=(const SigintGuard&) = delete;

 private:
  bool active_ = false;
};
void register_interrupted();
void bind_surface(pybind11::module_& m);        // bind_surface.cpp: virtual surfaces, render
void bind_marking(pybind11::module_& m);        // bind_marking.cpp: road markings, model export
void bind_lighting(pybind11::module_& m);       // bind_lighting.cpp: luminaires
void bind_lighting_calc(pybind11::module_& m);  // bind_lighting_calc.cpp: roadbrdf.lighting
void bind_output(pybind11::module_& m);         // bind_output.cpp: AtomicFile writes
void bind_requests(pybind11::module_& m);       // bind_output.cpp: request tables

using DoubleArray = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;

}  // namespace roadbrdf::python

// Every array argument of the bindings is a DoubleArray: whatever numpy turns into float64 (lists,
// integers, non-contiguous or other-endian arrays) is converted into a contiguous copy; anything
// else (text, objects, complex numbers, whose imaginary part numpy would silently drop) is a
// roadbrdf.InputError, as a bad value given to a command is, rather than pybind11's TypeError.
// This specialises pybind11's caster for exactly this array type (declared here, before any use,
// in the one header every binding file includes).
namespace pybind11::detail {
template <>
struct pyobject_caster<roadbrdf::python::DoubleArray> {
  using type = roadbrdf::python::DoubleArray;

  bool load(handle src, bool convert) {
    if (!convert && !type::check_(src)) return false;
    const bool complex_values =
        PyComplex_Check(src.ptr()) || (isinstance<array>(src) && reinterpret_borrow<array>(src).dtype().kind() == 'c');
    if (complex_values) throw roadbrdf::InputError("expected real numbers, got complex numbers");
    value = type::ensure(src);
    if (!value) {
      PyErr_Clear();
      throw roadbrdf::InputError("expected numbers (an array of real values), got " +
                                 std::string(pybind11::str(pybind11::type::handle_of(src).attr("__name__"))));
    }
    return true;
  }
  static handle cast(const handle& src, return_value_policy /*policy*/, handle /*parent*/) { return src.inc_ref(); }
  PYBIND11_TYPE_CASTER(type, handle_type_name<type>::name);
};
}  // namespace pybind11::detail

namespace roadbrdf::python {

// A dataset from the arrays of roadbrdf.Dataset (angles N x 4 in degrees, wavelengths, brdf N x M,
// sigma or None, metadata, convention "zenith"|"road"); validated. Throws InputError.
SpectralDataset dataset_from_arrays(const DoubleArray& angles, const DoubleArray& wavelengths, const DoubleArray& brdf,
                                    const pybind11::object& sigma, const std::map<std::string, std::string>& metadata,
                                    const std::string& convention);

// Values from a Python argument: None (empty), a number, a sequence of numbers or a string in the
// grammar of core/range.h, checked with `rules`; errors name `field` (the Python argument).
std::vector<double> values_argument(const pybind11::object& value, const std::string& field,
                                    const RangeRules& rules = {});
// Intervals [lower, upper] from None, "LOWER:UPPER", a (lower, upper) pair, or a list of those
// (parse_interval, core/range.h: the command line's grammar). Throws FieldError(field).
std::vector<std::pair<double, double>> intervals_argument(const pybind11::object& value, const std::string& field);
void bind_values(pybind11::module_& m);  // bind_values.cpp: parse_range, values, did_you_mean

// JSON (e.g. a fit file's content; nlohmann::json or ordered_json) as Python dicts (in the JSON's
// order), lists, numbers, strings, None (also for non-finite numbers, as the writers write them).
template <class Json>
inline pybind11::object json_to_python(const Json& j) {
  namespace py = pybind11;
  switch (j.type()) {
    case nlohmann::detail::value_t::null:
      return py::none();
    case nlohmann::detail::value_t::boolean:
      return py::bool_(j.template get<bool>());
    case nlohmann::detail::value_t::number_integer:
      return py::int_(j.template get<std::int64_t>());
    case nlohmann::detail::value_t::number_unsigned:
      return py::int_(j.template get<std::uint64_t>());
    case nlohmann::detail::value_t::number_float: {
      const double v = j.template get<double>();
      if (!std::isfinite(v)) return py::none();  // as in the file: JSON has no NaN, the writer writes null
      return py::float_(v);
    }
    case nlohmann::detail::value_t::string:
      return py::str(j.template get<std::string>());
    case nlohmann::detail::value_t::array: {
      py::list out;
      for (const auto& item : j) out.append(json_to_python(item));
      return py::object(std::move(out));
    }
    case nlohmann::detail::value_t::object: {
      py::dict out;
      for (const auto& [key, value] : j.items()) out[py::str(key)] = json_to_python(value);
      return py::object(std::move(out));
    }
    default:
      throw InputError("internal: JSON value of an unexpected type");
  }
}

}  // namespace roadbrdf::python
