#pragma once
// A file read by a dependency that may crash on it (assimp aborts on some malformed files), run in a
// child process so that the crash ends the child, not the program.
#include <deform/mesh.hpp>
#include <deform/mesh_import.hpp>

#include <functional>
#include <string>

namespace deform {

/// Runs `read` in a forked child process and returns the mesh it produced, with the report it filled.
/// An InputError thrown by `read` comes back as itself, another exception as std::runtime_error. A child
/// that dies (a signal, an abort inside the dependency), runs past `cpu_limit_s` seconds of CPU time (a
/// hang), or exits without an answer makes the file refused: InputError naming `path` and why. The child
/// dies with the caller. In a sanitizer build a sanitizer report in the child refuses
/// the file too, with the report's summary (the report itself is the child's; assimp's memory errors
/// are found this way, as its aborts are). Throws std::runtime_error when no
/// child can be started.
Mesh readContained(const std::string& path, const std::function<Mesh(ImportReport&)>& read,
                   ImportReport& report, int cpu_limit_s);

}  // namespace deform
