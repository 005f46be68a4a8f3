// Orbit camera (camera.hpp).
#include "camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace dentsph::viewer {

namespace {
glm::vec3 g(const Vec3& v) { return {float(v.x), float(v.y), float(v.z)}; }
}  // namespace

Vec3 Camera::eye() const {
  const Vec3 third = cross(up, side);
  const Vec3 dir = side * (std::cos(pitch) * std::cos(yaw)) + third * (std::cos(pitch) * std::sin(yaw)) +
                   up * std::sin(pitch);
  return target + dir * distance;
}

Vec3 Camera::forward() const {
  const Vec3 d = target - eye();
  return d / norm(d);
}

Vec3 Camera::right() const {
  const Vec3 r = cross(forward(), up);
  return r / norm(r);
}

Vec3 Camera::screen_up() const { return cross(right(), forward()); }

glm::mat4 Camera::view() const { return glm::lookAt(g(eye()), g(target), g(up)); }

glm::mat4 Camera::projection(float aspect) const {
  return glm::perspective(fov_y, std::max(aspect, 1e-3f), distance * 0.02f, distance * 20.f);
}

void Camera::orbit(float dx_px, float dy_px) {
  yaw -= 0.01f * dx_px;
  pitch = std::clamp(pitch + 0.01f * dy_px, -1.5f, 1.5f);
}

void Camera::zoom(float steps) { distance = std::clamp(distance * std::pow(0.9f, steps), 1e-3f, 1.f); }

void Camera::pan(float dx_px, float dy_px, int viewport_h) { target -= view_plane_offset(dx_px, dy_px, viewport_h); }

Vec3 Camera::view_plane_offset(float dx_px, float dy_px, int viewport_h) const {
  const real metres_per_px = 2 * distance * std::tan(0.5f * fov_y) / std::max(1, viewport_h);
  return right() * (dx_px * metres_per_px) - screen_up() * (dy_px * metres_per_px);
}

}  // namespace dentsph::viewer
