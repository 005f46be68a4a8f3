// Signed distance to a closed mesh: nearest triangle from the BVH, sign from the angle-weighted
// pseudo-normal of the nearest feature (face, edge or vertex). Baerentzen and Aanaes (2005)
// show that this sign is exact for a closed, manifold, consistently oriented mesh, where the
// face normal alone is wrong near edges and vertices.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "dentsph/tooth.hpp"
#include "tooth/bvh.hpp"
#include "tooth/geometry.hpp"

namespace dentsph {

using tooth::Feature;

struct MeshDistance::Impl {
  TriMesh mesh;
  tooth::Bvh bvh;
  std::vector<Vec3> face_normal;                 // unit (zero for a zero-area triangle)
  std::vector<std::array<Vec3, 3>> edge_normal;  // per triangle: edges 01, 12, 20
  std::vector<Vec3> vertex_normal;

  explicit Impl(TriMesh m) : mesh(std::move(m)), bvh(mesh) {
    const std::size_t nt = mesh.triangles.size();
    face_normal.resize(nt);
    edge_normal.resize(nt);
    vertex_normal.assign(mesh.vertices.size(), Vec3{});
    for (std::size_t t = 0; t < nt; ++t) {
      const auto& tri = mesh.triangles[t];
      const Vec3 a = mesh.vertices[tri[0]], b = mesh.vertices[tri[1]], c = mesh.vertices[tri[2]];
      const Vec3 n = tooth::normalized(cross(b - a, c - a));
      face_normal[t] = n;
      // Angle weights make the vertex normal independent of how the fan is triangulated.
      const Vec3 corner[3] = {a, b, c};
      for (int k = 0; k < 3; ++k) {
        const Vec3 e1 = tooth::normalized(corner[(k + 1) % 3] - corner[k]);
        const Vec3 e2 = tooth::normalized(corner[(k + 2) % 3] - corner[k]);
        const real angle = std::acos(std::clamp(dot(e1, e2), real(-1), real(1)));
        vertex_normal[tri[k]] += n * angle;
      }
    }
    // Edge pseudo-normal: the sum of the two faces' normals. Pair the half-edges by key.
    struct HalfEdge {
      std::uint64_t key;
      std::uint32_t triangle;
      std::uint8_t slot;
    };
    std::vector<HalfEdge> half;
    half.reserve(3 * nt);
    for (std::size_t t = 0; t < nt; ++t)
      for (std::uint8_t k = 0; k < 3; ++k) {
        std::uint64_t u = mesh.triangles[t][k], v = mesh.triangles[t][(k + 1) % 3];
        if (u > v) std::swap(u, v);
        half.push_back({(u << 32) | v, std::uint32_t(t), k});
      }
    std::sort(half.begin(), half.end(),
              [](const HalfEdge& x, const HalfEdge& y) { return x.key < y.key; });
    for (std::size_t i = 0; i < half.size();) {
      std::size_t j = i;
      Vec3 sum;
      while (j < half.size() && half[j].key == half[i].key) sum += face_normal[half[j++].triangle];
      for (std::size_t k = i; k < j; ++k) edge_normal[half[k].triangle][half[k].slot] = sum;
      i = j;
    }
  }

  Vec3 pseudo_normal(std::uint32_t t, Feature f) const {
    const auto& tri = mesh.triangles[t];
    switch (f) {
      case Feature::vertex0:
        return vertex_normal[tri[0]];
      case Feature::vertex1:
        return vertex_normal[tri[1]];
      case Feature::vertex2:
        return vertex_normal[tri[2]];
      case Feature::edge01:
        return edge_normal[t][0];
      case Feature::edge12:
        return edge_normal[t][1];
      case Feature::edge20:
        return edge_normal[t][2];
      case Feature::face:
        break;
    }
    return face_normal[t];
  }
};

MeshDistance::MeshDistance(TriMesh mesh) {
  if (mesh.triangles.empty())
    throw std::invalid_argument("MeshDistance: the mesh has no triangles (load it with load_mesh)");
  impl_ = std::make_shared<const Impl>(std::move(mesh));
}

const TriMesh& MeshDistance::mesh() const { return impl_->mesh; }
Bounds MeshDistance::bounds() const { return impl_->bvh.bounds(); }

SurfacePoint MeshDistance::query(const Vec3& p) const {
  const auto near = impl_->bvh.nearest(p);
  const Vec3 pn = impl_->pseudo_normal(near.triangle, near.at.feature);
  const Vec3 offset = p - near.at.point;
  const real d = std::sqrt(near.distance2);
  const bool inside = dot(offset, pn) < 0;
  SurfacePoint out;
  out.closest = near.at.point;
  out.distance = inside ? -d : d;
  // Away from the surface the gradient points from the nearest point to p (outward sense);
  // on the surface it is the pseudo-normal.
  out.normal = d > 1e-12 * (1 + norm(p)) ? offset / (inside ? -d : d) : tooth::normalized(pn);
  return out;
}

std::optional<real> MeshDistance::ray(const Vec3& origin, const Vec3& direction, real t_min) const {
  if (auto hit = impl_->bvh.ray(origin, direction, t_min)) return hit->t;
  return std::nullopt;
}

}  // namespace dentsph
