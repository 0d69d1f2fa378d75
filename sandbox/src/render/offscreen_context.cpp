#include "render/offscreen_context.hpp"

#include "render/gl_functions.hpp"

// osmesa.h pulls in <GL/gl.h>, whose prototypes would clash with the loader's names; it is only needed
// here, so it is included last and nothing from it leaks into a header.
#include <GL/osmesa.h>

#include <stdexcept>

namespace sandbox::render {
namespace {

gl::GenericProc lookupProc(const char* name) {
  return reinterpret_cast<gl::GenericProc>(OSMesaGetProcAddress(name));
}

}  // namespace

OffscreenContext::OffscreenContext() {
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (context == nullptr) {
    throw std::runtime_error(
        "cannot create an offscreen OpenGL 3.3 core context (OSMesa); rendering needs Mesa's OSMesa with "
        "the llvmpipe driver (Debian: libosmesa6). Check LIBGL_ALWAYS_SOFTWARE/GALLIUM_DRIVER if set.");
  }
  context_ = context;
  if (!OSMesaMakeCurrent(context, token_buffer_, GL_UNSIGNED_BYTE, 4, 4)) {
    OSMesaDestroyContext(context);
    context_ = nullptr;
    throw std::runtime_error("cannot make the offscreen OpenGL context current (OSMesaMakeCurrent failed)");
  }
  const std::vector<std::string> missing = gl::loadFunctions(&lookupProc);
  if (!missing.empty()) {
    OSMesaDestroyContext(context);
    context_ = nullptr;
    throw std::runtime_error("the offscreen OpenGL context lacks " + missing.front() + " (and " +
                             std::to_string(missing.size() - 1) + " more); OpenGL 3.3 core is needed");
  }
}

OffscreenContext::~OffscreenContext() {
  if (context_ != nullptr) OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
}

void OffscreenContext::makeCurrent() {
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(context_), token_buffer_, GL_UNSIGNED_BYTE, 4, 4)) {
    throw std::runtime_error("cannot make the offscreen OpenGL context current (OSMesaMakeCurrent failed)");
  }
}

std::string OffscreenContext::description() const {
  const auto text = [](GLenum name) {
    const GLubyte* value = gl::GetString(name);
    return value == nullptr ? std::string("?") : std::string(reinterpret_cast<const char*>(value));
  };
  return text(GL_RENDERER) + ", " + text(GL_VERSION);
}

}  // namespace sandbox::render
