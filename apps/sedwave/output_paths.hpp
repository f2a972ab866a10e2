#pragma once
// Output paths checked before any work: a long run must not find out at its end that it cannot
// write its result, and no output may replace one of the run's inputs.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "sedwave/io/atomic_file.hpp"

namespace sedwave::app {

/// A mistake in the command line found after parsing (an output naming an input): exit code
/// kExitUsage, like the parser's own errors.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// One output of a command: the option that names it ("--out"), the file, and whether its format
/// must seek (HDF5: refused on a device or FIFO, which a text output is written to in place).
struct OutputPath {
  std::string option;
  std::filesystem::path path;
  io::OutputFormat format = io::OutputFormat::text;
};

/// Throws UsageError if an output names an input or another output, and std::invalid_argument if
/// an output's directory cannot be written (io::require_writable_location). `command` names the
/// subcommand in messages.
void check_outputs(const std::vector<OutputPath>& outputs, const std::vector<std::filesystem::path>& inputs,
                   const std::string& command);

}  // namespace sedwave::app
