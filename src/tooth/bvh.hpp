// A bounding-volume hierarchy over a mesh's triangles, for nearest-triangle and ray queries.
// Median split on the longest axis of the triangle centroids, at most 4 triangles a leaf: the
// tree is balanced (depth about log2(n / 4)) whatever the triangle sizes.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "dentsph/tooth.hpp"
#include "tooth/geometry.hpp"

namespace dentsph::tooth {

class Bvh {
 public:
  explicit Bvh(const TriMesh& mesh);

  struct Nearest {
    real distance2 = 0;          // m^2
    std::uint32_t triangle = 0;  // index into the mesh's triangles
    TrianglePoint at;
  };
  Nearest nearest(const Vec3& p) const;

  struct Hit {
    real t = 0;  // m along the (unit) direction
    std::uint32_t triangle = 0;
  };
  std::optional<Hit> ray(const Vec3& origin, const Vec3& direction, real t_min) const;

  Bounds bounds() const { return {nodes_[0].lo, nodes_[0].hi}; }

 private:
  struct Node {
    Vec3 lo, hi;
    std::uint32_t first = 0;  // leaf: first slot in corners_; inner: index of the right child
    std::uint32_t count = 0;  // leaf: triangles (> 0); inner: 0, the left child follows
  };
  std::uint32_t build(std::vector<std::uint32_t>& ids, std::vector<Vec3>& centroids,
                      std::uint32_t begin, std::uint32_t end, const TriMesh& mesh);

  std::vector<Node> nodes_;
  std::vector<std::array<Vec3, 3>> corners_;  // triangle corners in leaf order (locality)
  std::vector<std::uint32_t> ids_;            // mesh triangle index of each slot
};

}  // namespace dentsph::tooth
