#pragma once
// An OpenGL 3.3 core context without a display (OSMesa, software rasterised by llvmpipe), so frames can
// be rendered on a headless machine or in CI. The renderer draws into its own framebuffer objects; the
// context's own buffer is only a token OSMesa needs to make the context current.
#include <string>

namespace sandbox::render {

class OffscreenContext {
 public:
  /// Creates the context, makes it current on this thread and loads the GL functions. Throws
  /// std::runtime_error with a message saying what to install or check when that is not possible.
  OffscreenContext();
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  /// Makes this context current on the calling thread (after another context was used there).
  void makeCurrent();

  /// GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6".
  std::string description() const;

 private:
  void* context_ = nullptr;                ///< OSMesaContext, opaque here so osmesa.h stays in one file
  unsigned char token_buffer_[4 * 4 * 4];  ///< 4x4 RGBA buffer OSMesaMakeCurrent requires
};

}  // namespace sandbox::render
