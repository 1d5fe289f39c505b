// Conversion of measurement files into a spectral dataset as the front ends ask for it (`roadbrdf
// convert`, roadbrdf.convert in Python): the request with its field table (core/request_fields.h) and
// the task, which reads dataset CSV files (several runs of one sample combined, io/dataset_runs.h),
// CUReT, ALTA, instrument files (.asd, .sed, .sig), run manifests and USGS splib07a spectra.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "roadbrdf/core/enum_names.h"
#include "roadbrdf/core/request_fields.h"
#include "roadbrdf/io/dataset.h"
#include "roadbrdf/io/dataset_runs.h"
#include "roadbrdf/io/instrument_options.h"

namespace roadbrdf {

// What `convert` reads (its `source`, the command line's from). The instrument formats are named as InstrumentFormat
// names them (io/instrument.h), which the file read must then be.
enum class ConvertSource { kAuto, kWide, kLong, kCuret, kAlta, kAsd, kSed, kSig, kInstrument, kManifest, kUsgs };
inline constexpr EnumName<ConvertSource> kConvertSourceNames[] = {
    {ConvertSource::kAuto, "auto", "wide or long CSV, or an instrument file by its extension"},
    {ConvertSource::kWide, "wide", ""},
    {ConvertSource::kLong, "long", ""},
    {ConvertSource::kCuret, "curet", ""},
    {ConvertSource::kAlta, "alta", ""},
    {ConvertSource::kAsd, "asd", ""},
    {ConvertSource::kSed, "sed", ""},
    {ConvertSource::kSig, "sig", ""},
    {ConvertSource::kInstrument, "instrument", "any of the three, by its content"},
    {ConvertSource::kManifest, "manifest", "a run of instrument files: docs/data.md"},
    {ConvertSource::kUsgs, "usgs",
     "a USGS splib07a ASCII spectrum: needs usgs_wavelengths and geometry; stored as BRDF = R/pi"},
};
constexpr std::span<const EnumName<ConvertSource>> enum_names(ConvertSource) { return kConvertSourceNames; }
static_assert(entries_are_distinct(kConvertSourceNames));

// The dataset-reading fields (DatasetReadFields) but one: `quantity` is the request's own row, what an
// instrument file's signal to store is, or what a dataset CSV's values are ("" = target or brdf).
struct ConvertRequest : DatasetReadFields, InstrumentOptions {
  std::vector<std::string> inputs;   // one file, or several dataset CSV files (runs of one sample)
  std::string source = "auto";       // a name of ConvertSource (`from` is a keyword of Python)
  std::string to = "wide";           // a name of DatasetFormat (io/dataset_io.h)
  std::string curet_table;           // CUReT geometry table ("" = table.txt next to the input)
  std::optional<int> sample;         // CUReT sample number
  std::optional<double> wavelength;  // [nm] of single-channel data (ALTA: required; CUReT: default 550)
  std::string alta_output;           // ALTA output unit when the file lacks #PARAM_OUT
  bool exclude_grazing = false;      // ALTA BRDF x cos(theta_v): leave out grazing rows
  std::string convention;            // angle columns of the output ("" = as read)
  std::string geometry;          // of a single instrument file: "theta_i=D,phi_i=D,theta_r=D,phi_r=D" or road angles
  std::string usgs_wavelengths;  // the splib07a wavelength file of a USGS spectrum
  std::string output;            // where the dataset is written ("" or "-" = standard output)

  ConvertRequest() { quantity.clear(); }
  static RequestFields<ConvertRequest> fields();
};

// The task of `roadbrdf convert`: the dataset, after check_distinct_files over the request's files (a
// manifest's listed files, the CUReT table next to the input and the USGS wavelength file among the
// inputs); written to `output` in `to` when given (write_dataset_output). Warnings (instrument notes, missing USGS
// channels) go to the front end's sink (core/diagnostics.h route_warning). Throws FieldError /
// InputError / FileError.
SpectralDataset convert(const ConvertRequest& request);

}  // namespace roadbrdf
