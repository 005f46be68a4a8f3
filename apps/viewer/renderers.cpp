// Particle impostors, tooth surface, arrows (renderers.hpp).
#include "renderers.hpp"

#include <cmath>

#include "dentsph/mesh_normals.hpp"

namespace dentsph::viewer {

namespace {

constexpr const char* kParticleVs = R"(#version 330 core
layout(location = 0) in vec3 pos;
layout(location = 1) in vec3 colour;
uniform mat4 view, proj;
uniform float radius, viewport_h;
uniform vec4 clip_plane;
out vec3 v_colour;
out vec3 v_centre;
out float v_cut;
void main() {
  vec4 p = view * vec4(pos, 1.0);
  v_centre = p.xyz;
  v_colour = colour;
  v_cut = dot(clip_plane, vec4(pos, 1.0));
  gl_Position = proj * p;
  gl_PointSize = viewport_h * proj[1][1] * radius / gl_Position.w;
}
)";

constexpr const char* kParticleFs = R"(#version 330 core
in vec3 v_colour;
in vec3 v_centre;
in float v_cut;
uniform mat4 proj;
uniform float radius;
out vec4 frag;
void main() {
  if (v_cut > 0.0) discard;
  vec2 c = gl_PointCoord * 2.0 - 1.0;
  c.y = -c.y;
  float r2 = dot(c, c);
  if (r2 > 1.0) discard;
  vec3 n = vec3(c, sqrt(1.0 - r2));
  vec4 clip = proj * vec4(v_centre + n * radius, 1.0);
  gl_FragDepth = 0.5 * clip.z / clip.w + 0.5;
  vec3 l = normalize(vec3(0.4, 0.6, 1.0));
  float diffuse = max(dot(n, l), 0.0);
  float spec = pow(max(dot(n, normalize(l + vec3(0, 0, 1))), 0.0), 40.0);
  frag = vec4(v_colour * (0.35 + 0.65 * diffuse) + vec3(0.2 * spec), 1.0);
}
)";

// Lit triangles. `extra` is the colour (use_cut = 0) or, in x, the signed distance to the cavity
// (use_cut = 1: fragments inside it are discarded, and `colour` is the surface's colour).
constexpr const char* kSurfaceVs = R"(#version 330 core
layout(location = 0) in vec3 pos;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 extra;
uniform mat4 view, proj;
uniform vec4 clip_plane;
out vec3 v_normal;
out vec3 v_extra;
out float v_cut;
void main() {
  v_normal = mat3(view) * normal;
  v_extra = extra;
  v_cut = dot(clip_plane, vec4(pos, 1.0));
  gl_Position = proj * view * vec4(pos, 1.0);
}
)";

constexpr const char* kSurfaceFs = R"(#version 330 core
in vec3 v_normal;
in vec3 v_extra;
in float v_cut;
uniform float use_cut;
uniform vec3 colour;
out vec4 frag;
void main() {
  if (v_cut > 0.0) discard;
  if (use_cut > 0.5 && v_extra.x < 0.0) discard;
  vec3 base = use_cut > 0.5 ? colour : v_extra;
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) { n = -n; base *= 0.45; }
  vec3 l = normalize(vec3(0.4, 0.6, 1.0));
  float diffuse = max(dot(n, l), 0.0);
  float spec = pow(max(dot(n, normalize(l + vec3(0, 0, 1))), 0.0), 24.0);
  frag = vec4(base * (0.3 + 0.7 * diffuse) + vec3(0.15 * spec), 1.0);
}
)";

void set_view(const GlProgram& p, const ViewUniforms& u) {
  p.use();
  p.set("view", u.view);
  p.set("proj", u.proj);
  p.set("clip_plane", u.clip_plane);
}

}  // namespace

ParticleRenderer::ParticleRenderer() : program_("particle", kParticleVs, kParticleFs) {}

void ParticleRenderer::draw(const ViewUniforms& u, const std::vector<float>& xyz, const std::vector<float>& rgb,
                            float radius) {
  const std::size_t n = xyz.size() / 3;
  if (n == 0) return;
  set_view(program_, u);
  program_.set("radius", radius);
  program_.set("viewport_h", u.viewport_h);
  arrays_.upload(0, xyz.data(), xyz.size());
  arrays_.upload(1, rgb.data(), rgb.size());
  arrays_.bind();
  glEnable(GL_PROGRAM_POINT_SIZE);
  glDrawArrays(GL_POINTS, 0, GLsizei(n));
}

ToothRenderer::ToothRenderer(const PreparedTooth& tooth) : program_("tooth", kSurfaceVs, kSurfaceFs) {
  const TriMesh& mesh = tooth.tooth().mesh();
  const std::vector<Vec3> vn = vertex_normals(mesh.vertices, mesh.triangles);  // smooth normals
  std::vector<float> cut(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) cut[v] = float(tooth.cavity_distance(mesh.vertices[v]).distance);
  std::vector<float> pos, normal, extra;
  pos.reserve(9 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (std::uint32_t k : t) {
      const Vec3 p = mesh.vertices[k];
      const Vec3 n = norm(vn[k]) > 0 ? vn[k] : Vec3{0, 0, 1};
      pos.insert(pos.end(), {float(p.x), float(p.y), float(p.z)});
      normal.insert(normal.end(), {float(n.x), float(n.y), float(n.z)});
      extra.insert(extra.end(), {cut[k], 0.f, 0.f});
    }
  arrays_.upload(0, pos.data(), pos.size());
  arrays_.upload(1, normal.data(), normal.size());
  arrays_.upload(2, extra.data(), extra.size());
  vertices_ = GLsizei(pos.size() / 3);
}

void ToothRenderer::draw(const ViewUniforms& u) {
  set_view(program_, u);
  program_.set("use_cut", 1.f);
  program_.set("colour", glm::vec3(0.93f, 0.90f, 0.82f));
  arrays_.bind();
  glDrawArrays(GL_TRIANGLES, 0, vertices_);
}

MeshRenderer::MeshRenderer(const glm::vec3& colour) : program_("mesh", kSurfaceVs, kSurfaceFs), colour_(colour) {}

void MeshRenderer::upload(const std::vector<Vec3>& vertices, const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  const std::vector<Vec3> vn = vertex_normals(vertices, triangles);
  pos_.clear();
  normal_.clear();
  colours_.clear();
  for (const auto& t : triangles)
    for (std::uint32_t k : t) {
      const Vec3 p = vertices[k];
      const Vec3 n = norm(vn[k]) > 0 ? vn[k] : Vec3{0, 0, 1};
      pos_.insert(pos_.end(), {float(p.x), float(p.y), float(p.z)});
      normal_.insert(normal_.end(), {float(n.x), float(n.y), float(n.z)});
      colours_.insert(colours_.end(), {colour_.x, colour_.y, colour_.z});
    }
  vertices_ = GLsizei(pos_.size() / 3);
  if (vertices_ == 0) return;
  arrays_.upload(0, pos_.data(), pos_.size());
  arrays_.upload(1, normal_.data(), normal_.size());
  arrays_.upload(2, colours_.data(), colours_.size());
}

void MeshRenderer::draw(const ViewUniforms& u) {
  if (vertices_ == 0) return;
  set_view(program_, u);
  program_.set("use_cut", 0.f);
  arrays_.bind();
  glDrawArrays(GL_TRIANGLES, 0, vertices_);
}

ArrowRenderer::ArrowRenderer() : program_("arrow", kSurfaceVs, kSurfaceFs) {}

void ArrowRenderer::add(const glm::vec3& from, const glm::vec3& vec, float radius, const glm::vec3& colour) {
  const float len = glm::length(vec);
  if (!(len > 0) || !std::isfinite(len)) return;
  const glm::vec3 d = vec / len;
  const glm::vec3 helper = std::abs(d.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
  const glm::vec3 e1 = glm::normalize(glm::cross(d, helper)), e2 = glm::cross(d, e1);
  const float head = std::min(0.35f * len, 4 * radius);
  const glm::vec3 neck = from + d * (len - head);
  constexpr int kSides = 12;
  auto push = [&](const glm::vec3& p, const glm::vec3& n) {
    pos_.insert(pos_.end(), {p.x, p.y, p.z});
    normal_.insert(normal_.end(), {n.x, n.y, n.z});
    colour_.insert(colour_.end(), {colour.x, colour.y, colour.z});
  };
  for (int k = 0; k < kSides; ++k) {
    const float a0 = 6.2831853f * float(k) / kSides, a1 = 6.2831853f * float(k + 1) / kSides;
    const glm::vec3 r0 = std::cos(a0) * e1 + std::sin(a0) * e2, r1 = std::cos(a1) * e1 + std::sin(a1) * e2;
    // Shaft side.
    push(from + radius * r0, r0); push(from + radius * r1, r1); push(neck + radius * r1, r1);
    push(from + radius * r0, r0); push(neck + radius * r1, r1); push(neck + radius * r0, r0);
    // Cone.
    const glm::vec3 tip = from + vec;
    const glm::vec3 n0 = glm::normalize(r0 * head + d * (2 * radius)), n1 = glm::normalize(r1 * head + d * (2 * radius));
    push(neck + 2.f * radius * r0, n0); push(neck + 2.f * radius * r1, n1); push(tip, glm::normalize(n0 + n1));
  }
}

void ArrowRenderer::draw(const ViewUniforms& u) {
  if (pos_.empty()) return;
  set_view(program_, u);
  program_.set("use_cut", 0.f);
  arrays_.upload(0, pos_.data(), pos_.size());
  arrays_.upload(1, normal_.data(), normal_.size());
  arrays_.upload(2, colour_.data(), colour_.size());
  arrays_.bind();
  glDrawArrays(GL_TRIANGLES, 0, GLsizei(pos_.size() / 3));
  pos_.clear();
  normal_.clear();
  colour_.clear();
}

void add_curing_light(ArrowRenderer& arrows, const CuringLight& light) {
  const glm::vec3 tip(float(light.tip.x), float(light.tip.y), float(light.tip.z));
  glm::vec3 d(float(light.direction.x), float(light.direction.y), float(light.direction.z));
  if (!(glm::length(d) > 0)) return;
  d = glm::normalize(d);
  const float r = 0.5f * float(light.diameter);
  arrows.add(tip - 6e-3f * d, 6e-3f * d, 0.3e-3f, glm::vec3(0.8f, 0.8f, 0.82f));
  const glm::vec3 helper = std::abs(d.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
  const glm::vec3 e1 = glm::normalize(glm::cross(d, helper)), e2 = glm::cross(d, e1);
  constexpr int kRods = 12;
  for (int k = 0; k < kRods; ++k) {
    const float a = 6.2831853f * float(k) / kRods;
    arrows.add(tip + r * (std::cos(a) * e1 + std::sin(a) * e2), 5e-3f * d, 0.1e-3f, glm::vec3(0.7f, 0.7f, 1.0f));
  }
}

}  // namespace dentsph::viewer
