#pragma once
// Command-line options shared by every command that loads a mesh: --scale, --up, --forward.
#include <deform/mesh_import.hpp>

#include <CLI/CLI.hpp>
#include <string>

namespace sandbox {

struct MeshLoadFlags {
  double scale = 1.0;
  std::string up;       ///< empty: the format's default
  std::string forward;  ///< empty: the format's default

  void addTo(CLI::App& command);
  /// Checked conversion to importer options; throws deform::InputError naming the flag.
  deform::ImportOptions importOptions() const;
};

}  // namespace sandbox
