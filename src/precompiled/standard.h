// Precompiled header of the library modules that do not use Ceres (core, spectra, formulation): the
// standard and third-party headers most of their sources include, parsed once per build instead of
// once per source (cmake/Precompiled.cmake). No source includes this file; every source still
// includes what it uses, so a build without precompiled headers (ROADBRDF_PRECOMPILE_HEADERS=OFF,
// as make tidy uses) compiles the same code.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/core.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>
