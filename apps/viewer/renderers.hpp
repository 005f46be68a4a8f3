// What the viewer draws: particles as lit sphere impostors, the tooth's surface (with the
// cavity cut away: the boundary particles line it), and arrows (the tool force, the curing light).
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "dentsph/curing_light.hpp"
#include "dentsph/tooth.hpp"
#include "gl_program.hpp"

namespace dentsph::viewer {

struct ViewUniforms {
  glm::mat4 view{1}, proj{1};
  float viewport_h = 1;
  glm::vec4 clip_plane{0, 0, 0, -1};  // world plane; fragments with dot(plane, (p, 1)) > 0 are cut away (none by default)
};

// Thousands of particles in one draw: point sprites shaded as spheres with correct depth.
class ParticleRenderer {
 public:
  ParticleRenderer();
  // xyz: [3n] m, rgb: [3n]; radius in m.
  void draw(const ViewUniforms& u, const std::vector<float>& xyz, const std::vector<float>& rgb, float radius);

 private:
  GlProgram program_;
  GlArrays arrays_{2};
};

// The tooth surface, lit from the camera, its inside (seen through the cavity) darker. Triangle
// corners carry the signed distance to the cavity's shape; fragments inside it are discarded, so
// the surface shows the outline of the preparation.
class ToothRenderer {
 public:
  explicit ToothRenderer(const PreparedTooth& tooth);
  void draw(const ViewUniforms& u);

 private:
  GlProgram program_;
  GlArrays arrays_{3};
  GLsizei vertices_ = 0;
};

// A surface of triangles with a normal per corner, in one colour (the paste's surface,
// dentsph/surface.hpp), uploaded when it changes.
class MeshRenderer {
 public:
  explicit MeshRenderer(const glm::vec3& colour);
  // Uploads the triangles of `vertices` (m), their corners' normals (area-weighted) and colour.
  void upload(const std::vector<Vec3>& vertices, const std::vector<std::array<std::uint32_t, 3>>& triangles);
  void draw(const ViewUniforms& u);

 private:
  GlProgram program_;
  GlArrays arrays_{3};
  GLsizei vertices_ = 0;
  glm::vec3 colour_;
  std::vector<float> pos_, normal_, colours_;  // reused between uploads
};

// Solid arrows (a cylinder and a cone), built per frame.
class ArrowRenderer {
 public:
  ArrowRenderer();
  // From `from` along `vec` (m), shaft radius `radius` (m), in `colour`.
  void add(const glm::vec3& from, const glm::vec3& vec, float radius, const glm::vec3& colour);
  void draw(const ViewUniforms& u);  // draws and clears what was added

 private:
  GlProgram program_;
  GlArrays arrays_{3};
  std::vector<float> pos_, normal_, colour_;
};

// The curing light as it is drawn: its light guide's axis (a grey rod 6 mm long ending at the exit
// window) and the beam it sends, collimated: twelve thin rods along the beam's edge from the
// window 5 mm forward, pale violet.
void add_curing_light(ArrowRenderer& arrows, const CuringLight& light);

}  // namespace dentsph::viewer
