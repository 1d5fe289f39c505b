// Hooks for the bindings of the other parts of the library (datasets, fitting, albedo,
// photometry, mixing), each in its own bind_*.cpp file.
#pragma once

#include <pybind11/pybind11.h>

namespace roadbrdf::python {

void bind_extensions(pybind11::module_& m);

}  // namespace roadbrdf::python
