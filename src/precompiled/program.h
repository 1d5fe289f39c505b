// Precompiled header of the command-line program (src/roadbrdf/cli): the library's headers of
// ceres.h and CLI11, which every command file includes. A program is compiled position-independent
// as an executable, not as a library, so it cannot share the library modules' precompiled header.
#pragma once

#include "ceres.h"

#include <CLI/CLI.hpp>
#include <iostream>
