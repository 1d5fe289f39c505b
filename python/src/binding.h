// Hooks for the bindings of the other parts of the library (datasets, fitting, albedo,
// photometry, mixing), each in its own bind_*.cpp file.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <map>
#include <string>

#include "roadbrdf/io/dataset.h"

namespace roadbrdf::python {

void bind_extensions(pybind11::module_& m);
void bind_surface(pybind11::module_& m);  // bind_surface.cpp: virtual surfaces, render

using DoubleArray = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;

// A dataset from the arrays of roadbrdf.Dataset (angles N x 4 in degrees, wavelengths, brdf N x M,
// sigma or None, metadata, convention "zenith"|"road"); validated. Throws InputError.
SpectralDataset dataset_from_arrays(const DoubleArray& angles, const DoubleArray& wavelengths,
                                    const DoubleArray& brdf, const pybind11::object& sigma,
                                    const std::map<std::string, std::string>& metadata,
                                    const std::string& convention);

}  // namespace roadbrdf::python
