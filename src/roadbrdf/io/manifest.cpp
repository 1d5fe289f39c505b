#include "roadbrdf/io/manifest.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "roadbrdf/core/csv.h"
#include "roadbrdf/core/diagnostics.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/math.h"
#include "roadbrdf/core/text.h"
#include "roadbrdf/io/geometry_file.h"

namespace roadbrdf {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool role_from_text(const std::string& text, ManifestRole& role) {
  const std::string t = lower(text);
  if (t == "sample" || t == "target") return role = ManifestRole::kSample, true;
  if (t == "white" || t == "white_reference" || t == "white reference" || t == "reference") {
    return role = ManifestRole::kWhite, true;
  }
  if (t == "dark") return role = ManifestRole::kDark, true;
  return false;
}

const char* role_name(ManifestRole r) {
  return r == ManifestRole::kSample ? "sample" : r == ManifestRole::kWhite ? "white reference" : "dark";
}

std::string trim_copy(std::string_view s) { return trimmed_copy(s); }

void default_warn(const std::string& message) { route_warning(message); }

std::string geometry_text(const Geometry& g) {
  return fmt::format("theta_i {:.4g}, phi_i {:.4g}, theta_r {:.4g}, phi_r {:.4g} deg", rad_to_deg(g.theta_i),
                     rad_to_deg(g.phi_i), rad_to_deg(g.theta_r), rad_to_deg(g.phi_r));
}

bool same_geometry(const Geometry& a, const Geometry& b) {
  return length(a.wi - b.wi) < 1e-6 && length(a.wr - b.wr) < 1e-6;
}

// The instrument files of a run, each read once.
class RunFiles {
 public:
  RunFiles(const Manifest& m, const ManifestOptions& o) : manifest_(m), options_(o) {
    if (!options_.warn) options_.warn = default_warn;
    options_.read.regular_file_only = true;
  }
  const InstrumentSpectrum& get(const ManifestEntry& e) {
    auto it = files_.find(e.path);
    if (it != files_.end()) return it->second;
    InstrumentSpectrum s = read_instrument_file(e.path, options_.read);
    for (const auto& note : s.notes) options_.warn(note);
    if (!first_) {
      first_ = e;
    } else {
      check_compatible(*first_, files_.at(first_->path), e, s);
    }
    return files_.emplace(e.path, std::move(s)).first->second;
  }
  void warn(const std::string& m) const { options_.warn(m); }
  std::string where(const ManifestEntry& e) const { return fmt::format("{}:{}", manifest_.path, e.line); }

 private:
  void check_compatible(const ManifestEntry& fe, const InstrumentSpectrum& f, const ManifestEntry& e,
                        const InstrumentSpectrum& s) const {
    if (s.quantity != f.quantity || s.units != f.units) {
      throw InputError(
          fmt::format("{}: {} holds {} [{}], but {} holds {} [{}]: every file of a run must hold the "
                      "same quantity",
                      where(e), e.file, s.quantity, s.units, fe.file, f.quantity, f.units));
    }
    bool same = s.wavelengths.size() == f.wavelengths.size();
    for (std::size_t k = 0; same && k < s.wavelengths.size(); ++k) {
      same = std::fabs(s.wavelengths[k] - f.wavelengths[k]) <= 1e-6 * f.wavelengths[k];
    }
    if (!same) {
      throw InputError(
          fmt::format("{}: {} has {} wavelengths {:g}-{:g} nm, {} has {} ({:g}-{:g} nm): every file of "
                      "a run must share the wavelengths",
                      where(e), e.file, s.wavelengths.size(), s.wavelengths.front(), s.wavelengths.back(), fe.file,
                      f.wavelengths.size(), f.wavelengths.front(), f.wavelengths.back()));
    }
  }
  const Manifest& manifest_;
  ManifestOptions options_;
  std::map<std::string, InstrumentSpectrum> files_;
  std::optional<ManifestEntry> first_;
};

std::vector<const ManifestEntry*> entries_of(const Manifest& m, ManifestRole role) {
  std::vector<const ManifestEntry*> out;
  for (const auto& e : m.entries) {
    if (e.role == role) out.push_back(&e);
  }
  return out;
}

// Settings on which a raw count depends must agree between a sample and what it is divided by.
void check_settings(const RunFiles& run, const ManifestEntry& e, const std::map<std::string, std::string>& a,
                    const std::string& what_b, const std::map<std::string, std::string>& b,
                    const std::string& quantity) {
  if (quantity != "DN" || a.empty() || b.empty()) return;
  for (const auto& [key, value] : a) {
    const auto it = b.find(key);
    if (it != b.end() && it->second != value) {
      throw InputError(
          fmt::format("{}: sample {} was measured with {} {}, its {} with {}: raw counts taken with "
                      "different settings cannot be divided (roadbrdf applies no DN normalization)",
                      run.where(e), e.file, key, value, what_b, it->second));
    }
  }
}

// Metadata shared by every sample file (equal values), else marked as varying.
void merge_file_metadata(SpectralDataset& d, const std::vector<const InstrumentSpectrum*>& files) {
  std::map<std::string, std::string> merged = files.front()->metadata;
  for (const auto* f : files) {
    for (auto& [key, value] : merged) {
      const auto it = f->metadata.find(key);
      if (it == f->metadata.end() || it->second != value) value = "varies between the sample files";
    }
  }
  for (const auto& [key, value] : merged) d.metadata[key] = value;
}

SpectralDataset rows_dataset(const Manifest& m, const std::vector<const ManifestEntry*>& entries, RunFiles& run,
                             InstrumentQuantity q, std::vector<const InstrumentSpectrum*>* files = nullptr) {
  SpectralDataset d;
  d.convention = m.convention;
  for (const ManifestEntry* e : entries) {
    const InstrumentSpectrum& s = run.get(*e);
    const std::vector<double>& v = instrument_signal(s, q);
    if (d.wavelengths.empty()) {
      d.wavelengths = s.wavelengths;
      d.metadata["units"] = instrument_signal_units(s, q);
    }
    d.geometries.push_back(e->geometry);
    d.brdf.insert(d.brdf.end(), v.begin(), v.end());
    if (files) files->push_back(&s);
  }
  return d;
}

// White or dark rows: all with geometry (matched) or exactly one without (used for all).
std::vector<const ManifestEntry*> reference_rows(const Manifest& m, ManifestRole role) {
  auto rows = entries_of(m, role);
  std::size_t without = 0;
  for (const auto* e : rows) without += e->has_geometry ? 0 : 1;
  if (without && rows.size() > 1) {
    throw FileError(m.path, rows[1]->line, 0,
                    fmt::format("{} {} rows, {} of them without angles: give every {} row its geometry, or list one "
                                "row without angles for the whole run",
                                rows.size(), role_name(role), without, role_name(role)));
  }
  return rows;
}

}  // namespace

Manifest read_manifest(const std::string& path) {
  InputLimits limits;
  limits.what = "a run manifest";
  limits.max_bytes = kManifestMaxBytes;
  limits.max_line_bytes = kManifestLineMaxBytes;
  limits.regular_file_only = true;
  CsvReader reader(path, limits);
  Manifest m;
  m.path = path;
  std::vector<CsvCell> cells;
  if (!reader.next_row(cells)) throw FileError(path, reader.line_number(), 0, "manifest is empty (no header line)");
  std::vector<std::string> header;
  header.reserve(cells.size());
  for (const auto& c : cells) header.push_back(lower(c.text));
  const long header_line = reader.line_number();
  const auto angle_columns = find_angle_columns(header, path, header_line, m.convention);
  int file_column = -1, role_column = -1;
  for (std::size_t k = 0; k < header.size(); ++k) {
    const bool is_angle = std::find(angle_columns.begin(), angle_columns.end(), k) != angle_columns.end();
    if (header[k] == "file") {
      file_column = static_cast<int>(k);
    } else if (header[k] == "role") {
      role_column = static_cast<int>(k);
    } else if (!is_angle && header[k] != "comment") {
      throw FileError(
          path, header_line, cells[k].column,
          fmt::format("unknown manifest column '{}' (file, role, the four angles, comment)", cells[k].text));
    }
  }
  if (file_column < 0 || role_column < 0) {
    throw FileError(path, header_line, 0, "manifest header needs the columns file and role (and the four angles)");
  }
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::vector<std::pair<Geometry, long>> sample_geometries;
  while (reader.next_row(cells)) {
    if (cells.size() != header.size()) {
      reader.fail(cells.back().column,
                  fmt::format("row has {} cells but the header has {} columns", cells.size(), header.size()));
    }
    ManifestEntry e;
    e.line = reader.line_number();
    const CsvCell& file = cells[static_cast<std::size_t>(file_column)];
    if (file.text.empty()) reader.fail(file.column, "empty file name");
    e.file = std::string(file.text);
    const std::filesystem::path p(e.file);
    e.path = (p.is_absolute() || folder.empty() ? p : folder / p).string();
    const CsvCell& role = cells[static_cast<std::size_t>(role_column)];
    if (!role_from_text(std::string(role.text), e.role)) {
      reader.fail(role.column, fmt::format("unknown role '{}' (sample, white, dark)", role.text));
    }
    std::size_t empty = 0;
    for (auto k : angle_columns) empty += cells[k].text.empty() ? 1 : 0;
    if (empty == 4 && e.role != ManifestRole::kSample) {
      e.has_geometry = false;
    } else {
      double a[4];
      for (int k = 0; k < 4; ++k)
        a[k] = reader.number(cells[angle_columns[static_cast<std::size_t>(k)]], "angle in degrees");
      try {
        e.geometry = geometry_from_angle_values(m.convention, a);
      } catch (const FileError&) {
        throw;
      } catch (const InputError& err) {
        reader.fail(cells[angle_columns[0]].column, err.what());
      }
      e.has_geometry = true;
    }
    if (e.role == ManifestRole::kSample) {
      for (const auto& [g, line] : sample_geometries) {
        if (same_geometry(g, e.geometry)) {
          reader.fail(cells[angle_columns[0]].column,
                      fmt::format("a second sample at the geometry of line {} ({})", line, geometry_text(g)));
        }
      }
      sample_geometries.emplace_back(e.geometry, e.line);
    }
    m.entries.push_back(std::move(e));
  }
  if (sample_geometries.empty()) throw FileError(path, reader.line_number(), 0, "manifest has no sample row");
  const auto& comments = reader.comments();
  for (const auto& c : comments) {
    const auto colon = c.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = trim_copy(c.substr(0, colon));
    if (key.empty() || key.find(' ') != std::string::npos) continue;
    m.metadata[key] = trim_copy(c.substr(colon + 1));
  }
  return m;
}

std::vector<FileArgument> manifest_input_files(const Manifest& manifest) {
  std::vector<FileArgument> files;
  files.reserve(manifest.entries.size());
  for (const ManifestEntry& e : manifest.entries) {
    files.push_back({fmt::format("{} file '{}' ({}:{})", role_name(e.role), e.file, manifest.path, e.line), e.path});
  }
  return files;
}

SpectralDataset manifest_dataset(const Manifest& m, InstrumentQuantity quantity, const ManifestOptions& options) {
  RunFiles run(m, options);
  std::vector<const InstrumentSpectrum*> files;
  SpectralDataset d = rows_dataset(m, entries_of(m, ManifestRole::kSample), run, quantity, &files);
  merge_file_metadata(d, files);
  for (const auto& [k, v] : m.metadata) d.metadata[k] = v;
  d.metadata["units"] = instrument_signal_units(*files.front(), quantity);
  d.metadata["manifest"] = m.path;
  d.metadata["signal"] = name_of(quantity);
  return d;
}

CalibrationInput manifest_calibration_input(const Manifest& m, const ManifestOptions& options) {
  RunFiles run(m, options);
  const auto samples = entries_of(m, ManifestRole::kSample);
  std::vector<const InstrumentSpectrum*> files;
  CalibrationInput in;
  in.sample = rows_dataset(m, samples, run, InstrumentQuantity::kTarget, &files);
  merge_file_metadata(in.sample, files);
  for (const auto& [k, v] : m.metadata) in.sample.metadata[k] = v;
  in.sample.metadata["manifest"] = m.path;
  in.sample.metadata["units"] = instrument_signal_units(*files.front(), InstrumentQuantity::kTarget);
  const std::string quantity = files.front()->quantity;
  const auto whites = reference_rows(m, ManifestRole::kWhite);
  if (whites.empty()) {
    // Each sample divided by the reference stored in its own file.
    in.reference = rows_dataset(m, samples, run, InstrumentQuantity::kReference);
    for (std::size_t k = 0; k < samples.size(); ++k) {
      check_settings(run, *samples[k], files[k]->target_settings, "stored reference", files[k]->reference_settings,
                     quantity);
    }
    in.sample.metadata["white_reference"] = "embedded (the reference stored in each sample file)";
  } else {
    in.reference = rows_dataset(m, whites, run, InstrumentQuantity::kTarget);
    std::string list;
    for (const auto* w : whites) list += (list.empty() ? "" : ", ") + w->file;
    in.sample.metadata["white_reference"] = list;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const ManifestEntry* white = whites.front();
      for (const auto* w : whites) {
        if (w->has_geometry && same_geometry(w->geometry, samples[k]->geometry)) white = w;
      }
      if (white->has_geometry && !same_geometry(white->geometry, samples[k]->geometry)) {
        throw InputError(fmt::format("{}: no white reference row at the geometry of sample {} ({})",
                                     run.where(*samples[k]), samples[k]->file, geometry_text(samples[k]->geometry)));
      }
      check_settings(run, *samples[k], files[k]->target_settings, "white reference " + white->file,
                     run.get(*white).target_settings, quantity);
    }
  }
  const auto darks = reference_rows(m, ManifestRole::kDark);
  if (!darks.empty()) {
    in.dark = rows_dataset(m, darks, run, InstrumentQuantity::kTarget);
    std::string list;
    for (const auto* d : darks) list += (list.empty() ? "" : ", ") + d->file;
    in.sample.metadata["dark"] = list;
    for (const auto* f : files) {
      const auto it = f->metadata.find("asd.dark_corrected");
      if (it != f->metadata.end() && it->second == "yes") {
        run.warn(f->path +
                 ": the ASD header says the spectrum is already dark-corrected, and the manifest lists a "
                 "dark: it is subtracted again");
        break;
      }
    }
  } else {
    in.sample.metadata["dark"] = "none";
  }
  return in;
}

SpectralDataset calibrate_manifest(const Manifest& m, const spectra::Spectrum& panel_reflectance,
                                   const std::optional<spectra::Spectrum>& panel_brf, const ManifestOptions& options) {
  CalibrationInput in = manifest_calibration_input(m, options);
  in.panel_reflectance = panel_reflectance;
  in.panel_brf = panel_brf;
  const std::string signal_units = in.sample.metadata["units"];
  SpectralDataset out = calibrate(in);
  out.metadata["signal_units"] = signal_units;
  return out;
}

}  // namespace roadbrdf
