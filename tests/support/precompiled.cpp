// The program that carries the tests' precompiled header (support/precompiled.h); it defines no test
// (GTest::gtest_main gives it its main).
#include "support/precompiled.h"
