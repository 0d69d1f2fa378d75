#include "render/gpu_program.hpp"

#include <stdexcept>
#include <utility>
#include <vector>

namespace sandbox::render {
namespace {

GLuint compile(const std::string& program_name, GLenum stage, const std::string& source) {
  const GLuint shader = gl::CreateShader(stage);
  const char* text = source.c_str();
  gl::ShaderSource(shader, 1, &text, nullptr);
  gl::CompileShader(shader);
  GLint ok = GL_FALSE;
  gl::GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return shader;
  GLint length = 0;
  gl::GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<std::size_t>(length) + 1, '\0');
  gl::GetShaderInfoLog(shader, length, nullptr, log.data());
  gl::DeleteShader(shader);
  throw std::runtime_error("shader '" + program_name + "' (" +
                           (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                           ") does not compile: " + log.data());
}

}  // namespace

GpuProgram::GpuProgram(const std::string& name, const std::string& vertex_source,
                       const std::string& fragment_source)
    : name_(name) {
  const GLuint vertex = compile(name, GL_VERTEX_SHADER, vertex_source);
  GLuint fragment = 0;
  try {
    fragment = compile(name, GL_FRAGMENT_SHADER, fragment_source);
  } catch (...) {
    gl::DeleteShader(vertex);
    throw;
  }
  program_ = gl::CreateProgram();
  gl::AttachShader(program_, vertex);
  gl::AttachShader(program_, fragment);
  gl::LinkProgram(program_);
  gl::DeleteShader(vertex);
  gl::DeleteShader(fragment);
  GLint ok = GL_FALSE;
  gl::GetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok == GL_TRUE) return;
  GLint length = 0;
  gl::GetProgramiv(program_, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<std::size_t>(length) + 1, '\0');
  gl::GetProgramInfoLog(program_, length, nullptr, log.data());
  gl::DeleteProgram(program_);
  program_ = 0;
  throw std::runtime_error("shader program '" + name + "' does not link: " + log.data());
}

GpuProgram::~GpuProgram() {
  if (program_ != 0) gl::DeleteProgram(program_);
}

GpuProgram::GpuProgram(GpuProgram&& other) noexcept
    : program_(std::exchange(other.program_, 0)), name_(std::move(other.name_)) {}

GpuProgram& GpuProgram::operator=(GpuProgram&& other) noexcept {
  if (this != &other) {
    if (program_ != 0) gl::DeleteProgram(program_);
    program_ = std::exchange(other.program_, 0);
    name_ = std::move(other.name_);
  }
  return *this;
}

void GpuProgram::set(const char* name, int value) const {
  gl::Uniform1i(gl::GetUniformLocation(program_, name), value);
}

void GpuProgram::set(const char* name, float value) const {
  gl::Uniform1f(gl::GetUniformLocation(program_, name), value);
}

void GpuProgram::set(const char* name, const Eigen::Vector2f& value) const {
  gl::Uniform2f(gl::GetUniformLocation(program_, name), value.x(), value.y());
}

void GpuProgram::set(const char* name, const Eigen::Vector3f& value) const {
  gl::Uniform3fv(gl::GetUniformLocation(program_, name), 1, value.data());
}

// Eigen is column-major like GLSL, so no transpose is needed.
void GpuProgram::set(const char* name, const Eigen::Matrix3f& value) const {
  gl::UniformMatrix3fv(gl::GetUniformLocation(program_, name), 1, GL_FALSE, value.data());
}

void GpuProgram::set(const char* name, const Eigen::Matrix4f& value) const {
  gl::UniformMatrix4fv(gl::GetUniformLocation(program_, name), 1, GL_FALSE, value.data());
}

}  // namespace sandbox::render
