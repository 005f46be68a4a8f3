// The paper-sized scene for benchmarks: material in a box-shaped cavity, a ball tool pressing
// into it and lifting, repeatedly. Dental scale: 0.25 mm spacing, paste of 2000 kg/m^3.
#include <cmath>

#include "dentsph/bench.hpp"
#include "physics/kernels.hpp"

namespace dentsph {

namespace {

constexpr real s = 2.5e-4;  // m, particle spacing
constexpr int nx = 16, ny = 10, nz = 10;  // material lattice: 1600 particles
constexpr int depth = 12;                 // cavity depth in spacings (two above the material)

ParticleInit make(Role role, Vec3 p, real mass, Material m) {
  ParticleInit q;
  q.role = role;
  q.pos = p;
  q.mass = mass;
  q.material = m;
  return q;
}

}  // namespace

Scene paper_counts_scene() {
  Scene sc;
  sc.name = "paper_counts";
  sc.source = "built-in";
  ModelParams& p = sc.params;
  p.dt = 5e-5;
  p.h = 2 * s;
  p.gravity = {0, 0, -9.81};
  p.adhesion.A = 1.2 * s;
  p.adhesion.B = 3 * s;
  p.domain_min = {-6 * s, -6 * s, -4 * s};
  p.domain_max = {(nx + 6) * s, (ny + 6) * s, (depth + 8) * s};
  sc.model = make_model(p);
  const Material paste{1.0, 10, 2000, 50}, wall{1.0, 15, 2000, 0};
  const real m = lattice_particle_mass(2000, s, sc.model.kernel);

  // Material fills lattice indices [0, nx) x [0, ny) x [0, nz).
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) sc.particles.push_back(make(Role::material, {i * s, j * s, k * s}, m, paste));
  // Walls one spacing outside it: a single layer on the sides, two under the floor, and a rim
  // three spacings wide at the top (the occlusal surface around the margin).
  for (int k = -2; k < depth; ++k)
    for (int j = -4; j <= ny + 3; ++j)
      for (int i = -4; i <= nx + 3; ++i) {
        const bool inside = i >= 0 && i < nx && j >= 0 && j < ny && k >= 0;
        const bool wall_shell = i >= -1 && i <= nx && j >= -1 && j <= ny;
        const bool rim = k == depth - 1;
        if (!inside && (wall_shell || rim)) sc.particles.push_back(make(Role::boundary, {i * s, j * s, k * s}, m, wall));
      }
  // A ball tool: 42 particles on a sphere (Fibonacci lattice) of radius giving spacing ~ s.
  const int n_tool = 42;
  const real R = s * std::sqrt(n_tool / (4 * kernels::pi));
  const real golden = kernels::pi * (3 - std::sqrt(5.0));
  for (int q = 0; q < n_tool; ++q) {
    const real z = 1 - 2 * (q + 0.5) / n_tool, r = std::sqrt(1 - z * z);
    sc.particles.push_back(make(Role::tool, {R * r * std::cos(golden * q), R * r * std::sin(golden * q), R * z}, m, wall));
  }
  // Press 3 spacings into the material and lift, every 0.1 s.
  const Vec3 above{(nx - 1) * s / 2, (ny - 1) * s / 2, (nz + 2) * s + R};
  for (int c = 0; c <= 20; ++c)
    sc.tool.keyframes.push_back({0.05 * c, Pose{above - Vec3{0, 0, (c % 2 ? 5.0 : 0.0) * s}, {}}});
  sc.duration = 1.0;
  return sc;
}

}  // namespace dentsph
