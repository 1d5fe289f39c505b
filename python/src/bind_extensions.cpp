#include "binding.h"

namespace roadbrdf::python {

// Each part of the library adds its bindings here as it lands.
void bind_extensions(pybind11::module_& m) { (void)m; }

}  // namespace roadbrdf::python
