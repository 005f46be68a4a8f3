// A linked OpenGL shader program; compile and link errors throw with the driver's log.
#pragma once

#include <epoxy/gl.h>
#include <glm/glm.hpp>

namespace dentsph::viewer {

class GlProgram {
 public:
  GlProgram(const char* name, const char* vertex_src, const char* fragment_src);
  ~GlProgram();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  void use() const { glUseProgram(id_); }
  GLint uniform(const char* name) const { return glGetUniformLocation(id_, name); }
  void set(const char* name, const glm::mat4& m) const;
  void set(const char* name, const glm::vec3& v) const;
  void set(const char* name, const glm::vec4& v) const;
  void set(const char* name, float f) const;

 private:
  GLuint id_ = 0;
};

// A vertex array with float attributes in separate buffers, refilled when the data changes.
class GlArrays {
 public:
  explicit GlArrays(int attributes);  // each attribute a vec3
  ~GlArrays();
  GlArrays(const GlArrays&) = delete;
  GlArrays& operator=(const GlArrays&) = delete;

  // Uploads `floats` (3 per vertex) to attribute `a`.
  void upload(int a, const float* floats, std::size_t count);
  void bind() const { glBindVertexArray(vao_); }

 private:
  GLuint vao_ = 0;
  GLuint vbo_[4] = {0, 0, 0, 0};
  int attributes_ = 0;
};

}  // namespace dentsph::viewer
