// libFuzzer entry points of the instrument-file parsers (io/asd.h, io/sed.h, io/sig.h,
// io/manifest.h), as inline functions so that the fuzz programs (harness_table.h) and the
// always-run replay test (tests/io/instrument_fuzz_replay_test.cpp)
// exercise the same code. Rejecting an input with InputError/FileError is the expected outcome;
// any other exception, a crash or a sanitizer report is a bug.
//
// Built and run like every harness of tests/fuzz (tests/fuzz/README.md).
// Seed corpora: BUILD/tests/fuzz/corpus/<parser>/, roadbrdf's own synthetic files, written when the
// build is configured (cmake/SyntheticInstruments.cmake); no third-party file.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "roadbrdf/core/error.h"
#include "roadbrdf/io/asd.h"
#include "roadbrdf/io/manifest.h"
#include "roadbrdf/io/sed.h"
#include "roadbrdf/io/sig.h"

namespace roadbrdf::fuzz {

inline std::string_view view(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

inline int asd_one_input(const std::uint8_t* data, std::size_t size) {
  try {
    parse_asd(view(data, size), "fuzz.asd");
  } catch (const InputError&) {
  }
  return 0;
}

inline int sed_one_input(const std::uint8_t* data, std::size_t size) {
  try {
    parse_sed(view(data, size), "fuzz.sed");
  } catch (const InputError&) {
  }
  return 0;
}

inline int sig_one_input(const std::uint8_t* data, std::size_t size) {
  for (OverlapRule rule : {OverlapRule::kUpper, OverlapRule::kLower, OverlapRule::kError}) {
    try {
      parse_sig(view(data, size), "fuzz.sig", rule);
    } catch (const InputError&) {
    }
  }
  return 0;
}

// The manifest parser reads a file: the input is written to a per-process temporary file. Only
// the manifest is parsed; the instrument files it names are not opened (a fuzzed name could be a
// device that never ends).
inline int manifest_one_input(const std::uint8_t* data, std::size_t size) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("roadbrdf-fuzz-manifest-" + std::to_string(::getpid()) + ".csv"))
          .string();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    read_manifest(path);
  } catch (const InputError&) {
  }
  std::filesystem::remove(path);
  return 0;
}

}  // namespace roadbrdf::fuzz
