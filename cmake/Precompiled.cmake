# Precompiled headers of the library, the program and the Python extension (src/precompiled/).
#
# Parsing the standard, Eigen, Ceres and nlohmann-json headers is most of the compile time of a
# library source (CI builds everything from scratch). Each group of targets compiled with the same
# flags and definitions shares one precompiled header, made once by a carrier target that links the
# same dependencies: GCC and clang refuse (or, for GCC, silently ignore) a precompiled header made
# with other definitions or code-generation flags.
#   standard: core, spectra, formulation (no Ceres: its definitions would differ)
#   ceres:    the modules that depend on models (Ceres' glog definitions)
#   the program and the Python extension have their own (executable and module flags).
# Off for make tidy: clang-tidy cannot read GCC's precompiled headers.
option(ROADBRDF_PRECOMPILE_HEADERS "Precompile the heavy third-party headers (faster builds)" ON)

set(ROADBRDF_PRECOMPILED_DIR ${CMAKE_SOURCE_DIR}/src/precompiled)

# roadbrdf_precompiled_carrier(<name> <header> <link dependencies>...): an object library that
# compiles the precompiled header <header> of src/precompiled/.
function(roadbrdf_precompiled_carrier name header)
  if(NOT ROADBRDF_PRECOMPILE_HEADERS)
    return()
  endif()
  add_library(${name} OBJECT ${ROADBRDF_PRECOMPILED_DIR}/carrier.cpp)
  target_link_libraries(${name} PRIVATE ${ARGN})
  target_precompile_headers(${name} PRIVATE ${ROADBRDF_PRECOMPILED_DIR}/${header})
endfunction()

# roadbrdf_use_precompiled(<target> <carrier>)
function(roadbrdf_use_precompiled target carrier)
  if(ROADBRDF_PRECOMPILE_HEADERS)
    target_precompile_headers(${target} REUSE_FROM ${carrier})
  endif()
endfunction()

# roadbrdf_own_precompiled(<target> <header>): a precompiled header made for <target> alone.
function(roadbrdf_own_precompiled target header)
  if(ROADBRDF_PRECOMPILE_HEADERS)
    target_precompile_headers(${target} PRIVATE ${ROADBRDF_PRECOMPILED_DIR}/${header})
  endif()
endfunction()
