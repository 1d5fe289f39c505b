// roadbrdf check DATA.csv [--json]: quality report (io/quality.h).
#include <fmt/core.h>

#include <iostream>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/dataset_flags.h"
#include "roadbrdf/core/atomic_file.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/core/json_input.h"
#include "roadbrdf/io/calibration.h"
#include "roadbrdf/io/dataset_io.h"
#include "roadbrdf/io/quality.h"
#include "roadbrdf/spectra/spectrum_file.h"

namespace roadbrdf::cli {

namespace {

struct CheckArgs {
  std::string data;
  bool json = false;
  DatasetReadFlags read;
  std::string panel;
  QualityOptions options;
};

void run(CheckArgs& a) {
  check_distinct_files({{"DATA", a.data}, {"--panel-reflectance", a.panel}}, {});
  DatasetReadOptions read = dataset_read_options(a.read, a.data, {a.data});
  read.allow_missing = true;  // counted in the report
  DatasetReadStats stats;
  const SpectralDataset d = read_dataset(a.data, read, stats);
  QualityOptions o = a.options;
  if (!a.panel.empty()) o.panel_reflectance = read_panel_reflectance(a.panel);
  const QualityReport r = check_dataset(d, o, stats);
  // The receiver solid angles of an OpenMATERIAL 3D file (io/openmaterial3d.h), kept in the metadata.
  constexpr std::string_view kSolidAngle = "receiver_solid_angle_sr.";
  nlohmann::json solid_angles = nlohmann::json::object();
  std::string solid_angle_text;
  for (const auto& [key, value] : d.metadata) {
    if (key.rfind(kSolidAngle, 0) != 0) continue;
    solid_angles[key.substr(kSolidAngle.size())] = value;
    solid_angle_text += fmt::format("receiver solid angle at {} nm: {} sr\n", key.substr(kSolidAngle.size()), value);
  }
  if (a.json) {
    nlohmann::json j = quality_report_json(d, r);
    j["file"] = a.data;
    if (!solid_angles.empty()) j["receiver_solid_angles_sr"] = solid_angles;
    AtomicFile out("-");
    roadbrdf::write_json(out.stream(), j, 2);
    out.stream() << '\n';
    out.commit();
  } else {
    AtomicFile out("-");
    out.stream() << a.data << '\n' << with_dataset_flags(quality_report_text(d, r)) << solid_angle_text;
    out.commit();
  }
}

}  // namespace

void register_check_command(CLI::App& app) {
  static CheckArgs args;
  auto* c = app.add_subcommand("check",
                               "Quality report of a dataset: angular coverage, negative/missing values, reciprocity, "
                               "noisy bands, outlier geometries, reference-panel validation");
  c->add_option("data", args.data, "Dataset CSV (wide or long)")->required();
  c->add_flag("--json", args.json, "Machine-readable report");
  add_dataset_read_flags(c, args.read);
  c->add_option("--panel-reflectance", args.panel,
                "The dataset is a reference panel: compare it with rho/pi, rho from this file (wavelength [nm], "
                "reflectance [, sigma])");
  c->add_option("--tolerance", args.options.angle_tolerance_deg, "Angle tolerance of reciprocity pairs [deg]");
  c->add_flag("--exact-reciprocity", args.options.exact_reciprocity,
              "Pair geometries by exchanged directions (default: exchanged zenith angles, same |dphi|: isotropic)");
  c->add_option("--reciprocity-threshold", args.options.reciprocity_threshold,
                "Relative disagreement above which a reciprocity pair is flagged");
  c->add_option("--snr-threshold", args.options.snr_threshold, "Signal-to-noise ratio below which a band is noisy");
  c->add_option("--noise-window", args.options.noise_window, "Wavelengths on each side pooled in the noise estimate");
  c->add_option("--neighbours", args.options.neighbours, "Angular neighbours compared with each geometry");
  c->add_option("--outlier-threshold", args.options.outlier_threshold,
                "Robust score above which a geometry is an outlier");
  c->add_option("--outlier-min-ratio", args.options.outlier_min_ratio,
                "Minimum ratio to the neighbours' median for an outlier");
  c->add_option("--specular-window", args.options.specular_cone_deg,
                "Angle from the mirror direction [deg] within which a bright geometry is a specular peak, not an "
                "outlier");
  c->add_option("--listed-outliers", args.options.listed_outliers,
                "Outliers listed in the text report (all of them with --json)");
  c->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
