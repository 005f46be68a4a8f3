// Bounding-volume hierarchy: build and the two traversals (see bvh.hpp).
#include "tooth/bvh.hpp"

#include <algorithm>
#include <limits>

namespace dentsph::tooth {

namespace {
constexpr std::uint32_t leaf_size = 4;
constexpr real inf = std::numeric_limits<real>::infinity();
}  // namespace

Bvh::Bvh(const TriMesh& mesh) {
  const auto n = std::uint32_t(mesh.triangles.size());
  std::vector<std::uint32_t> ids(n);
  std::vector<Vec3> centroids(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    ids[t] = t;
    const auto& tri = mesh.triangles[t];
    centroids[t] =
        (mesh.vertices[tri[0]] + mesh.vertices[tri[1]] + mesh.vertices[tri[2]]) / real(3);
  }
  nodes_.reserve(2 * (n / leaf_size + 1));
  corners_.reserve(n);
  ids_.reserve(n);
  if (n == 0) {
    nodes_.push_back({});
    return;
  }
  build(ids, centroids, 0, n, mesh);
}

std::uint32_t Bvh::build(std::vector<std::uint32_t>& ids, std::vector<Vec3>& centroids,
                         std::uint32_t begin, std::uint32_t end, const TriMesh& mesh) {
  const auto index = std::uint32_t(nodes_.size());
  nodes_.push_back({});
  Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf}, clo = lo, chi = hi;
  for (std::uint32_t i = begin; i < end; ++i) {
    for (std::uint32_t v : mesh.triangles[ids[i]]) {
      lo = vmin(lo, mesh.vertices[v]);
      hi = vmax(hi, mesh.vertices[v]);
    }
    clo = vmin(clo, centroids[ids[i]]);
    chi = vmax(chi, centroids[ids[i]]);
  }
  nodes_[index].lo = lo;
  nodes_[index].hi = hi;
  if (end - begin <= leaf_size) {
    nodes_[index].first = std::uint32_t(corners_.size());
    nodes_[index].count = end - begin;
    for (std::uint32_t i = begin; i < end; ++i) {
      const auto& tri = mesh.triangles[ids[i]];
      corners_.push_back({mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]});
      ids_.push_back(ids[i]);
    }
    return index;
  }
  const Vec3 ext = chi - clo;
  const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(
      ids.begin() + begin, ids.begin() + mid, ids.begin() + end,
      [&](std::uint32_t a, std::uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
  build(ids, centroids, begin, mid, mesh);  // left child is index + 1
  const std::uint32_t right = build(ids, centroids, mid, end, mesh);
  nodes_[index].first = right;
  return index;
}

Bvh::Nearest Bvh::nearest(const Vec3& p) const {
  Nearest best;
  best.distance2 = inf;
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (box_distance2(p, node.lo, node.hi) >= best.distance2) continue;
    if (node.count > 0) {
      for (std::uint32_t s = node.first; s < node.first + node.count; ++s) {
        const auto& c = corners_[s];
        const TrianglePoint tp = closest_on_triangle(p, c[0], c[1], c[2]);
        const real d2 = norm2(p - tp.point);
        if (d2 < best.distance2) best = {d2, ids_[s], tp};
      }
      continue;
    }
    // Visit the nearer child first: its triangles shrink the bound that prunes the other.
    const std::uint32_t left = std::uint32_t(&node - nodes_.data()) + 1, right = node.first;
    const real dl = box_distance2(p, nodes_[left].lo, nodes_[left].hi);
    const real dr = box_distance2(p, nodes_[right].lo, nodes_[right].hi);
    if (dl <= dr) {
      stack[top++] = right;
      stack[top++] = left;
    } else {
      stack[top++] = left;
      stack[top++] = right;
    }
  }
  return best;
}

std::optional<Bvh::Hit> Bvh::ray(const Vec3& o, const Vec3& d, real t_min) const {
  const Vec3 inv{1 / d.x, 1 / d.y, 1 / d.z};
  std::optional<Hit> hit;
  real t_max = inf;
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!ray_hits_box(o, inv, node.lo, node.hi, t_min, t_max)) continue;
    if (node.count > 0) {
      for (std::uint32_t s = node.first; s < node.first + node.count; ++s) {
        const auto& c = corners_[s];
        if (auto t = ray_triangle(o, d, c[0], c[1], c[2], t_min, t_max)) {
          t_max = *t;
          hit = Hit{*t, ids_[s]};
        }
      }
      continue;
    }
    stack[top++] = node.first;
    stack[top++] = std::uint32_t(&node - nodes_.data()) + 1;
  }
  return hit;
}

}  // namespace dentsph::tooth
