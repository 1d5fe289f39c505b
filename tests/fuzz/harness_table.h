// Every fuzz harness's entry point by name, the one list of harnesses: the build reads the names
// from the lines below (tests/fuzz/CMakeLists.txt) to make the ctest tests fuzz_corpus.<name> and the
// links <name>_fuzz of the libFuzzer program (fuzz_main.cpp); the replay program of normal builds
// (replay_main.cpp) runs the corpus of tests/fuzz/corpus/<name>/ through harnesses().at(name).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

#include "fuzz/dataset_mapped_harness.h"
#include "fuzz/installation_harnesses.h"
#include "fuzz/instrument_harnesses.h"
#include "fuzz/luminaire_harnesses.h"
#include "fuzz/openmaterial3d_harness.h"
#include "fuzz/parser_harnesses.h"

namespace roadbrdf::fuzz {

using Harness = int (*)(const std::uint8_t* data, std::size_t size);

inline const std::map<std::string, Harness>& harnesses() {
  static const std::map<std::string, Harness> table = {
      {"alta", alta_one_input},
      {"asd", asd_one_input},
      {"cross_sections", cross_sections_one_input},
      {"curet", curet_one_input},
      {"dataset", dataset_one_input},
      {"dataset_mapped", dataset_mapped_one_input},
      {"eulumdat", eulumdat_one_input},
      {"fit_file", fit_file_one_input},
      {"formulation", formulation_one_input},
      {"geometry", geometry_one_input},
      {"ies", ies_one_input},
      {"installation", installation_one_input},
      {"manifest", manifest_one_input},
      {"mix_file", mix_file_one_input},
      {"openmaterial3d", openmaterial3d_one_input},
      {"rtable_csv", rtable_csv_one_input},
      {"rtable_radiance", rtable_radiance_one_input},
      {"rtable_rtb", rtable_rtb_one_input},
      {"sed", sed_one_input},
      {"selection", selection_one_input},
      {"sig", sig_one_input},
      {"solar", solar_one_input},
      {"spectrum", spectrum_one_input},
      {"surface", surface_one_input},
      {"usgs", usgs_one_input},
  };
  return table;
}

}  // namespace roadbrdf::fuzz
