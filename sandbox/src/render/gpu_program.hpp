#pragma once
// A linked GLSL program and typed uniform setters. Compile and link errors throw with the driver's log
// and the program's name, since a shader bug is otherwise silent in an offscreen renderer.
#include "render/gl_functions.hpp"

#include <Eigen/Core>
#include <string>

namespace sandbox::render {

class GpuProgram {
 public:
  GpuProgram() = default;
  /// Compiles and links; throws std::runtime_error naming `name` with the info log on failure.
  GpuProgram(const std::string& name, const std::string& vertex_source, const std::string& fragment_source);
  ~GpuProgram();
  GpuProgram(GpuProgram&& other) noexcept;
  GpuProgram& operator=(GpuProgram&& other) noexcept;
  GpuProgram(const GpuProgram&) = delete;
  GpuProgram& operator=(const GpuProgram&) = delete;

  void use() const { gl::UseProgram(program_); }

  // Setters for the current program; a uniform the compiler optimised away is silently skipped.
  void set(const char* name, int value) const;
  void set(const char* name, float value) const;
  void set(const char* name, const Eigen::Vector2f& value) const;
  void set(const char* name, const Eigen::Vector3f& value) const;
  void set(const char* name, const Eigen::Matrix3f& value) const;
  void set(const char* name, const Eigen::Matrix4f& value) const;

 private:
  GLuint program_ = 0;
  std::string name_;
};

}  // namespace sandbox::render
