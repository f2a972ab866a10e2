#include "output_paths.hpp"

#include "sedwave/io/atomic_file.hpp"

namespace sedwave::app {

void check_outputs(const std::vector<OutputPath>& outputs, const std::vector<std::filesystem::path>& inputs,
                   const std::string& command) {
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    const OutputPath& out = outputs[k];
    try {
      io::refuse_overwriting_inputs({out.path}, inputs, "sedwave " + command + " " + out.option);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    for (std::size_t j = 0; j < k; ++j) {
      try {
        io::refuse_overwriting_inputs({out.path}, {outputs[j].path}, "");
      } catch (const std::invalid_argument&) {
        throw UsageError("sedwave " + command + ": " + outputs[j].option + " and " + out.option + " both name " +
                         out.path.string() + "; give each output its own file");
      }
    }
  }
  for (const OutputPath& out : outputs) io::require_writable_location(out.path, out.option, out.format);
}

}  // namespace sedwave::app
