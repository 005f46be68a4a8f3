// Shader programs and vertex arrays (gl_program.hpp).
#include "gl_program.hpp"

#include <algorithm>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

namespace dentsph::viewer {

namespace {

// Nothing when the `status` query (GL_COMPILE_STATUS, GL_LINK_STATUS) of a shader or a program
// says it succeeded, else its info log, whole; read by its pair of queries (glGetShaderiv and
// glGetShaderInfoLog, or glGetProgramiv and glGetProgramInfoLog).
template <class GetIv, class GetLog>
std::optional<std::string> failure_log(GLuint id, GLenum status, GetIv get_iv, GetLog get_log) {
  GLint ok = 0;
  get_iv(id, status, &ok);
  if (ok) return std::nullopt;
  GLint length = 0;
  get_iv(id, GL_INFO_LOG_LENGTH, &length);
  std::string log(std::size_t(std::max(length, 1)), '\0');
  get_log(id, GLsizei(log.size()), nullptr, log.data());
  log.resize(std::strlen(log.c_str()));
  return log;
}

GLuint compile(const char* name, GLenum type, const char* src) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  if (const auto log = failure_log(s, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog)) {
    glDeleteShader(s);
    throw std::runtime_error(fmt::format("{} {} shader does not compile: {}", name,
                                         type == GL_VERTEX_SHADER ? "vertex" : "fragment", *log));
  }
  return s;
}

}  // namespace

GlProgram::GlProgram(const char* name, const char* vertex_src, const char* fragment_src) {
  const GLuint vs = compile(name, GL_VERTEX_SHADER, vertex_src);
  const GLuint fs = compile(name, GL_FRAGMENT_SHADER, fragment_src);
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glLinkProgram(id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  if (const auto log = failure_log(id_, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog)) {
    glDeleteProgram(id_);
    throw std::runtime_error(fmt::format("{} shader program does not link: {}", name, *log));
  }
}

GlProgram::~GlProgram() { glDeleteProgram(id_); }

void GlProgram::set(const char* name, const glm::mat4& m) const {
  glUniformMatrix4fv(uniform(name), 1, GL_FALSE, glm::value_ptr(m));
}
void GlProgram::set(const char* name, const glm::vec3& v) const { glUniform3fv(uniform(name), 1, glm::value_ptr(v)); }
void GlProgram::set(const char* name, const glm::vec4& v) const { glUniform4fv(uniform(name), 1, glm::value_ptr(v)); }
void GlProgram::set(const char* name, float f) const { glUniform1f(uniform(name), f); }

GlArrays::GlArrays(int attributes) : attributes_(attributes) {
  if (attributes < 1 || attributes > 4) throw std::invalid_argument("GlArrays: 1 to 4 attributes");
  glGenVertexArrays(1, &vao_);
  glGenBuffers(attributes, vbo_);
  glBindVertexArray(vao_);
  for (int a = 0; a < attributes; ++a) {
    glBindBuffer(GL_ARRAY_BUFFER, vbo_[a]);
    glEnableVertexAttribArray(GLuint(a));
    glVertexAttribPointer(GLuint(a), 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  }
  glBindVertexArray(0);
}

GlArrays::~GlArrays() {
  glDeleteBuffers(attributes_, vbo_);
  glDeleteVertexArrays(1, &vao_);
}

void GlArrays::upload(int a, const float* floats, std::size_t count) {
  glBindBuffer(GL_ARRAY_BUFFER, vbo_[a]);
  // Orphan and refill: the driver need not wait for the last frame's draw.
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(count * sizeof(float)), nullptr, GL_STREAM_DRAW);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(count * sizeof(float)), floats, GL_STREAM_DRAW);
}

}  // namespace dentsph::viewer
