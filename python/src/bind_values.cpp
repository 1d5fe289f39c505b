// Lists of numbers from Python: a string in the grammar of core/range.h ("400:700:10,800"), a
// number, or a sequence of numbers; the same checks as on the command line.
#include <fmt/core.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>

#include "binding.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/nearest_name.h"
#include "roadbrdf/core/range.h"

namespace py = pybind11;

namespace roadbrdf::python {

std::vector<double> values_argument(const py::object& value, const std::string& field, const RangeRules& rules) {
  if (value.is_none()) return {};
  if (py::isinstance<py::str>(value)) return parse_range_list(value.cast<std::string>(), field, rules);
  std::vector<double> values;
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) {
    values.push_back(value.cast<double>());
  } else {
    const DoubleArray array = DoubleArray::ensure(value);
    if (!array || array.ndim() > 1)
      throw FieldError(field, "expected a number, a list of numbers or a string such as '0:60:30'");
    values.assign(array.data(), array.data() + array.size());
  }
  check_range_values(values, field, rules);
  return values;
}

std::vector<std::pair<double, double>> intervals_argument(const py::object& value, const std::string& field) {
  std::vector<std::pair<double, double>> out;
  if (value.is_none()) return out;
  auto one = [&field](const py::handle& item) -> std::pair<double, double> {
    if (py::isinstance<py::str>(item)) return parse_interval(item.cast<std::string>(), field);
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(item);
    if (!py::isinstance<py::sequence>(item) || py::len(pair) != 2) {
      throw FieldError(field, "expected 'LOWER:UPPER' or a (lower, upper) pair");
    }
    const double lower = pair[0].cast<double>(), upper = pair[1].cast<double>();
    return parse_interval(fmt::format("{}:{}", lower, upper), field);
  };
  if (py::isinstance<py::str>(value)) return {one(value)};
  if (!py::isinstance<py::sequence>(value)) throw FieldError(field, "expected 'LOWER:UPPER' or a list of those");
  const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
  // One (lower, upper) pair of numbers, or a list of intervals.
  if (py::len(items) == 2 && !py::isinstance<py::str>(items[0]) && !py::isinstance<py::sequence>(items[0])) {
    return {one(value)};
  }
  for (const auto& item : items) out.push_back(one(item));
  return out;
}

void bind_values(py::module_& m) {
  m.def(
      "parse_range",
      [](const std::string& text, const std::string& field, bool wavelengths) {
        return parse_range_list(text, field, wavelengths ? wavelength_rules() : RangeRules{});
      },
      py::arg("text"), py::arg("field") = "values", py::arg("wavelengths") = false,
      "Values of 'D', 'D1,D2,...', 'START:STOP:STEP' (both ends included) or a mix (core/range.h).");
  m.def("did_you_mean", &did_you_mean, py::arg("word"), py::arg("candidates"),
        "\" (did you mean 'NAME'?)\" for the candidate nearest to a mistyped word, or \"\".");
  m.def(
      "values",
      [](const py::object& value, const std::string& field, bool wavelengths) {
        return values_argument(value, field, wavelengths ? wavelength_rules() : RangeRules{});
      },
      py::arg("value"), py::arg("field"), py::arg("wavelengths") = false,
      "A list of floats from None, a number, a sequence or a range string, checked as on the command line.");
}

}  // namespace roadbrdf::python
