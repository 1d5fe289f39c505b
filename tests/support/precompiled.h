// The precompiled header of every test program (tests/CMakeLists.txt): the third-party and standard
// headers most tests include, parsed once per build instead of once per test. Tests still include
// what they use; this header only makes it cheaper.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <fmt/format.h>
