// molar_crown(): a closed lower-molar crown built from an implicit solid. Each vertex of a
// latitude-longitude sphere around a point inside is pushed out along its ray to where the solid
// ends, so the mesh has the sphere's topology (closed, manifold, outward) by construction, and
// being a radial graph it cannot intersect itself.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dentsph/tooth.hpp"

namespace dentsph {

namespace {

constexpr real pi = 3.14159265358979323846;

// Polynomial smooth maximum (Quilez): max(a, b) with the corner rounded over a width k.
real smax(real a, real b, real k) {
  const real h = std::fmax(k - std::fabs(a - b), 0.0) / k;
  return std::fmax(a, b) + h * h * k / 4;
}

// The crown as an implicit function of a point in millimetres: negative inside, roughly a
// distance in mm near the surface.
struct CrownSolid {
  real a, b, height, cusp;             // mm: half length, half width, height, cusp height
  static constexpr real exponent = 3;  // superellipse footprint: a rounded box

  // Footprint scale with height: narrower at the cervical line, widest at the height of
  // contour (a third of the way up), drawing in towards the occlusal table.
  real bulge(real z) const {
    const real u = std::clamp(z / height, 0.0, 1.0);
    return u < 0.35 ? 1 - 0.18 * std::pow((u - 0.35) / 0.35, 2)
                    : 1 - 0.12 * std::pow((u - 0.35) / 0.65, 2);
  }
  // Footprint "radius" of (x, y) at scale k: 1 on the outline.
  real footprint(real x, real y, real k) const {
    return std::pow(
        std::pow(std::fabs(x) / (a * k), exponent) + std::pow(std::fabs(y) / (b * k), exponent),
        1 / exponent);
  }
  // Occlusal surface: four cusps (Gaussian bumps) and marginal ridges round the rim, over a
  // central fossa; the cusp tips reach `height`.
  real raw_top(real x, real y) const {
    const real sigma = 0.24 * std::min(a, b);
    real bumps = 0;
    for (real sx : {-1.0, 1.0})
      for (real sy : {-1.0, 1.0}) {
        const real dx = x - sx * 0.45 * a, dy = y - sy * 0.42 * b;
        bumps += std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma));
      }
    const real rim = footprint(x, y, 1) - 0.8;
    return bumps + 0.3 * std::exp(-rim * rim / (2 * 0.12 * 0.12));
  }
  real top_scale = 1;  // 1 / max of raw_top
  real top(real x, real y) const { return height - cusp + cusp * raw_top(x, y) * top_scale; }

  real operator()(real x, real y, real z) const {
    const real k = bulge(z);
    const real side = (footprint(x, y, k) - 1) * std::min(a, b) * k;
    const real base = -z;
    const real occlusal = z - top(x, y);
    return smax(smax(side, base, 0.4), occlusal, 0.9);
  }
};

}  // namespace

MolarCrown molar_crown(const MolarCrownParams& p) {
  if (!(p.length > 0 && p.width > 0 && p.height > 0 && p.cusp_height >= 0 &&
        p.cusp_height < p.height && p.resolution >= 8 && p.resolution <= 4096))
    throw std::invalid_argument(fmt::format(
        "molar_crown: need length, width, height > 0, 0 <= cusp_height < height, resolution in "
        "[8, 4096]; got {} x {} x {} mm, cusps {} mm, resolution {}",
        p.length * 1e3, p.width * 1e3, p.height * 1e3, p.cusp_height * 1e3, p.resolution));
  CrownSolid solid{p.length * 1e3 / 2, p.width * 1e3 / 2, p.height * 1e3, p.cusp_height * 1e3};
  real peak = 0;  // the cusp tips: search near the four cusp centres
  for (int i = -40; i <= 40; ++i)
    for (int j = -40; j <= 40; ++j)
      peak = std::fmax(peak, solid.raw_top(i * solid.a / 40, j * solid.b / 40));
  solid.top_scale = 1 / peak;

  // Rays from a point on the axis at 40% of the height: the occlusal surface, the sides and
  // the base are all seen from it once (the solid is star-shaped about it).
  const Vec3 centre{0, 0, 0.4 * solid.height};
  const real reach = 2 * (solid.a + solid.b + solid.height), step = 0.05;
  auto surface = [&](const Vec3& dir) {
    real r0 = 0, r1 = step;
    while (r1 < reach) {
      const Vec3 q = centre + dir * r1;
      if (solid(q.x, q.y, q.z) > 0) break;
      r0 = r1;
      r1 += step;
    }
    for (int it = 0; it < 40; ++it) {
      const real m = (r0 + r1) / 2;
      const Vec3 q = centre + dir * m;
      (solid(q.x, q.y, q.z) > 0 ? r1 : r0) = m;
    }
    return (centre + dir * ((r0 + r1) / 2)) * 1e-3;  // m
  };

  const int nlon = p.resolution, nlat = p.resolution / 2;
  TriMesh mesh;
  mesh.vertices.push_back(surface({0, 0, 1}));
  for (int i = 1; i < nlat; ++i) {
    const real th = pi * i / nlat;
    for (int j = 0; j < nlon; ++j) {
      const real ph = 2 * pi * j / nlon;
      mesh.vertices.push_back(
          surface({std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)}));
    }
  }
  mesh.vertices.push_back(surface({0, 0, -1}));
  const auto ring = [&](int i, int j) { return std::uint32_t(1 + (i - 1) * nlon + (j % nlon)); };
  const auto bottom = std::uint32_t(mesh.vertices.size() - 1);
  // Counter-clockwise seen from outside: (theta, phi) directions make an outward cross product.
  for (int j = 0; j < nlon; ++j) mesh.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i < nlat - 1; ++i)
    for (int j = 0; j < nlon; ++j) {
      mesh.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i, j + 1)});
      mesh.triangles.push_back({ring(i, j + 1), ring(i + 1, j), ring(i + 1, j + 1)});
    }
  for (int j = 0; j < nlon; ++j)
    mesh.triangles.push_back({ring(nlat - 1, j), bottom, ring(nlat - 1, j + 1)});

  LoadedMesh checked = repair_mesh(std::move(mesh), "built-in molar crown");
  return {std::move(checked.mesh), std::move(checked.report),
          make_tooth_frame({0, 0, 0}, {0, 0, 1}, {1, 0, 0})};
}

}  // namespace dentsph
