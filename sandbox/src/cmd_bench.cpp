#include "commands.hpp"

namespace sandbox {

void registerBenchCommands(CLI::App& app) {
  auto* bench = app.add_subcommand("bench", "Benchmarks of the hot passes");
  bench->require_subcommand(1);
  registerBenchStepCommand(*bench);
}

}  // namespace sandbox
