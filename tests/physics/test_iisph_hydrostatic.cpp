// The iisph solver holds a column of paste at rest at a time step 16 times the paper's step's
// acoustic limit: the pressure grows with depth as rho g d, and the paste is compressed by what its
// equation of state says, well under 1%.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "dentsph/step.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

// The dental paste's scale and material (dental.hpp): spacing 0.3 mm, h = 0.6 mm, rho0 2000 kg/m^3,
// mu 1 Pa s, Kp 10 m^2/s^2 (walls 15), without adhesion.
constexpr real s = 3e-4, rho0 = 2000, g = 9.81;
constexpr int nx = 14, nz = 16;

struct Column {
  Model model;
  State state;
};

Column column(real dt) {
  ModelParams p = testing::params_for_spacing(s, Vec3{-5, -5, -5} * s, Vec3{nx + 5, nx + 5, nz + 8} * s, dt, {0, 0, -g});
  p.solver = Solver::iisph;
  Column c{make_model(p), {}};
  const real m = lattice_particle_mass(rho0, s, c.model.kernel);
  const Material paste{1.0, 10, rho0, 0}, wall{1.0, 15, rho0, 0};
  std::vector<ParticleInit> ps;
  for (Vec3 x : testing::lattice({0, 0, 0}, s, nx, nx, nz)) ps.push_back(testing::particle(Role::material, x, m, paste));
  for (Vec3 x : testing::open_container({0, 0, 0}, s, nx - 1, nx - 1, nz + 2, 2))
    ps.push_back(testing::particle(Role::boundary, x, m, wall));
  c.state.add_particles(c.model, ps);
  return c;
}

TEST(IisphHydrostatic, PressureIsRhoGDepthAndTheDensityHolds) {
  Column c = column(1e-3);
  State& st = c.state;
  const StabilityLimits paper_limits = stability_limits(c.model, st);
  EXPECT_GT(c.model.dt, 15 * paper_limits.paper_acoustic) << "far above the paper's step's acoustic limit";
  real density_error = 0;
  int max_iterations = 0;
  for (int k = 0; k < 300; ++k) {
    step(c.model, st);
    ASSERT_EQ(st.diagnostics.non_finite, 0u) << "step " << k;
    density_error = std::max(density_error, k > 100 ? st.diagnostics.density_error : 0);
    max_iterations = std::max(max_iterations, st.diagnostics.pressure_iterations);
  }
  EXPECT_LT(st.diagnostics.max_speed, 1e-3) << "m/s: the column is at rest";
  EXPECT_LT(density_error, 0.01) << "mean compression of the paste, every step after the first 0.1 s";
  EXPECT_LE(max_iterations, c.model.iisph.max_iterations);

  // Layer means of the interior (two columns from the walls), by depth below the free surface.
  real top = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.role[i] == Role::material) top = std::max(top, st.pos[i].z);
  std::vector<real> p_sum(nz + 2, 0), rho_sum(nz + 2, 0), count(nz + 2, 0), z_sum(nz + 2, 0);
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    const Vec3 x = st.pos[i];
    if (st.role[i] != Role::material || x.x < 2 * s || x.x > (nx - 3) * s || x.y < 2 * s || x.y > (nx - 3) * s) continue;
    const int layer = std::clamp(int(std::floor(x.z / s + 0.5)), 0, nz + 1);
    p_sum[layer] += st.pressure[i];
    rho_sum[layer] += st.rho[i];
    z_sum[layer] += x.z;
    count[layer] += 1;
  }
  // Least squares of pressure against depth over the interior layers (two from the floor, three
  // from the surface); pairs of layers alternate about the line by a few percent, the line does not.
  std::vector<real> d, p;
  for (int l = 2; l < nz - 3; ++l) {
    ASSERT_GT(count[l], 0) << "layer " << l;
    d.push_back(top + 0.5 * s - z_sum[l] / count[l]);
    p.push_back(p_sum[l] / count[l]);
    EXPECT_LT(rho_sum[l] / count[l], 1.01 * rho0) << "layer " << l;
    EXPECT_GT(rho_sum[l] / count[l], 0.995 * rho0) << "layer " << l;
  }
  real md = 0, mp = 0;
  for (std::size_t k = 0; k < d.size(); ++k) md += d[k] / d.size(), mp += p[k] / p.size();
  real sdp = 0, sdd = 0;
  for (std::size_t k = 0; k < d.size(); ++k) sdp += (d[k] - md) * (p[k] - mp), sdd += (d[k] - md) * (d[k] - md);
  const real slope = sdp / sdd, intercept = mp - slope * md;
  EXPECT_NEAR(slope / (rho0 * g), 1.0, 0.03) << "Pa/m: dp/dd against rho g";
  EXPECT_LT(std::abs(intercept), 0.03 * rho0 * g * md) << "Pa: the line goes through zero at the surface";
  // The paper's step, for comparison: its pressure is about twice rho g d (test_pressure_output).
}

}  // namespace
}  // namespace dentsph
