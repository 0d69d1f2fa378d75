#include "commands.hpp"

namespace sandbox {

void registerBenchStepCommand(CLI::App& bench) { (void)bench; }

}  // namespace sandbox
