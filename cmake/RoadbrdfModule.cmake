# One static library per folder of src/roadbrdf (roadbrdf_<folder>, exported as roadbrdf::<folder>).
#
# The layering is enforced by the include path: a folder's headers are reachable only through
# build/include/<folder>/roadbrdf/<folder> (a link to src/roadbrdf/<folder>), and a target sees only
# its own staged folder and those of the modules it depends on. Including a header of a module that
# is not a declared dependency therefore fails to compile.

set(ROADBRDF_MODULES "")

# Stage src/roadbrdf/<folder> as build/include/<folder>/roadbrdf/<folder>.
function(roadbrdf_stage_headers folder)
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/include/${folder}/roadbrdf)
  file(CREATE_LINK ${CMAKE_SOURCE_DIR}/src/roadbrdf/${folder} ${CMAKE_BINARY_DIR}/include/${folder}/roadbrdf/${folder}
       SYMBOLIC)
endfunction()

# roadbrdf_module(<folder> DEPENDS <module folders and external targets>...)
function(roadbrdf_module folder)
  cmake_parse_arguments(ARG "" "" "DEPENDS" ${ARGN})
  roadbrdf_stage_headers(${folder})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/roadbrdf/${folder}/*.cpp)
  set(target roadbrdf_${folder})
  add_library(${target} STATIC ${sources})
  add_library(roadbrdf::${folder} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${folder})
  # The headers are C++20 (concepts): a project that links a module compiles its own sources as C++20
  # at least, whatever its CMAKE_CXX_STANDARD (exported with the targets, as Ceres exports its standard).
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${CMAKE_BINARY_DIR}/include/${folder}>
                                              $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  foreach(dep ${ARG_DEPENDS})
    if(TARGET roadbrdf_${dep})
      target_link_libraries(${target} PUBLIC roadbrdf_${dep})
    else()
      target_link_libraries(${target} PUBLIC ${dep})
    endif()
  endforeach()
  set(ROADBRDF_MODULES ${ROADBRDF_MODULES} ${target} PARENT_SCOPE)
endfunction()
