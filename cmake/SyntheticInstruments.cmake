# roadbrdf's own synthetic instrument files (ASD, SED, SIG, panel reflectance, run manifests) are
# written from closed forms by tests/data/instruments/make_synthetic.py when the build is
# configured, not kept in the repository: binary .asd files in the tree were too easily taken for
# copies of real instrument data, which is never copied here (../shared/real-data).
#   ROADBRDF_INSTRUMENT_FILES_DIR  BUILD/tests/data/instruments (the tests' input files)
#   ROADBRDF_GENERATED_CORPUS_DIR  BUILD/tests/fuzz/corpus (seeds of the asd, sed, sig and manifest
#                                  fuzz harnesses)
# Included by tests/ and tests/fuzz/: the variables are set in each, the files written once.
set(ROADBRDF_INSTRUMENT_FILES_DIR ${CMAKE_BINARY_DIR}/tests/data/instruments)
set(ROADBRDF_GENERATED_CORPUS_DIR ${CMAKE_BINARY_DIR}/tests/fuzz/corpus)
get_property(synthetic_done GLOBAL PROPERTY ROADBRDF_SYNTHETIC_INSTRUMENTS_WRITTEN)
if(synthetic_done)
  return()
endif()
set_property(GLOBAL PROPERTY ROADBRDF_SYNTHETIC_INSTRUMENTS_WRITTEN TRUE)
find_package(Python3 COMPONENTS Interpreter REQUIRED)
set(synthetic_script ${CMAKE_SOURCE_DIR}/tests/data/instruments/make_synthetic.py)
execute_process(COMMAND ${Python3_EXECUTABLE} ${synthetic_script} ${ROADBRDF_INSTRUMENT_FILES_DIR}
                        ${ROADBRDF_GENERATED_CORPUS_DIR}
                RESULT_VARIABLE synthetic_status ERROR_VARIABLE synthetic_error)
if(NOT synthetic_status EQUAL 0)
  message(FATAL_ERROR "make_synthetic.py failed (${synthetic_status}): ${synthetic_error}")
endif()
set_property(DIRECTORY ${CMAKE_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${synthetic_script})
