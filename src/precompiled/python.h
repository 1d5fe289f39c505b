// Precompiled header of the Python extension (python/src): pybind11's headers, the slowest part of
// every binding source, with the library's. The extension is compiled with its own flags (hidden
// visibility), so it has its own precompiled header.
#pragma once

#include "ceres.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
