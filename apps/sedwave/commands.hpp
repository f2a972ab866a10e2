#pragma once
// Each subcommand registers its options on the CLI11 app and returns the function that runs it.
#include <CLI/CLI.hpp>
#include <functional>

namespace sedwave::app {

/// Exit codes of every subcommand (docs/cli.md, "Exit codes").
inline constexpr int kExitOk = 0;          ///< finished; every result printed is a trustworthy answer
inline constexpr int kExitError = 1;       ///< bad input or failed I/O: an error message, no new output
inline constexpr int kExitUsage = 2;       ///< the command line itself is wrong (unknown option, bad value)
inline constexpr int kExitIncomplete = 3;  ///< ran, but some result is flagged: not converged, not measured,
                                           ///< failed table points, or outside physical ranges

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
Command add_models_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_interface_command(CLI::App& app);
Command add_reflect_command(CLI::App& app);

}  // namespace sedwave::app
