// An orbiting camera around a target, with a fixed up axis (the tooth's long axis), and the
// mapping of mouse motion to world motion in the view plane (to move the tool with the mouse).
#pragma once

#include <glm/glm.hpp>

#include "dentsph/vec3.hpp"

namespace dentsph::viewer {

struct Camera {
  Vec3 target;                 // m, the point orbited
  Vec3 up{0, 0, 1};            // unit, world axis kept vertical on screen
  Vec3 side{1, 0, 0};          // unit, perpendicular to up: yaw 0 looks from +side
  float yaw = 0.9f;            // rad, about `up`
  float pitch = 0.6f;          // rad, above the plane normal to `up`, in (-1.5, 1.5)
  float distance = 0.03f;      // m, eye to target
  float fov_y = 0.7f;          // rad, vertical field of view

  Vec3 eye() const;
  Vec3 forward() const;        // unit, eye to target
  Vec3 right() const;          // unit, screen right
  Vec3 screen_up() const;      // unit, screen up
  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;

  void orbit(float dx_px, float dy_px);              // drag: 0.01 rad per pixel
  void zoom(float steps);                            // wheel steps: 10% each
  void pan(float dx_px, float dy_px, int viewport_h);
  // World displacement that follows the cursor at the target's depth for a drag of (dx, dy)
  // pixels (y down, as window coordinates).
  Vec3 view_plane_offset(float dx_px, float dy_px, int viewport_h) const;
};

}  // namespace dentsph::viewer
