#pragma once
// GLSL 3.30 sources of the renderer's programs. Lighting happens in linear light: colours arrive as
// sRGB and are linearised, the result is tone mapped (ACES fit) and encoded back to sRGB.
#include <string>

namespace sandbox::render::shaders {

extern const char* const kMeshVertex;    ///< lit meshes: world position, normal, colour, light-space position
extern const std::string kMeshFragment;  ///< sun (Blinn-Phong) + hemisphere ambient + PCF shadow
extern const char* const kGroundVertex;  ///< ground quad generated from gl_VertexID (no buffers)
extern const std::string kGroundFragment;  ///< anti-aliased grid, shadow, fade into the horizon
extern const char* const kShadowVertex;    ///< depth-only pass from the sun
extern const char* const kShadowFragment;
extern const char* const kSkyVertex;    ///< full-screen triangle
extern const char* const kSkyFragment;  ///< zenith-to-horizon gradient along the true view ray

}  // namespace sandbox::render::shaders
