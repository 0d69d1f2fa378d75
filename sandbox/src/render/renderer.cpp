#include "render/renderer.hpp"

#include "render/edge_smoothing.hpp"
#include "render/shaders.hpp"

#include <deform/error.hpp>

#include <algorithm>
#include <stdexcept>

namespace sandbox::render {

// A mesh on the GPU: one buffer per attribute so positions can be replaced without touching the rest.
struct Renderer::GpuMesh {
  GLuint vao = 0, positions = 0, normals = 0, colours = 0, indices = 0;
  GLsizei index_count = 0;
  std::size_t vertex_count = 0;
  bool has_colours = false;
  bool visible = true;
  Eigen::Matrix4f model = Eigen::Matrix4f::Identity();
  Eigen::Vector3f base_colour{0.8f, 0.8f, 0.8f};
  float specular = 0.35f, shininess = 60.0f;
  bool closed = false;               ///< cull back faces (see MeshData::closed)
  Eigen::AlignedBox3f local_bounds;  ///< box of the current positions in the mesh frame

  ~GpuMesh() {
    const GLuint buffers[] = {positions, normals, colours, indices};
    gl::DeleteBuffers(4, buffers);
    gl::DeleteVertexArrays(1, &vao);
  }
};

namespace {

Eigen::AlignedBox3f boundsOf(const std::vector<Eigen::Vector3f>& points) {
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& p : points) box.extend(p);
  return box;
}

// sRGB -> linear light, as the shaders do (gamma 2.2), for colours passed as uniforms.
Eigen::Vector3f linear(const Eigen::Vector3f& srgb) {
  return srgb.cwiseMax(0.0f).array().pow(2.2f).matrix();
}

// Culls `face` for closed meshes; everything else is drawn two-sided (imported meshes are not always
// closed or consistently wound).
void setCulling(bool closed, GLenum face) {
  if (closed) {
    gl::Enable(GL_CULL_FACE);
    gl::CullFace(face);
  } else {
    gl::Disable(GL_CULL_FACE);
  }
}

GLsizeiptr bytes(std::size_t count, std::size_t element) {
  return static_cast<GLsizeiptr>(count * element);
}

void uploadVec3(GLuint buffer, const std::vector<Eigen::Vector3f>& data, GLenum usage) {
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "Vector3f must be tightly packed");
  gl::BindBuffer(GL_ARRAY_BUFFER, buffer);
  gl::BufferData(GL_ARRAY_BUFFER, bytes(data.size(), sizeof(Eigen::Vector3f)), data.data(), usage);
}

}  // namespace

Renderer::Renderer(const RenderSettings& settings) : settings_(settings) {
  if (settings_.width < 1 || settings_.width > 8192 || settings_.height < 1 || settings_.height > 8192) {
    throw deform::InputError("--width/--height: picture size must be 1..8192 pixels (got " +
                             std::to_string(settings_.width) + "x" + std::to_string(settings_.height) + ")");
  }
  context_ = std::make_unique<OffscreenContext>();
  mesh_program_ = GpuProgram("mesh", shaders::kMeshVertex, shaders::kMeshFragment);
  ground_program_ = GpuProgram("ground", shaders::kGroundVertex, shaders::kGroundFragment);
  shadow_program_ = GpuProgram("shadow", shaders::kShadowVertex, shaders::kShadowFragment);
  sky_program_ = GpuProgram("sky", shaders::kSkyVertex, shaders::kSkyFragment);
  gl::GenVertexArrays(1, &empty_vao_);
  createFramebuffers();
  gl::checkError("creating the renderer");
}

Renderer::~Renderer() {
  if (!context_) return;
  context_->makeCurrent();
  meshes_.clear();
  gl::DeleteFramebuffers(1, &colour_fbo_);
  gl::DeleteFramebuffers(1, &resolve_fbo_);
  gl::DeleteFramebuffers(1, &shadow_fbo_);
  const GLuint renderbuffers[] = {colour_rb_, depth_rb_, resolve_rb_};
  gl::DeleteRenderbuffers(3, renderbuffers);
  gl::DeleteTextures(1, &shadow_texture_);
  gl::DeleteVertexArrays(1, &empty_vao_);
  // Programs are deleted by their destructors, which run before the context (declared later).
}

void Renderer::createFramebuffers() {
  const GLsizei w = settings_.width, h = settings_.height;
  GLint max_samples = 0;
  gl::GetIntegerv(GL_MAX_SAMPLES, &max_samples);
  const int wanted = settings_.smooth_edges ? 0 : settings_.samples;
  samples_ = wanted > 1 ? std::min(wanted, static_cast<int>(max_samples)) : 0;
  if (samples_ < 2) samples_ = 0;

  // The frame: colour + depth renderbuffers, multisampled when the driver allows.
  for (;;) {
    gl::GenFramebuffers(1, &colour_fbo_);
    gl::GenRenderbuffers(1, &colour_rb_);
    gl::GenRenderbuffers(1, &depth_rb_);
    gl::BindFramebuffer(GL_FRAMEBUFFER, colour_fbo_);
    gl::BindRenderbuffer(GL_RENDERBUFFER, colour_rb_);
    gl::RenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_RGBA8, w, h);
    gl::FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_rb_);
    gl::BindRenderbuffer(GL_RENDERBUFFER, depth_rb_);
    gl::RenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_DEPTH_COMPONENT24, w, h);
    gl::FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb_);
    if (gl::CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE) break;
    if (samples_ == 0) throw std::runtime_error("cannot create the offscreen framebuffer");
    // No multisampling at this size: fall back to plain rendering rather than failing.
    gl::DeleteFramebuffers(1, &colour_fbo_);
    const GLuint rbs[] = {colour_rb_, depth_rb_};
    gl::DeleteRenderbuffers(2, rbs);
    samples_ = 0;
  }

  // Single-sample target the multisampled frame resolves into.
  gl::GenFramebuffers(1, &resolve_fbo_);
  gl::GenRenderbuffers(1, &resolve_rb_);
  gl::BindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_);
  gl::BindRenderbuffer(GL_RENDERBUFFER, resolve_rb_);
  gl::RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
  gl::FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_rb_);
  if (gl::CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("cannot create the offscreen resolve framebuffer");
  }

  // Shadow map: a depth texture compared in hardware (each lookup is a 2x2 bilinear PCF already).
  const GLsizei s = settings_.shadow_map_size;
  gl::GenTextures(1, &shadow_texture_);
  gl::BindTexture(GL_TEXTURE_2D, shadow_texture_);
  gl::TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, s, s, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  const float far_border[] = {1.0f, 1.0f, 1.0f, 1.0f};
  gl::TexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, far_border);
  gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  gl::GenFramebuffers(1, &shadow_fbo_);
  gl::BindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
  gl::FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadow_texture_, 0);
  gl::DrawBuffer(GL_NONE);
  gl::ReadBuffer(GL_NONE);
  if (gl::CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("cannot create the shadow-map framebuffer");
  }
  gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
}

Renderer::MeshId Renderer::addMesh(const MeshData& data) {
  context_->makeCurrent();
  if (data.normals.size() != data.positions_m.size()) {
    throw std::invalid_argument("Renderer::addMesh: one normal per position is needed");
  }
  if (!data.colours.empty() && data.colours.size() != data.positions_m.size()) {
    throw std::invalid_argument("Renderer::addMesh: one colour per position is needed");
  }
  auto mesh = std::make_unique<GpuMesh>();
  mesh->vertex_count = data.positions_m.size();
  mesh->index_count = static_cast<GLsizei>(data.triangles.size() * 3);
  mesh->model = data.model;
  mesh->base_colour = data.base_colour;
  mesh->specular = data.specular;
  mesh->shininess = data.shininess;
  mesh->closed = data.closed;
  mesh->local_bounds = boundsOf(data.positions_m);

  gl::GenVertexArrays(1, &mesh->vao);
  gl::BindVertexArray(mesh->vao);
  GLuint buffers[4];
  gl::GenBuffers(4, buffers);
  mesh->positions = buffers[0];
  mesh->normals = buffers[1];
  mesh->colours = buffers[2];
  mesh->indices = buffers[3];
  // Positions and normals change every frame of a deforming car: DYNAMIC_DRAW.
  uploadVec3(mesh->positions, data.positions_m, GL_DYNAMIC_DRAW);
  gl::VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  gl::EnableVertexAttribArray(0);
  uploadVec3(mesh->normals, data.normals, GL_DYNAMIC_DRAW);
  gl::VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  gl::EnableVertexAttribArray(1);
  gl::BindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh->indices);
  static_assert(sizeof(deform::Triangle) == 3 * sizeof(uint32_t), "Triangle must be three packed indices");
  gl::BufferData(GL_ELEMENT_ARRAY_BUFFER, bytes(data.triangles.size(), sizeof(deform::Triangle)),
                 data.triangles.data(), GL_STATIC_DRAW);
  gl::BindVertexArray(0);
  meshes_.push_back(std::move(mesh));
  const MeshId id = meshes_.size() - 1;
  if (!data.colours.empty()) setColours(id, data.colours);
  gl::checkError("uploading a mesh");
  return id;
}

void Renderer::updatePositions(MeshId id, const std::vector<Eigen::Vector3f>& positions_m,
                               const std::vector<Eigen::Vector3f>& normals) {
  context_->makeCurrent();
  GpuMesh& mesh = *meshes_.at(id);
  if (positions_m.size() != mesh.vertex_count || (!normals.empty() && normals.size() != mesh.vertex_count)) {
    throw std::invalid_argument("Renderer::updatePositions: vertex count differs from the uploaded mesh");
  }
  gl::BindBuffer(GL_ARRAY_BUFFER, mesh.positions);
  gl::BufferSubData(GL_ARRAY_BUFFER, 0, bytes(positions_m.size(), sizeof(Eigen::Vector3f)),
                    positions_m.data());
  if (!normals.empty()) {
    gl::BindBuffer(GL_ARRAY_BUFFER, mesh.normals);
    gl::BufferSubData(GL_ARRAY_BUFFER, 0, bytes(normals.size(), sizeof(Eigen::Vector3f)), normals.data());
  }
  mesh.local_bounds = boundsOf(positions_m);
}

void Renderer::setColours(MeshId id, const std::vector<Eigen::Vector3f>& colours) {
  context_->makeCurrent();
  GpuMesh& mesh = *meshes_.at(id);
  gl::BindVertexArray(mesh.vao);
  if (colours.empty()) {
    gl::DisableVertexAttribArray(2);  // the shader then sees the constant set per draw (base colour)
    mesh.has_colours = false;
  } else {
    if (colours.size() != mesh.vertex_count) {
      gl::BindVertexArray(0);
      throw std::invalid_argument("Renderer::setColours: one colour per vertex is needed");
    }
    uploadVec3(mesh.colours, colours, GL_DYNAMIC_DRAW);
    gl::VertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    gl::EnableVertexAttribArray(2);
    mesh.has_colours = true;
  }
  gl::BindVertexArray(0);
}

void Renderer::setBaseColour(MeshId id, const Eigen::Vector3f& colour) {
  meshes_.at(id)->base_colour = colour;
}
void Renderer::setTransform(MeshId id, const Eigen::Matrix4f& model) {
  meshes_.at(id)->model = model;
}
void Renderer::setVisible(MeshId id, bool visible) {
  meshes_.at(id)->visible = visible;
}

Eigen::AlignedBox3f Renderer::visibleBounds() const {
  Eigen::AlignedBox3f world;
  for (const auto& mesh : meshes_) {
    if (!mesh->visible || mesh->local_bounds.isEmpty()) continue;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3f p =
          mesh->local_bounds.corner(static_cast<Eigen::AlignedBox3f::CornerType>(corner));
      world.extend((mesh->model * p.homogeneous()).hnormalized());
    }
  }
  return world;
}

void Renderer::renderShadowMap(const SunShadow& shadow) {
  gl::BindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
  gl::Viewport(0, 0, settings_.shadow_map_size, settings_.shadow_map_size);
  gl::Clear(GL_DEPTH_BUFFER_BIT);
  // Slope-scaled offset on top of the shader's bias: steep faces are the ones that acne.
  gl::Enable(GL_POLYGON_OFFSET_FILL);
  gl::PolygonOffset(1.5f, 2.0f);
  shadow_program_.use();
  shadow_program_.set("u_light_view_projection", shadow.light_view_projection);
  for (const auto& mesh : meshes_) {
    if (!mesh->visible || mesh->index_count == 0) continue;
    // Closed meshes cast from their back faces: the lit front faces then never shadow themselves.
    setCulling(mesh->closed, GL_FRONT);
    shadow_program_.set("u_model", mesh->model);
    gl::BindVertexArray(mesh->vao);
    gl::DrawElements(GL_TRIANGLES, mesh->index_count, GL_UNSIGNED_INT, nullptr);
  }
  gl::Disable(GL_POLYGON_OFFSET_FILL);
  gl::Disable(GL_CULL_FACE);
}

void Renderer::render(const Camera& camera, const Environment& environment) {
  context_->makeCurrent();
  const Eigen::Matrix4f view_projection = camera.projection(aspect()) * camera.view();
  const Eigen::Vector3f sun = environment.sun_direction.normalized();
  const Ground& ground = environment.ground;
  gl::Enable(GL_DEPTH_TEST);
  gl::DepthFunc(GL_LESS);
  gl::FrontFace(GL_CCW);

  // 1. Sun shadow map, fitted to what casts shadows near where the camera looks: a long wall or a
  //    second car far away must not spread the map's texels over the whole scene. The region and the
  //    penumbra scale with the viewing distance, so the shadows look alike for a can and for a car.
  const float view_distance = std::max((camera.target_m - camera.eye_m).norm(), 1e-4f);
  const Eigen::Vector3f reach = Eigen::Vector3f::Constant(settings_.shadow_reach * view_distance);
  const Eigen::AlignedBox3f casters =
      visibleBounds().intersection(Eigen::AlignedBox3f(camera.target_m - reach, camera.target_m + reach));
  const bool shadows = environment.shadows && !casters.isEmpty() && sun.z() > 0.0f;
  SunShadow shadow;
  if (shadows) {
    const float penumbra = settings_.penumbra_fraction * view_distance;
    const float floor = ground.visible ? std::min(ground.height_m, casters.min().z()) : casters.min().z();
    shadow = fitSunShadow(casters, floor, sun, penumbra, settings_.shadow_map_size);
    renderShadowMap(shadow);
  }

  // 2. The frame: meshes, ground, sky (or plain background). Front to back: llvmpipe tests depth before
  //    shading, so the ground is not shaded under the car, nor the sky under either.
  gl::BindFramebuffer(GL_FRAMEBUFFER, colour_fbo_);
  gl::Viewport(0, 0, settings_.width, settings_.height);
  const Eigen::Vector3f clear = environment.sky ? environment.sky_horizon : environment.background;
  gl::ClearColor(clear.x(), clear.y(), clear.z(), 1.0f);
  gl::Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  gl::ActiveTexture(GL_TEXTURE0);
  gl::BindTexture(GL_TEXTURE_2D, shadow_texture_);
  const auto setLighting = [&](const GpuProgram& program) {
    program.use();
    program.set("u_view_projection", view_projection);
    program.set("u_light_view_projection", shadow.light_view_projection);
    program.set("u_sun_direction", sun);
    program.set("u_sun_radiance",
                Eigen::Vector3f(linear(environment.sun_colour) * environment.sun_intensity));
    program.set("u_sky_ambient",
                Eigen::Vector3f(linear(environment.sky_light) * environment.ambient_intensity));
    program.set("u_ground_ambient",
                Eigen::Vector3f(linear(environment.ground_light) * environment.ambient_intensity));
    program.set("u_eye", camera.eye_m);
    program.set("u_shadows", shadows ? 1 : 0);
    program.set("u_shadow_map", 0);
    program.set("u_shadow_radius", shadow.pcf_radius_uv);
    program.set("u_shadow_bias", shadow.depth_bias);
    program.set("u_shadow_slope_bias", shadow.slope_bias);
  };

  setLighting(mesh_program_);
  for (const auto& mesh : meshes_) {
    if (!mesh->visible || mesh->index_count == 0) continue;
    setCulling(mesh->closed, GL_BACK);
    mesh_program_.set("u_model", mesh->model);
    const Eigen::Matrix3f normal_matrix = mesh->model.topLeftCorner<3, 3>().inverse().transpose();
    mesh_program_.set("u_normal_matrix", normal_matrix);
    mesh_program_.set("u_specular", mesh->specular);
    mesh_program_.set("u_shininess", mesh->shininess);
    // Without a colour array the attribute reads this constant (generic vertex attribute state).
    gl::VertexAttrib3f(2, mesh->base_colour.x(), mesh->base_colour.y(), mesh->base_colour.z());
    gl::BindVertexArray(mesh->vao);
    gl::DrawElements(GL_TRIANGLES, mesh->index_count, GL_UNSIGNED_INT, nullptr);
  }
  gl::Disable(GL_CULL_FACE);

  if (ground.visible) {
    setLighting(ground_program_);
    ground_program_.set("u_centre", ground.centre_m);
    ground_program_.set("u_radius", ground.radius_m);
    ground_program_.set("u_height", ground.height_m);
    ground_program_.set("u_grid_spacing", ground.grid_spacing_m);
    ground_program_.set("u_ground_linear", linear(ground.colour));
    ground_program_.set("u_line_linear", linear(ground.line_colour));
    ground_program_.set("u_horizon", environment.sky ? environment.sky_horizon : environment.background);
    // The ground is drawn pushed back a little so coplanar mesh faces (a box resting on it) win.
    gl::Enable(GL_POLYGON_OFFSET_FILL);
    gl::PolygonOffset(1.0f, 1.0f);
    gl::BindVertexArray(empty_vao_);
    gl::DrawArrays(GL_TRIANGLES, 0, 6);
    gl::Disable(GL_POLYGON_OFFSET_FILL);
  }

  if (environment.sky) {
    // Depth-tested with GL_LESS as when it was drawn first: at the far plane, where the depth buffer is
    // cleared to, it passes nowhere, and the frames keep the plain horizon colour they always had.
    gl::DepthMask(GL_FALSE);
    sky_program_.use();
    sky_program_.set("u_inverse_view_projection", Eigen::Matrix4f(view_projection.inverse()));
    sky_program_.set("u_zenith", environment.sky_zenith);
    sky_program_.set("u_horizon", environment.sky_horizon);
    gl::BindVertexArray(empty_vao_);
    gl::DrawArrays(GL_TRIANGLES, 0, 3);
    gl::DepthMask(GL_TRUE);
  }
  gl::BindVertexArray(0);

  // 3. Resolve the multisampled frame into the single-sample one that is read back.
  if (samples_ > 0) {
    gl::BindFramebuffer(GL_READ_FRAMEBUFFER, colour_fbo_);
    gl::BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
    gl::BlitFramebuffer(0, 0, settings_.width, settings_.height, 0, 0, settings_.width, settings_.height,
                        GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  gl::checkError("rendering a frame");
}

void Renderer::finish() {
  context_->makeCurrent();
  gl::Finish();
}

Image Renderer::readPixels() {
  context_->makeCurrent();
  Image image;
  image.width = settings_.width;
  image.height = settings_.height;
  const std::size_t stride = static_cast<std::size_t>(image.width) * 4;
  const auto rows = static_cast<std::size_t>(image.height);
  image.rgba.resize(stride * rows);
  gl::BindFramebuffer(GL_READ_FRAMEBUFFER, samples_ > 0 ? resolve_fbo_ : colour_fbo_);
  gl::ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::ReadPixels(0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  gl::checkError("reading pixels back");
  // OpenGL's rows start at the bottom; images (PNG, video) start at the top. Swapped in place: a
  // second 3.7 MB buffer per 720p frame is not needed.
  for (std::size_t y = 0; y < rows / 2; ++y) {
    uint8_t* top = image.rgba.data() + y * stride;
    std::swap_ranges(top, top + stride, image.rgba.data() + (rows - 1 - y) * stride);
  }
  return image;
}

void Renderer::finishImage(Image& image) const {
  if (settings_.smooth_edges) smoothEdges(image);
}

Image Renderer::renderImage(const Camera& camera, const Environment& environment) {
  render(camera, environment);
  Image image = readPixels();
  finishImage(image);
  return image;
}

std::string Renderer::description() const {
  const std::string anti_aliasing = samples_ > 0             ? ", " + std::to_string(samples_) + "x MSAA"
                                    : settings_.smooth_edges ? ", edges smoothed after readback"
                                                             : ", no anti-aliasing";
  return context_->description() + anti_aliasing;
}

}  // namespace sandbox::render
