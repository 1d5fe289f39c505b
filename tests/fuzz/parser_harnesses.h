// libFuzzer entry points of the file parsers (datasets, geometry tables, CUReT, ALTA, formulations,
// fit and MIX files, r-tables, spectrum files and solar spectra, surfaces, USGS splib07a spectra), as inline functions
// listed by name in harness_table.h. Rejecting an input with InputError or
// FileError is the expected outcome; any other exception, a crash or a sanitizer report is a bug.
//
// Parsers that read a path get the input in a per-process scratch file. Warnings are swallowed.
// Built two ways (tests/fuzz/CMakeLists.txt): with -DROADBRDF_FUZZ=ON as libFuzzer programs
// (build-fuzz/tests/fuzz/<name>_fuzz), and in every normal build linked with replay_main.cpp as
// the ctest test fuzz_corpus.<name>, which runs each file of tests/fuzz/corpus/<name>/.
#pragma once

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "roadbrdf/albedo/solar.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/fitting/fit_file.h"
#include "roadbrdf/fitting/params_table.h"
#include "roadbrdf/formulation/formulation.h"
#include "roadbrdf/io/alta.h"
#include "roadbrdf/io/curet.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/geometry_file.h"
#include "roadbrdf/io/geometry_selection.h"
#include "roadbrdf/io/usgs.h"
#include "roadbrdf/mixing/calibration.h"
#include "roadbrdf/mixing/mix_file.h"
#include "roadbrdf/modelfile/model_source.h"
#include "roadbrdf/photometry/rtable_io.h"
#include "roadbrdf/spectra/spectrum_file.h"
#include "roadbrdf/surface/height_field.h"

namespace roadbrdf::fuzz {

inline std::string_view bytes(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// A file holding `content`, removed when it goes out of scope.
class ScratchFile {
 public:
  ScratchFile(const std::string& name, std::string_view content)
      : path_((std::filesystem::temp_directory_path() / ("roadbrdf-fuzz-" + std::to_string(::getpid()) + "-" + name))
                  .string()) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  }
  ~ScratchFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Runs `parse`; an InputError (FileError included) is a correct refusal.
template <class Parse>
int refusing(Parse parse) {
  try {
    parse();
  } catch (const InputError&) {
  }
  return 0;
}

inline void quiet(const std::string&) {}

inline int dataset_one_input(const std::uint8_t* data, std::size_t size) {
  const ScratchFile file("dataset.csv", bytes(data, size));
  for (bool average : {false, true}) {
    DatasetReadOptions o;
    o.average_duplicates = average;
    o.allow_missing = average;
    o.warn = quiet;
    refusing([&] { read_dataset(file.path(), o); });
  }
  return 0;
}

inline int geometry_one_input(const std::uint8_t* data, std::size_t size) {
  const ScratchFile file("geometry.csv", bytes(data, size));
  return refusing([&] { read_geometry_file(file.path()); });
}

// CUReT needs two files: the input is the geometry table, a NUL byte, then abrdf.dat (without a
// NUL, a fixed two-geometry table is used). The first sample listed is read.
inline int curet_one_input(const std::uint8_t* data, std::size_t size) {
  const std::string_view all = bytes(data, size);
  const auto nul = all.find('\0');
  const std::string_view table_text =
      nul == std::string_view::npos ? std::string_view("1 0.1 0.2 0.3 0.4\n2 0.5 0.6 0.7 0.8\n") : all.substr(0, nul);
  const std::string_view abrdf_text = nul == std::string_view::npos ? all : all.substr(nul + 1);
  const ScratchFile table("table.txt", table_text), abrdf("abrdf.dat", abrdf_text);
  return refusing([&] {
    const auto samples = curet_sample_numbers(abrdf.path());
    CuretReadOptions o;
    o.warn = quiet;
    read_curet(abrdf.path(), table.path(), samples.front(), o);
  });
}

inline int alta_one_input(const std::uint8_t* data, std::size_t size) {
  const ScratchFile file("data.alta", bytes(data, size));
  for (bool average : {false, true}) {
    AltaReadOptions o;
    o.wavelength_nm = 550.0;
    o.assumed_output = average ? "INV_STERADIAN_COSINE_FACTOR" : "";
    o.exclude_grazing = average;
    o.average_duplicates = average;
    o.warn = quiet;
    refusing([&] { read_alta(file.path(), o); });
  }
  return 0;
}

inline int formulation_one_input(const std::uint8_t* data, std::size_t size) {
  return refusing([&] { parse_formulation(std::string(bytes(data, size)), "fuzz.json", false); });
}

// A fit file read as a model (the best fit, then one group's; and through the resolver of fit files and
// MIX.json, which parses once and dispatches on "format") and as a parameter table.
inline int fit_file_one_input(const std::uint8_t* data, std::size_t size) {
  const ScratchFile file("fit.json", bytes(data, size));
  refusing([&] { read_fit_file(file.path()); });
  refusing([&] { read_model_file(file.path()); });
  refusing([&] { read_fit_file(file.path(), "lambert,theta_i=40"); });
  ParamsRequest request;
  request.fit_file = file.path();
  request.wavelengths = {600.0};
  return refusing([&] { (void)read_params_table(request).render(ParamsFormat::kMarkdown); });
}

// Text selections: a `where` expression (matched against a geometry) and a `--fit` selector.
inline int selection_one_input(const std::uint8_t* data, std::size_t size) {
  const std::string text(bytes(data, size));
  refusing([&] { (void)parse_geometry_selection(text).matches(geometry_from_degrees(40, 0, 60, 180)); });
  return refusing([&] { (void)parse_fit_selector(text); });
}

inline int mix_file_one_input(const std::uint8_t* data, std::size_t size) {
  const ScratchFile file("mix.json", bytes(data, size));
  refusing([&] { read_model_file(file.path(), "areal"); });
  return refusing([&] { read_mix_file(file.path()); });
}

// Beyond refusing bad input, an accepted calibration file must give positive, finite factors
// (mixing/calibration.h); a broken promise aborts.
inline int cross_sections_one_input(const std::uint8_t* data, std::size_t size) {
  const ScratchFile file("cal.json", bytes(data, size));
  return refusing([&] {
    for (const auto& [name, k] : mixing::read_cross_section_factors(file.path())) {
      if (!(k > 0.0 && std::isfinite(k))) {
        std::fprintf(stderr, "cross_sections: accepted factor %g of '%s'\n", k, name.c_str());
        std::abort();
      }
    }
  });
}

inline int rtable_one_input(const std::uint8_t* data, std::size_t size, photometry::RTableFormat format,
                            const char* name) {
  const ScratchFile file(name, bytes(data, size));
  return refusing([&] { photometry::read_rtable(file.path(), format); });
}

inline int rtable_csv_one_input(const std::uint8_t* data, std::size_t size) {
  return rtable_one_input(data, size, photometry::RTableFormat::csv, "r.csv");
}
inline int rtable_radiance_one_input(const std::uint8_t* data, std::size_t size) {
  return rtable_one_input(data, size, photometry::RTableFormat::radiance, "r.dat");
}
inline int rtable_rtb_one_input(const std::uint8_t* data, std::size_t size) {
  return rtable_one_input(data, size, photometry::RTableFormat::rtb, "r.rtb");
}

inline int solar_one_input(const std::uint8_t* data, std::size_t size) {
  const ScratchFile file("solar.csv", bytes(data, size));
  return refusing([&] { albedo::read_solar_spectrum(file.path()); });
}

// The spectrum reader (spectra/spectrum_file.h) under three sets of options: the permissive default
// (one to three columns, a grid for one-column files), a wide table's named column, and the strict
// solar checks. Beyond refusing bad input, an accepted spectrum must keep the reader's promises:
// finite, strictly increasing wavelengths, finite values, as many uncertainties as values or none,
// >= 0 where asked; a broken promise aborts.
inline void check_spectrum(const spectra::Spectrum& s, bool non_negative) {
  const auto& w = s.wavelengths();
  const auto& v = s.values();
  bool kept = !w.empty() && w.size() == v.size() && (s.sigma().empty() || s.sigma().size() == v.size());
  for (std::size_t k = 0; kept && k < w.size(); ++k) {
    kept = std::isfinite(w[k]) && std::isfinite(v[k]) && (k == 0 || w[k] > w[k - 1]) && (!non_negative || v[k] >= 0.0);
  }
  if (!kept) {
    std::fprintf(stderr, "spectrum: accepted a spectrum that breaks the reader's promises\n");
    std::abort();
  }
}

inline int spectrum_one_input(const std::uint8_t* data, std::size_t size) {
  const ScratchFile file("spectrum.txt", bytes(data, size));
  spectra::SpectrumReadOptions permissive;
  permissive.first_wavelength = 350.0;
  permissive.step = 1.0;
  spectra::SpectrumReadOptions wide;
  wide.value_column = "value";
  spectra::SpectrumReadOptions strict;
  strict.uncertainties = false;
  strict.one_column = false;
  strict.non_negative = true;
  strict.min_points = 2;
  strict.positive_integral = true;
  strict.interpolation = spectra::Interpolation::kSprague;
  for (const auto* o : {&permissive, &wide, &strict}) {
    refusing([&] {
      const spectra::Spectrum s = spectra::read_spectrum(file.path(), *o);
      check_spectrum(s, o->non_negative);
      // Interpolation anywhere inside the range gives a finite value.
      const double mid = 0.5 * (s.min_wavelength() + s.max_wavelength());
      if (!std::isfinite(s.value(mid))) {
        std::fprintf(stderr, "spectrum: interpolated value is not finite\n");
        std::abort();
      }
    });
  }
  return 0;
}

inline int surface_one_input(const std::uint8_t* data, std::size_t size) {
  const ScratchFile file("surface.json", bytes(data, size));
  return refusing([&] { surface::read_surface(file.path()); });
}

// USGS splib07a needs two texts: the input is the wavelength file, a NUL byte, then the spectrum
// (without a NUL, the input is both, so that the channel counts agree and the value checks run).
// Beyond refusing bad input, an accepted spectrum must keep the reader's promises (io/usgs.h):
// as many wavelengths as values, finite, strictly increasing and positive, kept + dropped = channels;
// a broken promise aborts, which the fuzzer and the replay test report.
inline int usgs_one_input(const std::uint8_t* data, std::size_t size) {
  const std::string_view all = bytes(data, size);
  const auto nul = all.find('\0');
  const std::string_view wavelengths = nul == std::string_view::npos ? all : all.substr(0, nul);
  const std::string_view spectrum = nul == std::string_view::npos ? all : all.substr(nul + 1);
  return refusing([&] {
    const UsgsSpectrum s = parse_usgs_spectrum(spectrum, "fuzz_spectrum.txt", wavelengths, "fuzz_wavelengths.txt");
    bool kept = s.wavelengths.size() == s.reflectance.size() && s.wavelengths.size() + s.missing == s.channels;
    for (std::size_t i = 0; kept && i < s.wavelengths.size(); ++i) {
      kept = s.wavelengths[i] > 0.0 && std::isfinite(s.wavelengths[i]) && std::isfinite(s.reflectance[i]) &&
             (i == 0 || s.wavelengths[i] > s.wavelengths[i - 1]) && s.reflectance[i] >= kUsgsMissingBelow;
    }
    if (!kept) {
      std::fprintf(stderr, "usgs: accepted spectrum breaks the reader's invariants\n");
      std::abort();
    }
    usgs_dataset(s, geometry_from_degrees(30.0, 0.0, 0.0, 0.0), AngleConvention::kZenithAzimuth);
  });
}

}  // namespace roadbrdf::fuzz
