// Sub-commands of the roadbrdf program; one file each (cmd_*.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace roadbrdf::cli {

void register_models_command(CLI::App& app);
void register_eval_command(CLI::App& app);
void register_rtable_command(CLI::App& app);
void register_fit_command(CLI::App& app);
void register_params_command(CLI::App& app);
void register_simulate_command(CLI::App& app);
void register_check_command(CLI::App& app);
void register_resample_command(CLI::App& app);
void register_calibrate_command(CLI::App& app);
void register_convert_command(CLI::App& app);
void register_mix_command(CLI::App& app);
void register_mix_calibrate_command(CLI::App& app);
void register_surface_command(CLI::App& app);  // also registers "render"
void register_albedo_command(CLI::App& app);
void register_plot_command(CLI::App& app);
void register_study_command(CLI::App& app);
void register_report_command(CLI::App& app);
void register_marking_command(CLI::App& app);
void register_export_command(CLI::App& app);
void register_luminaire_command(CLI::App& app);
void register_lighting_command(CLI::App& app);
// [command-declarations]

}  // namespace roadbrdf::cli
