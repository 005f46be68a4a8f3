// Lattice samplers of the scene's shapes; see shapes.hpp for the exact point sets.
#include "scene/shapes.hpp"

#include <cmath>

namespace dentsph::scene {

namespace {

// Slack (in spacings) for points that land on a boundary up to rounding: 0.29 / 0.01 is
// 28.999999999999996 in binary floating point, and the point at 0.29 belongs to the box.
constexpr real boundary_slack = 1e-9;

template <class... Fs>
struct Visitor : Fs... {
  using Fs::operator()...;
};
template <class... Fs>
Visitor(Fs...) -> Visitor<Fs...>;  // clang 14 lacks aggregate deduction

// Largest k >= 0 with k^2 <= r (r >= 0), exact for 64-bit integers in range.
std::int64_t isqrt(std::int64_t r) {
  auto k = std::int64_t(std::sqrt(double(r)));
  while (k * k > r) --k;
  while ((k + 1) * (k + 1) <= r) ++k;
  return k;
}

// Box: highest index per axis, floor((max - min) / s) with the slack.
real box_last_index(real lo, real hi, real s) { return std::floor((hi - lo) / s + boundary_slack); }

// Sphere: a lattice point s (i, j, k) from the centre is inside when i^2 + j^2 + k^2 <= q, an
// integer test, so the point set is exactly symmetric under the 48 lattice symmetries.
std::int64_t sphere_q(real radius, real s) {
  const real r = radius / s + boundary_slack;
  return std::int64_t(std::floor(r * r));
}

// Calls f(i, j, k_max) for every column (i, j) of the sphere that holds points k in
// [-k_max, k_max].
template <class F>
void for_each_sphere_column(std::int64_t q, F&& f) {
  const std::int64_t m = isqrt(q);
  for (std::int64_t j = -m; j <= m; ++j)
    for (std::int64_t i = -m; i <= m; ++i) {
      const std::int64_t rest = q - i * i - j * j;
      if (rest >= 0) f(i, j, isqrt(rest));
    }
}

double sphere_count(const SphereShape& sp, real s) {
  const real r = sp.radius / s;
  // Beyond ~500 spacings of radius the sphere holds over 5e8 points: no need to count them.
  if (r > 500) return 4.0 / 3.0 * 3.14159265358979323846 * r * r * r;
  double n = 0;
  for_each_sphere_column(sphere_q(sp.radius, s), [&](std::int64_t, std::int64_t, std::int64_t k) {
    n += double(2 * k + 1);
  });
  return n;
}

struct ContainerIndexRange {
  std::int64_t n[3];   // inner cells per axis
  std::int64_t lo[3];  // lowest index per axis (-layers)
  std::int64_t hi[3];  // highest index per axis
};

ContainerIndexRange container_range(const ContainerShape& c, real s) {
  ContainerIndexRange r{};
  for (int ax = 0; ax < 3; ++ax) {
    r.n[ax] = std::int64_t(container_cells(c.min[ax], c.max[ax], s));
    r.lo[ax] = -c.layers;
    r.hi[ax] = r.n[ax] + c.layers;
  }
  if (c.open_top) r.hi[2] = r.n[2];
  return r;
}

double container_count(const ContainerShape& c, real s) {
  double outer = 1, inner = 1;
  for (int ax = 0; ax < 3; ++ax) {
    const real n = container_cells(c.min[ax], c.max[ax], s);
    const real hi = (ax == 2 && c.open_top) ? n : n + c.layers;
    outer *= hi + c.layers + 1;
    inner *= n + 1;
  }
  return outer - inner;
}

Vec3 lattice_point(const Vec3& base, real s, std::int64_t i, std::int64_t j, std::int64_t k) {
  return base + Vec3{real(i) * s, real(j) * s, real(k) * s};
}

std::vector<Vec3> sample_box(const BoxShape& b, real s) {
  const auto nx = std::int64_t(box_last_index(b.min.x, b.max.x, s));
  const auto ny = std::int64_t(box_last_index(b.min.y, b.max.y, s));
  const auto nz = std::int64_t(box_last_index(b.min.z, b.max.z, s));
  std::vector<Vec3> pts;
  pts.reserve(std::size_t((nx + 1) * (ny + 1) * (nz + 1)));
  for (std::int64_t k = 0; k <= nz; ++k)
    for (std::int64_t j = 0; j <= ny; ++j)
      for (std::int64_t i = 0; i <= nx; ++i) pts.push_back(lattice_point(b.min, s, i, j, k));
  return pts;
}

std::vector<Vec3> sample_sphere(const SphereShape& sp, real s) {
  const std::int64_t q = sphere_q(sp.radius, s);
  const std::int64_t m = isqrt(q);
  std::vector<Vec3> pts;
  pts.reserve(std::size_t(sphere_count(sp, s)));
  for (std::int64_t k = -m; k <= m; ++k)
    for (std::int64_t j = -m; j <= m; ++j)
      for (std::int64_t i = -m; i <= m; ++i)
        if (i * i + j * j + k * k <= q) pts.push_back(lattice_point(sp.center, s, i, j, k));
  return pts;
}

std::vector<Vec3> sample_lattice(const LatticeShape& l, real s) {
  std::vector<Vec3> pts;
  pts.reserve(std::size_t(l.count[0] * l.count[1] * l.count[2]));
  for (std::int64_t k = 0; k < l.count[2]; ++k)
    for (std::int64_t j = 0; j < l.count[1]; ++j)
      for (std::int64_t i = 0; i < l.count[0]; ++i)
        pts.push_back(lattice_point(l.origin, s, i, j, k));
  return pts;
}

std::vector<Vec3> sample_container(const ContainerShape& c, real s) {
  const ContainerIndexRange r = container_range(c, s);
  auto inner = [&](int ax, std::int64_t idx) { return idx >= 0 && idx <= r.n[ax]; };
  std::vector<Vec3> pts;
  pts.reserve(std::size_t(container_count(c, s)));
  for (std::int64_t k = r.lo[2]; k <= r.hi[2]; ++k)
    for (std::int64_t j = r.lo[1]; j <= r.hi[1]; ++j)
      for (std::int64_t i = r.lo[0]; i <= r.hi[0]; ++i)
        if (!(inner(0, i) && inner(1, j) && inner(2, k)))
          pts.push_back(lattice_point(c.min, s, i, j, k));
  return pts;
}

}  // namespace

real container_cells(real lo, real hi, real spacing) { return std::round((hi - lo) / spacing); }

double point_count(const Shape& shape, real s) {
  return std::visit(Visitor{[&](const BoxShape& b) {
                              double n = 1;
                              for (int ax = 0; ax < 3; ++ax)
                                n *= box_last_index(b.min[ax], b.max[ax], s) + 1;
                              return n;
                            },
                            [&](const SphereShape& sp) { return sphere_count(sp, s); },
                            [&](const LatticeShape& l) {
                              return double(l.count[0]) * double(l.count[1]) * double(l.count[2]);
                            },
                            [&](const ContainerShape& c) { return container_count(c, s); }},
                    shape);
}

std::vector<Vec3> sample(const Shape& shape, real s) {
  return std::visit(Visitor{[&](const BoxShape& b) { return sample_box(b, s); },
                            [&](const SphereShape& sp) { return sample_sphere(sp, s); },
                            [&](const LatticeShape& l) { return sample_lattice(l, s); },
                            [&](const ContainerShape& c) { return sample_container(c, s); }},
                    shape);
}

}  // namespace dentsph::scene
