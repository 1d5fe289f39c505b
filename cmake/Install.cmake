# Installation: the program, the library (static, one archive per module) with its headers and a
# CMake package (find_package(roadbrdf) -> roadbrdf::roadbrdf and roadbrdf::<module>), the bundled
# data, the man page and the Python package (python/CMakeLists.txt); `cpack -G DEB` makes a .deb.
include(CMakePackageConfigHelpers)

install(TARGETS roadbrdf RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT program)
install(TARGETS ${ROADBRDF_MODULES} roadbrdf_library EXPORT roadbrdfTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/src/roadbrdf/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/roadbrdf
        COMPONENT development FILES_MATCHING PATTERN "*.h" PATTERN "cli" EXCLUDE)
install(EXPORT roadbrdfTargets NAMESPACE roadbrdf:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/roadbrdf
        COMPONENT development)
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/roadbrdfConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/roadbrdfConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/roadbrdf
                              PATH_VARS ROADBRDF_INSTALL_DATADIR)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/roadbrdfConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/roadbrdfConfig.cmake ${CMAKE_BINARY_DIR}/roadbrdfConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/roadbrdf COMPONENT development)

install(DIRECTORY ${CMAKE_SOURCE_DIR}/data/ DESTINATION ${ROADBRDF_INSTALL_DATADIR} COMPONENT program)

# Man page, generated from the program's own --help texts.
if(PYTHON_EXECUTABLE)
  set(Python3_EXECUTABLE ${PYTHON_EXECUTABLE})
endif()
find_package(Python3 COMPONENTS Interpreter REQUIRED)
# A sanitized program hands `plot` and `study` to python3 (cli/python_module.h), which loads the
# sanitized extension: the ASan runtime must then be preloaded, as for the Python tests.
set(manpage_environment "")
if(ROADBRDF_ASAN_RUNTIME)
  set(manpage_environment ${CMAKE_COMMAND} -E env LD_PRELOAD=${ROADBRDF_ASAN_RUNTIME} ASAN_OPTIONS=detect_leaks=0)
endif()
add_custom_command(OUTPUT ${CMAKE_BINARY_DIR}/roadbrdf.1
                   COMMAND ${manpage_environment} ${Python3_EXECUTABLE} ${CMAKE_SOURCE_DIR}/scripts/make_manpage.py
                           $<TARGET_FILE:roadbrdf>
                           ${PROJECT_VERSION} ${CMAKE_BINARY_DIR}/roadbrdf.1
                   DEPENDS roadbrdf ${CMAKE_SOURCE_DIR}/scripts/make_manpage.py)
# The page includes `roadbrdf study --help` and `report --help`, which the Python package answers: it
# is part of every build that builds the package, and a target to build on request in one that does
# not (the fuzzing build, -DROADBRDF_BUILD_PYTHON=OFF), where it would fail.
if(ROADBRDF_BUILD_PYTHON)
  set(manpage_in_all ALL)
else()
  set(manpage_in_all "")
endif()
add_custom_target(roadbrdf_manpage ${manpage_in_all} DEPENDS ${CMAKE_BINARY_DIR}/roadbrdf.1)
install(FILES ${CMAKE_BINARY_DIR}/roadbrdf.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT program OPTIONAL)

# The model reference, generated from the models' metadata (`roadbrdf models --markdown`) with every
# build of the program: build/docs/models.md, installed as the reference. docs/models.md is the
# same text committed for readers of the repository (the README links it); the test
# CliModels.MarkdownReferenceIsUpToDate fails when the two differ, and the target
# update_models_reference (`make docs`) copies the generated file over it.
set(models_reference ${CMAKE_BINARY_DIR}/docs/models.md)
add_custom_command(OUTPUT ${models_reference}
                   COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_BINARY_DIR}/docs
                   COMMAND ${CMAKE_COMMAND} -DOUTPUT=${models_reference} -P
                           ${CMAKE_SOURCE_DIR}/cmake/WriteCommandOutput.cmake -- $<TARGET_FILE:roadbrdf> models --markdown
                   DEPENDS roadbrdf ${CMAKE_SOURCE_DIR}/cmake/WriteCommandOutput.cmake
                   COMMENT "Generating docs/models.md from the models' metadata" VERBATIM)
add_custom_target(roadbrdf_models_reference ALL DEPENDS ${models_reference})
add_custom_target(update_models_reference
                  COMMAND ${CMAKE_COMMAND} -E copy_if_different ${models_reference} ${CMAKE_SOURCE_DIR}/docs/models.md
                  DEPENDS ${models_reference} VERBATIM)
install(FILES ${models_reference} DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT program)

# ---- Debian package (cpack -G DEB) -------------------------------------------------------------
set(CPACK_PACKAGE_NAME roadbrdf)
set(CPACK_PACKAGE_VENDOR "roadbrdf developers")
set(CPACK_PACKAGE_CONTACT "roadbrdf developers <roadbrdf@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# Shared-library dependencies come from dpkg-shlibdeps; the Python side needs Debian's interpreter
# and the packages the roadbrdf module imports.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, python3-numpy, python3-matplotlib")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "python3-pandas, python3-distributed")
include(CPack)
