#include "render/gl_functions.hpp"

#include <cstdio>
#include <stdexcept>

namespace sandbox::gl {

#define SANDBOX_GL_DEFINE(type, name) type name = nullptr;
SANDBOX_GL_FUNCTIONS(SANDBOX_GL_DEFINE)
#undef SANDBOX_GL_DEFINE

std::vector<std::string> loadFunctions(ProcLookup lookup) {
  std::vector<std::string> missing;
#define SANDBOX_GL_LOAD(type, name)                  \
  name = reinterpret_cast<type>(lookup("gl" #name)); \
  if (name == nullptr) missing.emplace_back("gl" #name);
  SANDBOX_GL_FUNCTIONS(SANDBOX_GL_LOAD)
#undef SANDBOX_GL_LOAD
  return missing;
}

void checkError(const char* what) {
  const GLenum error = GetError();
  if (error == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", error);
  throw std::runtime_error(std::string("OpenGL error ") + code + " in " + what);
}

}  // namespace sandbox::gl
