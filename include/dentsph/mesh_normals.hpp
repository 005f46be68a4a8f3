// A triangle mesh's normal at each vertex: the sum of its triangles' normals weighted by their
// area (a cross product's length is twice it), of unit length (zero for a vertex no triangle with
// an area touches). For lighting the tooth's and the paste's surfaces smoothly.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "dentsph/vec3.hpp"

namespace dentsph {

inline std::vector<Vec3> vertex_normals(std::span<const Vec3> vertices,
                                        std::span<const std::array<std::uint32_t, 3>> triangles) {
  std::vector<Vec3> n(vertices.size());
  for (const auto& t : triangles) {
    const Vec3 fn = cross(vertices[t[1]] - vertices[t[0]], vertices[t[2]] - vertices[t[0]]);
    for (const std::uint32_t v : t) n[v] += fn;
  }
  for (Vec3& v : n) {
    const real l = norm(v);
    if (l > 0) v = v / l;
  }
  return n;
}

}  // namespace dentsph
