// sedwave: geoacoustic inversion with discrete-element and 1D chain forward models.
#include <CLI/CLI.hpp>
#include <glog/logging.h>

#include <exception>
#include <iostream>
#include <vector>

#include "commands.hpp"
#include "mpi_session.hpp"
#include "sedwave/io/atomic_file.hpp"
#include "sedwave/io/hdf5.hpp"
#include "sedwave/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"sedwave: fit grain-contact parameters (stiffness kappa, diameter d, dashpot gamma or "
               "restitution e_n) to seabed attenuation and sound-speed data"};
  app.set_version_flag("--version", sedwave::kVersion);
  app.require_subcommand(1);
  const std::vector<sedwave::app::Command> commands{sedwave::app::add_theory_command(app),
                                                    sedwave::app::add_invert_command(app),
                                                    sedwave::app::add_dem_command(app),
                                                    sedwave::app::add_forward_command(app),
                                                    sedwave::app::add_table_command(app),
                                                    sedwave::app::add_synthesize_command(app),
                                                    sedwave::app::add_merge_command(app),
                                                    sedwave::app::add_show_command(app),
                                                    sedwave::app::add_models_command(app),
                                                    sedwave::app::add_compare_command(app),
                                                    sedwave::app::add_interface_command(app),
                                                    sedwave::app::add_reflect_command(app)};
  // Ceres logs through glog a line for every failed evaluation of a local fit, even with its own
  // logging silent (a model evaluated outside a table's range, for one). The fits check and report
  // every failure themselves, so only glog's fatal messages reach the terminal.
  FLAGS_minloglevel = google::GLOG_FATAL;
  // Every HDF5 call is checked, and a failure becomes an error that names the file, what was done
  // to it and HDF5's reason ("HDF5: cannot open FILE (file signature not found)"); the library's
  // own error stack would print its internals above that line, once per rank.
  const sedwave::io::QuietErrors hdf5_quiet;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" to CLI11 with code 0; every real one is a usage error.
    const int code = e.get_exit_code() == 0 ? sedwave::app::kExitOk : sedwave::app::kExitUsage;
    if (!sedwave::app::under_launcher()) {
      app.exit(e);
      return code;
    }
    // Under mpirun or srun every rank met the same command line: told once, by rank 0.
    const sedwave::app::MpiSession mpi;
    mpi.tell_once([&] { app.exit(e); });
    return code;
  }
  try {
    for (const sedwave::app::Command& command : commands) {
      if (command.app->parsed()) {
        const int code = command.run();
        sedwave::io::flush_standard_output();
        return code;
      }
    }
  } catch (...) {
    return sedwave::app::report_failure(std::current_exception(), &std::cerr);
  }
  return sedwave::app::kExitError;
}
