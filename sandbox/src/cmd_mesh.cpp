#include "commands.hpp"

namespace sandbox {

void registerMeshCommands(CLI::App& app) {
  auto* mesh = app.add_subcommand("mesh", "Inspect a mesh, its control mesh and its embedding");
  mesh->require_subcommand(1);
  registerMeshRenderCommand(*mesh);
}

}  // namespace sandbox
