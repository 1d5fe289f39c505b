#include "binding.h"

namespace roadbrdf::python {

void bind_io(pybind11::module_& m);
void bind_photometry(pybind11::module_& m);
void bind_fitting(pybind11::module_& m);
void bind_mixing(pybind11::module_& m);
void bind_albedo(pybind11::module_& m);

// Each part of the library adds its bindings here.
void bind_extensions(pybind11::module_& m) {
  bind_io(m);
  bind_photometry(m);
  bind_fitting(m);
  bind_mixing(m);
  bind_albedo(m);
  bind_values(m);
}

}  // namespace roadbrdf::python
