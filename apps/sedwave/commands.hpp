#pragma once
// Each subcommand registers its options on the CLI11 app and returns the function that runs it.
#include <CLI/CLI.hpp>
#include <functional>

namespace sedwave::app {

/// A registered subcommand and what runs it once parsed.
struct Command {
  CLI::App* app;
  std::function<int()> run;
};

Command add_theory_command(CLI::App& app);
Command add_invert_command(CLI::App& app);
Command add_dem_command(CLI::App& app);
Command add_forward_command(CLI::App& app);
Command add_table_command(CLI::App& app);
Command add_synthesize_command(CLI::App& app);
Command add_merge_command(CLI::App& app);
Command add_show_command(CLI::App& app);

}  // namespace sedwave::app
