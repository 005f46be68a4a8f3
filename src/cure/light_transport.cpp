// The curing light's transport through the paste (docs/model.md, "Curing"). The beam is collimated
// along its direction, so the light reaching a point has crossed the matter on the straight line
// back to the window along that direction. The matter is put on a grid aligned with the beam:
// every particle near the lit paste deposits its attenuation (its material's coefficient times its
// share spacing^3 / cell^3 of a cell) on the grid's nodes with trilinear weights; the nodes of each
// column are integrated along the beam (trapezoids), which gives the optical depth from the first
// node to each node; a lit particle reads it at its own place (bilinear across the columns, linear
// along), so it is shaded by what lies before its centre, half of itself included. The irradiance
// is then E0 exp(-optical depth). One pass over the particles to find them in the beam's frame,
// one to deposit, one over the grid, one to read: linear in the particles, the grid no larger than
// the lit paste's box (plus what shades it).
#include <algorithm>
#include <cmath>
#include <limits>

#include "dentsph/cure.hpp"

namespace dentsph {

namespace {

// The beam's frame: w along the beam, u and v across it.
struct BeamFrame {
  Vec3 origin, u, v, w;
  explicit BeamFrame(const CuringLight& light) : origin(light.tip) {
    w = light.direction / norm(light.direction);
    const Vec3 a = std::abs(w.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    u = cross(w, a);
    u = u / norm(u);
    v = cross(w, u);
  }
};

// Attenuation coefficient (1/m) of particle i.
real attenuation(const CureModel& cm, const State& s, std::uint32_t i) {
  const std::uint32_t id = s.id[i];
  if (s.cure.curable[id]) return paste_attenuation(cm.paste, s.cure.alpha[id]);
  return s.role[i] == Role::tool ? cm.tool_attenuation : cm.tissue_attenuation;
}

// Grids larger than this many nodes are coarsened (cells of a multiple of the spacing): a beam
// across a whole scanned tooth at a fine spacing still costs a bounded pass.
constexpr std::size_t kMaxNodes = std::size_t(1) << 22;

}  // namespace

std::uint32_t compute_irradiance(const CureModel& cm, State& s, const CuringLight& light) {
  CureState& c = s.cure;
  const std::uint32_t n = s.size();
  c.beam_x.resize(n);
  c.beam_y.resize(n);
  c.beam_z.resize(n);
  for (std::uint32_t id = 0; id < n; ++id) c.irradiance[id] = 0;
  c.lit_ids.clear();
  c.lit_irradiance.clear();
  if (!light.on || !(light.irradiance > 0) || !(norm2(light.direction) > 0) || !(cm.spacing > 0)) return 0;

  const BeamFrame f(light);
  const real R2 = 0.25 * light.diameter * light.diameter;
  constexpr real inf = std::numeric_limits<real>::infinity();
  real x0 = inf, x1 = -inf, y0 = inf, y1 = -inf, z1 = -inf;
  std::uint32_t lit = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    // Set paste where it set: its shrinkage (under 1% of lengths) is left out of the optics, where
    // the grid would turn the thin gap it opens at the side of an increment into a cell-wide one.
    const std::uint32_t id = s.id[i];
    const Vec3 r = (c.rigid[id] ? c.gel_pos[id] : s.pos[i]) - f.origin;
    const real x = dot(r, f.u), y = dot(r, f.v), z = dot(r, f.w);
    c.beam_x[i] = x, c.beam_y[i] = y, c.beam_z[i] = z;
    if (c.curable[id] && z > 0 && x * x + y * y <= R2) {
      x0 = std::min(x0, x), x1 = std::max(x1, x);
      y0 = std::min(y0, y), y1 = std::max(y1, y);
      z1 = std::max(z1, z);
      ++lit;
    }
  }
  if (lit == 0) return 0;

  // The box that matters: the lit paste's, a cell wider (a particle's deposit reaches one cell),
  // and along the beam from the first matter in front of the window.
  real cell = cm.spacing;
  x0 -= cell, x1 += cell, y0 -= cell, y1 += cell;
  const real zmax = z1 + cell;
  real zmin = z1;
  auto in_box = [&](std::uint32_t i) {
    const real x = c.beam_x[i], y = c.beam_y[i], z = c.beam_z[i];
    return x >= x0 && x <= x1 && y >= y0 && y <= y1 && z > 0 && z <= zmax;
  };
  for (std::uint32_t i = 0; i < n; ++i)
    if (in_box(i)) zmin = std::min(zmin, c.beam_z[i]);
  const real z0 = zmin - cell;
  std::size_t nx, ny, nz;
  for (;;) {
    nx = std::size_t((x1 - x0) / cell) + 2;
    ny = std::size_t((y1 - y0) / cell) + 2;
    nz = std::size_t((zmax - z0) / cell) + 2;
    if (nx * ny * nz <= kMaxNodes) break;
    cell *= 2;
  }
  c.beam_grid.assign(nx * ny * nz, 0);
  real* g = c.beam_grid.data();
  const real share = std::pow(cm.spacing / cell, 3);  // of a cell's volume, per particle
  const real inv = 1 / cell;

  // Deposit: attenuation per unit length, on the nodes around each particle (column-major: a
  // column's nodes are contiguous).
  auto node = [&](std::size_t ix, std::size_t iy, std::size_t iz) { return (iy * nx + ix) * nz + iz; };
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!in_box(i)) continue;
    const real k = attenuation(cm, s, i) * share;
    const real fx = (c.beam_x[i] - x0) * inv, fy = (c.beam_y[i] - y0) * inv, fz = (c.beam_z[i] - z0) * inv;
    const std::size_t ix = std::size_t(fx), iy = std::size_t(fy), iz = std::size_t(fz);
    const real tx = fx - real(ix), ty = fy - real(iy), tz = fz - real(iz);
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a) {
        const real wxy = (a ? tx : 1 - tx) * (b ? ty : 1 - ty) * k;
        const std::size_t col = node(ix + std::size_t(a), iy + std::size_t(b), iz);
        g[col] += wxy * (1 - tz);
        g[col + 1] += wxy * tz;
      }
  }
  // Each column's optical depth from its first node: trapezoids along the beam.
  for (std::size_t col = 0; col < nx * ny; ++col) {
    real* t = g + col * nz;
    real prev = t[0], depth = 0;
    t[0] = 0;
    for (std::size_t k = 1; k < nz; ++k) {
      const real here = t[k];
      depth += 0.5 * (prev + here) * cell;
      t[k] = depth;
      prev = here;
    }
  }
  // Read: each lit paste particle's optical depth at its place, from the nearest column (linear
  // along it). Not interpolated across columns: at the paste's side a column outside holds only the
  // spill of the deposits next to it, and reading it would let light in sideways; the nearest
  // column holds the paste in line with the particle (its neighbours' spill making up its own).
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t id = s.id[i];
    const real x = c.beam_x[i], y = c.beam_y[i], z = c.beam_z[i];
    if (!c.curable[id] || !(z > 0) || x * x + y * y > R2) continue;
    const real fz = (z - z0) * inv;
    const std::size_t ix = std::size_t(std::lround((x - x0) * inv)), iy = std::size_t(std::lround((y - y0) * inv));
    const std::size_t iz = std::size_t(fz);
    const real tz = fz - real(iz);
    const real* t = g + node(ix, iy, iz);
    c.irradiance[id] = light.irradiance * std::exp(-(t[0] * (1 - tz) + t[1] * tz));
    c.lit_ids.push_back(id);
    c.lit_irradiance.push_back(c.irradiance[id]);
  }
  return lit;
}

}  // namespace dentsph
