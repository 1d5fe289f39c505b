// Precompiled header of the library modules that depend on the models (and so on Ceres' Jet type):
// models, io, fitting, albedo, photometry, mixing, surface. Ceres' headers (with Eigen's dense
// module) are the most expensive part of those sources; see standard.h for the rules.
#pragma once

#include "standard.h"

#include <ceres/ceres.h>
#include <ceres/jet.h>
#include <Eigen/Dense>
