#pragma once
// The offscreen renderer: meshes uploaded once (positions and normals in dynamic buffers, so a
// deforming 900,000-vertex body costs one buffer update per frame), drawn lit with a soft sun shadow on
// a gridded ground under a gradient sky, multisampled, read back as RGBA8.
#include "render/camera.hpp"
#include "render/gpu_program.hpp"
#include "render/offscreen_context.hpp"
#include "render/png_io.hpp"
#include "render/scene.hpp"
#include "render/sun_shadow.hpp"

#include <memory>
#include <vector>

namespace sandbox::render {

struct RenderSettings {
  int width = 1280;            ///< picture width [px]
  int height = 720;            ///< picture height [px]
  int samples = 4;             ///< MSAA samples per pixel (0 or 1: none); lowered to what the driver has
  int shadow_map_size = 2048;  ///< shadow map side [texels]
  float penumbra_fraction = 0.0065f;  ///< shadow blur radius [m] per metre from the camera to its target
  float shadow_reach = 2.5f;  ///< shadows are cast by what lies within this many view distances of the target
  /// Anti-alias by smoothing the read-back picture's edges (smoothEdges) instead of multisampling: on
  /// llvmpipe 4x MSAA costs two thirds more per frame. `samples` is then ignored (no MSAA).
  bool smooth_edges = false;
};

class Renderer {
 public:
  using MeshId = std::size_t;

  /// Creates the offscreen context, framebuffers and programs. Throws std::runtime_error when OSMesa
  /// cannot give an OpenGL 3.3 core context, deform::InputError for a size outside 1..8192.
  explicit Renderer(const RenderSettings& settings = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads a mesh (normals required, one per position) and returns its id.
  MeshId addMesh(const MeshData& mesh);
  /// New vertex positions (same count as uploaded) and, optionally, normals; empty normals keep the old.
  void updatePositions(MeshId id, const std::vector<Eigen::Vector3f>& positions_m,
                       const std::vector<Eigen::Vector3f>& normals = {});
  /// Per-vertex sRGB colours (same count as positions); empty: back to the mesh's base colour.
  void setColours(MeshId id, const std::vector<Eigen::Vector3f>& colours);
  void setBaseColour(MeshId id, const Eigen::Vector3f& colour);
  void setTransform(MeshId id, const Eigen::Matrix4f& model);
  void setVisible(MeshId id, bool visible);

  /// Draws one frame. Read it with readPixels().
  void render(const Camera& camera, const Environment& environment);
  /// Waits until the rasteriser has finished what was submitted (for timing the stages apart).
  void finish();
  /// The last frame, rows top to bottom, as rasterised (finishImage() smooths its edges if asked).
  Image readPixels();
  /// Smooths the edges of a read-back frame when the settings ask for it (smooth_edges); may run on
  /// another thread than the renderer's.
  void finishImage(Image& image) const;
  /// render(), readPixels() and finishImage().
  Image renderImage(const Camera& camera, const Environment& environment);

  int width() const { return settings_.width; }
  int height() const { return settings_.height; }
  float aspect() const { return static_cast<float>(settings_.width) / static_cast<float>(settings_.height); }
  int samples() const { return samples_; }  ///< MSAA samples actually used (0: none)
  std::string description() const;          ///< GL renderer and version

  /// World-space box of the visible meshes (for shadow fitting and camera framing).
  Eigen::AlignedBox3f visibleBounds() const;

 private:
  struct GpuMesh;
  void createFramebuffers();
  void renderShadowMap(const SunShadow& shadow);

  RenderSettings settings_;
  std::unique_ptr<OffscreenContext> context_;
  int samples_ = 0;
  GLuint colour_fbo_ = 0, colour_rb_ = 0, depth_rb_ = 0;  ///< the frame (multisampled when samples_ > 0)
  GLuint resolve_fbo_ = 0, resolve_rb_ = 0;               ///< single-sample copy that is read back
  GLuint shadow_fbo_ = 0, shadow_texture_ = 0;
  GLuint empty_vao_ = 0;  ///< bound for the buffer-less sky and ground draws (core profile needs one)
  GpuProgram mesh_program_, ground_program_, shadow_program_, sky_program_;
  std::vector<std::unique_ptr<GpuMesh>> meshes_;
};

}  // namespace sandbox::render
