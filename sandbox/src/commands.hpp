#pragma once
// Each command group registers its subcommands on the program's CLI11 app.
#include <CLI/CLI.hpp>

namespace sandbox {

void registerMeshCommands(CLI::App& app);
void registerBenchCommands(CLI::App& app);

}  // namespace sandbox
