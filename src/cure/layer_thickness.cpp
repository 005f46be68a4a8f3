// layer_thickness() (include/dentsph/layer_thickness.hpp).
#include "dentsph/layer_thickness.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <numeric>
#include <set>
#include <utility>

namespace dentsph {

namespace {

// The q-quantile of `v` (nearest rank).
real quantile(std::vector<real> v, double q) {
  if (v.empty()) return 0;
  const auto k = v.begin() + std::ptrdiff_t(std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5)));
  std::nth_element(v.begin(), k, v.end());
  return *k;
}

}  // namespace

LayerThickness layer_thickness(const std::vector<Vec3>& points, const Vec3& up_in, real spacing) {
  LayerThickness t;
  t.spacing = spacing;
  if (points.empty()) return t;
  const Vec3 up = up_in / norm(up_in);
  const Vec3 side = std::abs(up.x) < 0.8 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 e1 = cross(up, side) / norm(cross(up, side));
  const Vec3 e2 = cross(up, e1);
  // Each point's cell a spacing square, and its column: the 2 x 2 cells around it.
  std::map<std::pair<long, long>, std::uint32_t> index;  // column's (e1, e2) -> column
  std::vector<std::set<std::pair<long, long>>> cells;      // each column's cells holding paste
  t.column.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const long a = std::lround(std::floor(dot(points[i], e1) / spacing)),
               b = std::lround(std::floor(dot(points[i], e2) / spacing));
    const std::pair<long, long> column{a >= 0 ? a / 2 : -((1 - a) / 2), b >= 0 ? b / 2 : -((1 - b) / 2)};
    const auto [it, added] = index.emplace(column, std::uint32_t(t.column_particles.size()));
    if (added) {
      t.column_particles.push_back(0);
      cells.emplace_back();
    }
    t.column[i] = it->second;
    ++t.column_particles[it->second];
    cells[it->second].insert({a, b});
  }
  t.column_cells.resize(cells.size());
  for (std::size_t c = 0; c < cells.size(); ++c) t.column_cells[c] = std::uint32_t(cells[c].size());
  // Depth: the particles above each one in its column (by height along `up`, ties by index).
  std::vector<std::uint32_t> order(points.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const real ha = dot(points[a], up), hb = dot(points[b], up);
    return ha != hb ? ha > hb : a < b;
  });
  std::vector<std::uint32_t> above(t.column_particles.size(), 0);
  t.depth.resize(points.size());
  for (const std::uint32_t i : order) t.depth[i] = above[t.column[i]]++ * spacing / t.column_cells[t.column[i]];
  std::vector<real> thick;
  thick.reserve(t.column_particles.size());
  for (std::uint32_t c = 0; c < t.column_particles.size(); ++c) thick.push_back(t.column_thickness(c));
  t.median = quantile(thick, 0.5);
  t.p90 = quantile(thick, 0.9);
  return t;
}

}  // namespace dentsph
