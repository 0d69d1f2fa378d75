#include "commands.hpp"

namespace sandbox {

void registerMeshRenderCommand(CLI::App& mesh) { (void)mesh; }

}  // namespace sandbox
