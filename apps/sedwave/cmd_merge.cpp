// `sedwave merge`: combines the member tables of one ensemble (`sedwave table --member K`, one
// packing per run, for packings too large to hold several in one process) into the ensemble's
// table: per point the mean over the members and its standard error, with the significance rule
// of a table made in one run (experiment/linear_points.hpp). Serial; the tables are small.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "output_paths.hpp"
#include "sedwave/forward/experiment/linear_points.hpp"
#include "sedwave/forward/table/table_file.hpp"

namespace sedwave::app {

Command add_merge_command(CLI::App& app) {
  struct Options {
    std::vector<std::string> members;
    std::string out;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "Combine the member tables of an ensemble (sedwave table --member K) into one table of means and "
               "standard errors (docs/tables.md)");
  cmd->add_option("tables", o->members, "member tables (HDF5), one per member")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "ensemble table to write (HDF5; must not exist)")->required();
  return {cmd, [o]() {
    std::vector<std::filesystem::path> inputs;
    for (const std::string& member : o->members) {
      inputs.emplace_back(member);
      inputs.push_back(forward::table::TableFile::journal_path(member));
    }
    const auto hdf5 = io::OutputFormat::seekable;
    check_outputs({{"--out", o->out, hdf5}, {"--out", forward::table::TableFile::journal_path(o->out), hdf5}}, inputs,
                  "merge");
    std::vector<forward::table::DispersionTable> tables;
    for (const std::string& path : o->members) tables.push_back(forward::table::read_table(path));
    const forward::table::DispersionTable merged = forward::experiment::merge_member_tables(tables, o->members);
    forward::table::write_table(o->out, merged);
    std::size_t ok = 0;
    for (std::size_t g = 0; g < merged.n_gamma(); ++g)
      for (std::size_t w = 0; w < merged.n_omega(); ++w) ok += merged.at(g, w).status == forward::table::PointStatus::ok;
    std::cout << "merged " << tables.size() << " member table(s) into " << o->out << ": " << ok << " of "
              << merged.grid().size() << " points ok\n";
    return 0;
  }};
}

}  // namespace sedwave::app
