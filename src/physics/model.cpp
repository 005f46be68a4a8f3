// make_model(): checks the user's parameters and derives kernel constants, C_d and the grid.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "dentsph/limits.hpp"
#include "dentsph/model.hpp"
#include "physics/kernels.hpp"

namespace dentsph {

namespace {

[[noreturn]] void fail(const std::string& field, const std::string& why) {
  throw std::invalid_argument(fmt::format("{}: {}", field, why));
}

void require_finite_positive(real v, const char* field, const char* fix) {
  if (!std::isfinite(v) || v <= 0) fail(field, fmt::format("must be a positive number, got {}; {}", v, fix));
}

}  // namespace

const char* gradient_name(PressureGradient g) {
  switch (g) {
    case PressureGradient::spiky: return "spiky";
    case PressureGradient::cubic: return "cubic";
  }
  return "unknown";
}

std::optional<PressureGradient> gradient_from_name(std::string_view name) {
  for (PressureGradient g : {PressureGradient::spiky, PressureGradient::cubic})
    if (name == gradient_name(g)) return g;
  return std::nullopt;
}

const char* density_kernel_name(DensityKernel k) {
  switch (k) {
    case DensityKernel::poly6: return "poly6";
    case DensityKernel::cubic: return "cubic";
  }
  return "unknown";
}

std::optional<DensityKernel> density_kernel_from_name(std::string_view name) {
  for (DensityKernel k : {DensityKernel::poly6, DensityKernel::cubic})
    if (name == density_kernel_name(k)) return k;
  return std::nullopt;
}

const char* pressure_solve_name(PressureSolve s) {
  switch (s) {
    case PressureSolve::jacobi: return "jacobi";
    case PressureSolve::cg: return "cg";
  }
  return "unknown";
}

std::optional<PressureSolve> pressure_solve_from_name(std::string_view name) {
  for (PressureSolve s : {PressureSolve::jacobi, PressureSolve::cg})
    if (name == pressure_solve_name(s)) return s;
  return std::nullopt;
}

real adhesion_normalisation(real eps, real zeta) {
  // The bracket x^eps - x^zeta has its minimum where eps x^(eps-1) = zeta x^(zeta-1).
  const real xs = std::pow(zeta / eps, 1.0 / (eps - zeta));
  return 1.0 / (std::pow(xs, zeta) - std::pow(xs, eps));
}

void check_iisph_params(const IisphParams& ip) {
  if (ip.min_iterations < 1 || ip.max_iterations < ip.min_iterations || ip.max_iterations > 1000)
    fail("iisph.max_iterations",
         fmt::format("need 1 <= min_iterations <= max_iterations <= 1000, got {} and {}", ip.min_iterations,
                     ip.max_iterations));
  if (!(ip.density_error > 0 && ip.density_error < 1))
    fail("iisph.density_error", fmt::format("must be in (0, 1), got {}; 0.001 to 0.01 is usual", ip.density_error));
  if (!(ip.max_density_error >= ip.density_error && ip.max_density_error < 1))
    fail("iisph.max_density_error",
         fmt::format("must be in [density_error, 1), got {} (density_error {}); 0.01 is usual", ip.max_density_error,
                     ip.density_error));
  if (!(ip.viscosity_tolerance >= 0 && ip.viscosity_tolerance < 1))
    fail("iisph.viscosity_tolerance",
         fmt::format("must be in [0, 1), got {}; 0 for a fixed number of iterations, 1e-3 is usual", ip.viscosity_tolerance));
  if (!(ip.omega > 0 && ip.omega <= 1))
    fail("iisph.omega", fmt::format("must be in (0, 1], got {}; 0.5 is usual", ip.omega));
  if (!(ip.warm_start >= 0 && ip.warm_start <= 1))
    fail("iisph.warm_start", fmt::format("must be in [0, 1], got {}", ip.warm_start));
  if (ip.viscosity_iterations < 1 || ip.viscosity_iterations > 1000)
    fail("iisph.viscosity_iterations", fmt::format("must be in [1, 1000], got {}", ip.viscosity_iterations));
  require_finite_positive(ip.cfl, "iisph.cfl", "about 0.4 is usual");
  if (ip.rheology_iterations < 1 || ip.rheology_iterations > 100)
    fail("iisph.rheology_iterations", fmt::format("must be in [1, 100], got {}; 3 is usual", ip.rheology_iterations));
  if (!(ip.rheology_tolerance >= 0 && ip.rheology_tolerance < 1))
    fail("iisph.rheology_tolerance", fmt::format("must be in [0, 1), got {}; 0.02 is usual", ip.rheology_tolerance));
  if (!(ip.rheology_forcing >= 0 && ip.rheology_forcing <= 1))
    fail("iisph.rheology_forcing", fmt::format("must be in [0, 1], got {}; 0 (every solve to the tolerance) is the default, 0.1 usual", ip.rheology_forcing));
  if (!(ip.surface_tension >= 0 && ip.surface_tension <= 1))
    fail("iisph.surface_tension",
         fmt::format("must be in [0, 1] N/m, got {}; 0 for none, water's is 0.072, a resin's about 0.04 (docs/model.md)",
                     ip.surface_tension));
  if (!(ip.wetting >= 0 && ip.wetting <= 2))
    fail("iisph.wetting", fmt::format("must be in [0, 2], got {}; 0 for none (docs/model.md)", ip.wetting));
  if (ip.wetting > 0 && !(ip.surface_tension > 0))
    fail("iisph.wetting", fmt::format("{} needs a surface tension: set iisph.surface_tension (N/m), or wetting 0",
                                      ip.wetting));
  if (!(ip.viscous_pressure >= 0 && ip.viscous_pressure <= 1))
    fail("iisph.viscous_pressure",
         fmt::format("must be in [0, 1], got {}; 0 for none, 0.5 is the presets' (docs/model.md)", ip.viscous_pressure));
  if (ip.density_kernel == DensityKernel::cubic && ip.gradient != PressureGradient::cubic)
    fail("iisph.density_kernel",
         fmt::format("\"cubic\" needs the pressure's gradient to be the same kernel's, got gradient \"{}\"; set "
                     "iisph.gradient to \"cubic\", or density_kernel to \"poly6\"",
                     gradient_name(ip.gradient)));
  if (!(ip.stiffness > 0 && ip.stiffness <= 1))
    fail("iisph.stiffness", fmt::format("must be in (0, 1], got {}; 0.5 is the paper's paste's stiffness", ip.stiffness));
}

void check_adhesion(const AdhesionParams& a, real h) {
  require_finite_positive(a.A, "adhesion.A", "give the bond-forming distance in metres, a little under h");
  require_finite_positive(a.B, "adhesion.B", "give the bond-breaking distance in metres, a little over h");
  if (!(a.A < h && h < a.B))
    fail("adhesion.A/adhesion.B",
         fmt::format("need A < h < B (docs/model.md, \"Adhesion hysteresis\"), got A = {}, h = {}, B = {}; e.g. A = 0.6 h, "
                     "B = 1.5 h",
                     a.A, h, a.B));
  require_finite_positive(a.eps, "adhesion.eps", "the paper uses eps = 3");
  require_finite_positive(a.zeta, "adhesion.zeta", "the paper uses zeta = 2");
  if (!(a.eps > a.zeta))
    fail("adhesion.eps", fmt::format("must exceed adhesion.zeta (got eps = {}, zeta = {}); the paper uses 3 and 2", a.eps, a.zeta));
}

Model with_adhesion(Model m, const AdhesionParams& a) {
  check_adhesion(a, m.kernel.h);
  const bool cubic_density = m.kernel.cubic_density;
  m.adhesion = a;
  m.adhesion.Cd = adhesion_normalisation(a.eps, a.zeta);
  m.kernel = kernels::make_coeffs(m.kernel.h, m.adhesion);
  m.kernel.cubic_density = cubic_density;
  return m;
}

Model make_model(const ModelParams& p) {
  require_finite_positive(p.dt, "dt", "give the time step in seconds, e.g. 1e-4");
  if (p.dt < limits::min_dt)
    fail("dt", fmt::format("{:.3g} s is under the smallest time step of {:.3g} s (a run would never end); give the time "
                           "step in seconds, e.g. 1e-4",
                           p.dt, limits::min_dt));
  require_finite_positive(p.h, "h", "give the kernel support in metres, about twice the particle spacing");
  if (!is_finite(p.gravity)) fail("gravity", "must be three finite numbers in m/s^2");
  if (!(norm(p.gravity) <= limits::max_gravity))
    fail("gravity", fmt::format("|g| = {:.3g} m/s^2 is over the largest of {:.0f} m/s^2; give it in m/s^2, e.g. "
                                "[0, 0, -9.81]",
                                norm(p.gravity), limits::max_gravity));
  const AdhesionParams& a = p.adhesion;
  check_adhesion(a, p.h);
  if (p.max_bonds_per_particle < 1 || p.max_bonds_per_particle > 1024)
    fail("max_bonds_per_particle", fmt::format("must be in [1, 1024], got {}", p.max_bonds_per_particle));
  require_finite_positive(p.cfl_lambda, "cfl_lambda", "about 0.4 is usual");
  if (!std::isfinite(p.neighbour_skin) || p.neighbour_skin < 0 || p.neighbour_skin > p.h)
    fail("neighbour_skin", fmt::format("must be in [0, h] metres, got {}; 0.1 h to 0.3 h is usual", p.neighbour_skin));
  if (p.grid_reach < 1 || p.grid_reach > 3)
    fail("grid_reach", fmt::format("must be 1, 2 or 3 (cells of h / reach), got {}", p.grid_reach));
  check_iisph_params(p.iisph);
  if (!is_finite(p.domain_min) || !is_finite(p.domain_max) || !(p.domain_min.x < p.domain_max.x) ||
      !(p.domain_min.y < p.domain_max.y) || !(p.domain_min.z < p.domain_max.z))
    fail("domain", "min must be below max on every axis (metres)");

  Model m;
  m.dt = p.dt;
  m.gravity = p.gravity;
  m.adhesion = a;
  m.adhesion.Cd = adhesion_normalisation(a.eps, a.zeta);
  m.kernel = kernels::make_coeffs(p.h, m.adhesion);
  m.kernel.cubic_density = p.solver == Solver::iisph && p.iisph.density_kernel == DensityKernel::cubic;
  m.max_bonds_per_particle = p.max_bonds_per_particle;
  m.cfl_lambda = p.cfl_lambda;
  m.neighbour_skin = p.neighbour_skin;
  m.domain_min = p.domain_min;
  m.domain_max = p.domain_max;
  m.solver = p.solver;
  m.iisph = p.iisph;
  m.hold_outside_domain = p.hold_outside_domain;

  // Grid: cells of edge h / reach over the domain; at least 2 reach + 1 per axis (distinct
  // searched cells), at most 2^22 cells in all (the domain wraps beyond, which stays correct).
  GridSpec& g = m.grid;
  g.origin = p.domain_min;
  g.reach = p.grid_reach;
  // Cells must hold every pair within h even when the grid is up to skin / 2 of motion old.
  g.cell_size = (p.h + p.neighbour_skin) / g.reach;
  const Vec3 ext = p.domain_max - p.domain_min;
  constexpr std::int64_t max_cells = limits::max_grid_cells;
  for (;;) {
    for (int ax = 0; ax < 3; ++ax)
      g.dims[ax] = int(std::clamp<real>(std::ceil(ext[ax] / g.cell_size), 2 * g.reach + 1, 4096));
    if (g.cell_count() <= max_cells) break;
    g.cell_size *= 1.25;
  }
  return m;
}

}  // namespace dentsph
