// A set of points hashed into cells, asked whether any of its points lies within a radius of a
// given one: the boundary sampler's Poisson-disk thinning (boundary.cpp) and the procedure's free
// lattice sites (src/scene/procedure.cpp). Also the cell key and hash a grid of points uses
// (mesh_repair.cpp's vertex merging).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "dentsph/vec3.hpp"

namespace dentsph {

// The cell of a point on a grid of cubes of edge `edge` (floor of each coordinate / edge).
struct CellKey {
  std::int64_t i, j, k;
  bool operator==(const CellKey&) const = default;
};
inline CellKey cell_of(const Vec3& p, real edge) {
  return {std::int64_t(std::floor(p.x / edge)), std::int64_t(std::floor(p.y / edge)),
          std::int64_t(std::floor(p.z / edge))};
}
struct CellHash {
  std::size_t operator()(const CellKey& c) const {
    // Unsigned: the products wrap instead of overflowing.
    return std::size_t(std::uint64_t(c.i) * 73856093u ^ std::uint64_t(c.j) * 19349663u ^
                       std::uint64_t(c.k) * 83492791u);
  }
};

// Points in cells of edge `radius`: near(p) looks at the 27 cells around p's own, so a query
// costs the points nearby, not all of them. With a radius of 0 or less (or NaN) no point is near
// another, and the set keeps nothing.
class DiskSet {
 public:
  explicit DiskSet(real radius) : r_(radius) {}

  // Whether some point of the set lies closer than the radius to p (strictly).
  bool near(const Vec3& p) const {
    if (!(r_ > 0)) return false;
    const CellKey c = cell_of(p, r_);
    for (std::int64_t di = -1; di <= 1; ++di)
      for (std::int64_t dj = -1; dj <= 1; ++dj)
        for (std::int64_t dk = -1; dk <= 1; ++dk) {
          const auto it = cells_.find({c.i + di, c.j + dj, c.k + dk});
          if (it == cells_.end()) continue;
          for (const Vec3& q : it->second)
            if (norm2(p - q) < r_ * r_) return true;
        }
    return false;
  }
  void add(const Vec3& p) {
    if (r_ > 0) cells_[cell_of(p, r_)].push_back(p);
  }
  // Adds p unless a point of the set is nearer than the radius; says whether it did.
  bool try_add(const Vec3& p) {
    if (near(p)) return false;
    add(p);
    return true;
  }

 private:
  real r_;
  std::unordered_map<CellKey, std::vector<Vec3>, CellHash> cells_;
};

}  // namespace dentsph
