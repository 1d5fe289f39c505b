// roadbrdf mix-calibrate FORMULATION.json DATA.csv [FORMULATION.json DATA.csv ...] [--reference NAME]
//                        -o CAL.json
// Fits the effective cross-section factors of the hapke mixing method's end-members to measured
// mixtures (mixing/calibration.h); `roadbrdf mix --method hapke --cross-sections CAL.json` uses them.
#include <fmt/core.h>

#include "roadbrdf/cli/commands.h"
#include "roadbrdf/cli/common.h"
#include "roadbrdf/cli/dataset_flags.h"
#include "roadbrdf/core/error.h"
#include "roadbrdf/mixing/calibration.h"

namespace roadbrdf::cli {

namespace {

struct MixCalibrateArgs {
  std::vector<std::string> pairs;
  DatasetReadFlags read;
  std::string reference;
  std::string output;
};

void run(const MixCalibrateArgs& a) {
  using namespace mixing;
  if (a.output.empty()) throw InputError("give the output file with -o CAL.json");
  if (a.pairs.size() % 2 != 0) {
    throw InputError(
        fmt::format("MIXTURES: give pairs FORMULATION.json DATA.csv ({} files given: the last one has no "
                    "partner)",
                    a.pairs.size()));
  }
  CrossSectionRequest request;
  for (std::size_t i = 0; i + 1 < a.pairs.size(); i += 2) {
    request.formulations.push_back(a.pairs[i]);
    request.data.push_back(a.pairs[i + 1]);
  }
  request.data_read = dataset_read_options(a.read);
  request.reference = a.reference;
  CrossSectionRun run;
  try {
    run = run_cross_section_calibration(request, {{"-o", a.output}});
  } catch (const FieldError& e) {
    const std::string flag = e.field() == "reference" ? "--reference" : "MIXTURES";
    throw InputError(flag + ": " + e.detail());
  }
  write_cross_section_file(a.output, run.content);
  std::FILE* report = report_stream(a.output);
  fmt::print(report, "{}", run.table());
  fmt::print(report, "wrote {}\n", a.output);
}

}  // namespace

void register_mix_calibrate_command(CLI::App& app) {
  static MixCalibrateArgs args;
  auto* command = app.add_subcommand(
      "mix-calibrate",
      "Fit effective cross-section factors of the hapke mixing method's end-members to measured mixtures");
  command
      ->add_option("mixtures", args.pairs,
                   "Pairs FORMULATION.json DATA.csv: each measured mixture's formulation and measured BRDF")
      ->required();
  add_dataset_read_flags(command, args.read);
  command->add_option("--reference", args.reference,
                      "End-member whose factor is fixed at 1 (default: the first end-member of the first mixture)");
  command
      ->add_option("-o,--output", args.output, "Output calibration file (JSON, see src/roadbrdf/mixing/calibration.h)")
      ->required();
  command->callback([] { run(args); });
}

}  // namespace roadbrdf::cli
