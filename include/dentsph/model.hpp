// Model: everything that stays fixed during a step (docs/model.md; cf. MuJoCo's mjModel).
// Build one with make_model(); its derived constants are filled in and checked there.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "dentsph/material.hpp"
#include "dentsph/vec3.hpp"
#include "dentsph/wall_field.hpp"

namespace dentsph {

// The paper's adhesion kernel (eq. 12), support [A, B] in metres. eps > zeta.
struct AdhesionParams {
  real A = 0;       // m, bond forms below this distance; the kernel starts here
  real B = 0;       // m, bond breaks beyond this distance; the kernel ends here
  real eps = 3;     // exponent of the rising term
  real zeta = 2;    // exponent of the falling term
  real Cd = 6.75;   // normalisation: peak magnitude of Cd * (x^eps - x^zeta) is 1 (derived)
};

// Kernel support h and the normalisation constants of the three Mueller kernels (derived).
struct KernelCoeffs {
  real h = 0;            // m, support radius
  real h2 = 0;           // m^2
  real poly6 = 0;        // 315 / (64 pi h^9), 1/m^9
  real spiky_grad = 0;   // 45 / (pi h^6), 1/m^6; gradW = -spiky_grad (h - r)^2 rhat
  real visc_lap = 0;     // 45 / (pi h^6), 1/m^6; lapW = visc_lap (h - r)
  real adh_scale = 0;    // Cd / h^4, 1/m^4
  real cubic = 0;        // 8 / (pi h^3), 1/m^3: the cubic spline of support h (an iisph gradient)
  real spiky_lattice = 0;  // spiky_grad / kSpikyLatticeGradient, 1/m^6: the iisph solver's spiky gradient
  // The density is the cubic spline's sum instead of poly6's (the iisph solver's density_kernel
  // "cubic"; make_model sets it); the lattice mass (lattice_particle_mass) follows it.
  bool cubic_density = false;
};

// On a simple cubic lattice of spacing h / 2 whose particles have the poly6 lattice mass
// (lattice_particle_mass), the spiky gradient of a linear field is this share of the true one
// (tests/unit/test_kernels.cpp recomputes it); the iisph solver's spiky gradient divides by it so
// that its pressure is the mechanical one.
inline constexpr real kSpikyLatticeGradient = 0.9470316764699314;

// On the same lattice, the projected viscosity of a non-Newtonian material (solver/rheology.cpp),
// 2 (d + 2) sum_j V_j ((v_i - v_j) . x_ij) / (r^2 + 0.01 h^2) gradW_ij, gives this share of the
// Laplacian of a shear flow (v = (y^2, 0, 0)) with the iisph solver's spiky gradient (above) and
// with the cubic spline's (tests/unit/test_kernels.cpp recomputes both); the solver divides by it so
// that its viscosity is the paste's.
inline constexpr real kProjectedShearSpiky = 0.6843967583601716;
inline constexpr real kProjectedShearCubic = 0.6913551034031142;

// The uniform grid of the broad phase. Cells are cubes of edge `cell_size` starting at `origin`;
// a particle's neighbours within h lie in the (2 reach + 1)^3 cells around its own, with
// reach * cell_size >= h. Half-h cells (reach 2, 125 cells) hold 15.6 h^3 of candidates where
// h cells (reach 1, the paper's 27) hold 27 h^3: 42% fewer pairs to test for the same
// neighbours. Coordinates wrap modulo `dims`, so a particle anywhere in space has a cell (far
// particles share cells with near ones, which costs time but never correctness).
struct GridSpec {
  Vec3 origin;             // m
  real cell_size = 0;      // m
  int reach = 1;           // cells searched on each side
  int dims[3] = {0, 0, 0}; // cells per axis, each >= 2 reach + 1 so the searched cells are distinct

  std::int64_t cell_count() const { return std::int64_t(dims[0]) * dims[1] * dims[2]; }
};

// Which solver steps the model (docs/model.md, "Solvers"): the key of a solver object in the
// registry (dentsph/solver.hpp, src/solver/registry.cpp), which says everything else about it.
// - paper: the paper's explicit, weakly compressible step (src/step), capped by its acoustic,
//   viscous and force limits; the reference every paper figure is about.
// - iisph: implicit incompressible SPH (Ihmsen et al. 2014) with implicit viscosity and the
//   paper's adhesion bonds (src/solver), capped by the velocity CFL condition only.
enum class Solver { paper, iisph };
// The kernel whose gradient the iisph solver's pressure uses: the paper's spiky kernel (scaled by
// 1 / kSpikyLatticeGradient) or the cubic spline (docs/model.md, "The iisph solver").
enum class PressureGradient { spiky, cubic };
const char* gradient_name(PressureGradient g);  // "spiky", "cubic"
std::optional<PressureGradient> gradient_from_name(std::string_view name);
// The kernel the iisph solver sums its density with (docs/model.md, "One kernel for the density
// and its rate"): the paper's poly6, or the cubic spline, whose gradient is then the pressure's
// (gradient "cubic"), so that the density the solve predicts for the step's end is the rate of the
// density it then sums.
enum class DensityKernel { poly6, cubic };
const char* density_kernel_name(DensityKernel k);  // "poly6", "cubic"
std::optional<DensityKernel> density_kernel_from_name(std::string_view name);
// How the iisph solver solves its pressure (docs/model.md, "The pressure solve"): relaxed Jacobi
// (solver/pressure_jacobi.cpp; a correction travels about one particle layer an iteration, so its iterations
// grow with the square of the scene's depth in layers) or projected conjugate gradients
// (solver/pressure_cg.cpp, MPRGP: with the square root of the condition number, about the depth).
enum class PressureSolve { jacobi, cg };
const char* pressure_solve_name(PressureSolve s);  // "jacobi", "cg"
std::optional<PressureSolve> pressure_solve_from_name(std::string_view name);
// The registered solvers' names (registry.cpp): "paper", "iisph".
const char* solver_name(Solver s);
std::optional<Solver> solver_from_name(std::string_view name);
std::string solver_choices();  // "paper or iisph", for messages

// The iisph solver's budget and targets (docs/model.md, "The iisph solver").
struct IisphParams {
  int min_iterations = 2;         // pressure iterations always done
  int max_iterations = 12;        // pressure iterations at most: the step's cost is bounded
  real density_error = 0.002;     // stop once the solve's mean error (relative density) is below this
  // cg: and once the largest error of a material particle is below this too (jacobi ignores it).
  real max_density_error = 0.01;
  PressureSolve pressure_solve = PressureSolve::jacobi;
  real omega = 0.5;               // relaxation of the Jacobi pressure update
  real warm_start = 1;            // the last step's pressure times this starts the solve
  int viscosity_iterations = 8;   // conjugate-gradient iterations of the backward-Euler viscosity (at most,
                                  // where viscosity_tolerance is set)
  // 0: viscosity_iterations iterations from v* + dt a_p, whatever the residual (the iisph solver as it
  // was). Above 0: from the last step's velocity, until the relative residual is below this.
  real viscosity_tolerance = 0;
  real cfl = 0.4;                 // velocity Courant number: dt <= cfl h / max|v|
  // A non-Newtonian material's viscosity (docs/model.md, "Rheology") by Picard iterations: each
  // takes the shear rates of the latest velocities (the last step's, then each solve's), their
  // effective viscosities, and solves the viscosity again from the last solution; at most this many
  // a step, fewer once no material particle's viscosity changed by more than rheology_tolerance
  // (relative) in the last one.
  int rheology_iterations = 3;
  real rheology_tolerance = 0.02;
  // Inexact Picard iterations: above 0, each Picard iteration's viscosity solve stops at the relative
  // residual rheology_forcing times the change of the viscosities that called for it, kept between
  // viscosity_tolerance and kPicardLoosest (10) times it; the first solve of a step at the loosest
  // (its viscosities' error is not known yet). 0: every solve to viscosity_tolerance. Where the
  // viscosities are still far from their law a tight solve is wasted, but the paste then keeps its
  // volume less well; no preset sets it (docs/model.md, "Rheology").
  real rheology_forcing = 0;
  // A wall particle's density target is the larger of its rest density and its walls' own density
  // (where walls overlap, as paste that set against the tooth's lining): without it a stiff paste
  // (Kp 1e4) is pushed off overlapping walls with megapascals and the run diverges; with it the
  // paper's soft paste compresses more near them (docs/model.md, "Presets"). The presets set it.
  bool wall_rest_density = false;
  // The solve's equation of state is p = stiffness Kp (rho - rho0). The paper's eq. 5 turns half of
  // a pressure field's gradient into force (its (P_i + P_j) / 2 average), so under a load the paper's
  // paste compresses twice what Kp (rho - rho0) with a consistent force gives: 0.5 makes the same Kp
  // the same paste on both solvers (docs/model.md), 1 takes the equation of state as written.
  real stiffness = 0.5;
  PressureGradient gradient = PressureGradient::spiky;
  // The density's kernel; "cubic" needs gradient "cubic" (check_iisph_params).
  DensityKernel density_kernel = DensityKernel::poly6;
  // The viscous pressure's step alpha (docs/model.md, "The viscous pressure"; 0: none, the solver as
  // it was): a viscous paste's pressure built up across steps, one Uzawa iteration of the coupled
  // pressure and viscosity a step, so that the viscosity solved after the pressure does not leave the
  // paste compressed. At most 1; the presets' 0.5.
  real viscous_pressure = 0;
  // The paste's surface tension, N/m (docs/model.md, "Surface tension and wetting"; 0: none, the
  // solver as it was): Akinci, Akinci & Teschner 2013's cohesion and curvature between paste
  // particles, their coefficient the tension's by kSurfaceTensionScale (fitted to Laplace's law).
  real surface_tension = 0;
  // The paste's wetting of walls (the tooth, set paste): their adhesion force over the cohesion's,
  // Akinci's beta / gamma, 0 to 2 (0: none; with surface_tension only).
  real wetting = 0;
};

// The user's choices; make_model() checks them and derives the rest.
struct ModelParams {
  real dt = 1e-4;                 // s, fixed time step
  real h = 0;                     // m, kernel support
  Vec3 gravity{0, 0, -9.81};      // m/s^2
  AdhesionParams adhesion;        // A, B, eps, zeta (Cd derived)
  Vec3 domain_min, domain_max;    // m, region the grid covers without wrapping
  int max_bonds_per_particle = 64;
  real cfl_lambda = 0.4;          // acoustic Courant number of the stability limit
  int grid_reach = 1;             // grid cells of h / grid_reach, searched grid_reach deep
  real neighbour_skin = 0;        // m, neighbour lists reach h + skin and are kept until a
                                  // particle has moved skin / 2 (0: rebuilt every step)
  Solver solver = Solver::paper;  // which step runs
  IisphParams iisph;              // the iisph solver's budget (unused by the paper's step)
  // The iisph solver holds material that would leave the domain where it is, at rest (dental
  // scenes: the domain is the lined tooth and 4 mm around the cavity, and paste beyond it has fallen
  // off the model; without it, overfill falling past the lined walls would fall for ever, and its
  // speed would split every step into substeps). The paper's step ignores it.
  bool hold_outside_domain = false;
};

struct Model {
  real dt = 0;
  Vec3 gravity;
  KernelCoeffs kernel;
  AdhesionParams adhesion;
  GridSpec grid;
  int max_bonds_per_particle = 64;
  real cfl_lambda = 0.4;
  real neighbour_skin = 0;  // m, see ModelParams
  Vec3 domain_min, domain_max;
  Solver solver = Solver::paper;
  IisphParams iisph;
  bool hold_outside_domain = false;  // see ModelParams
  // The materials the particles' State::material indices name (material.hpp). A dental scene names
  // "paste", "tooth" and each instrument; a scene file its `materials`. make_model() leaves it
  // empty: the scene builders fill it, and State::add_particles with a Model it may grow adds the
  // values of particles that name none.
  MaterialTable materials;
  // The iisph solver keeps material this far out of the scene's fixed walls (wall_field.hpp; the
  // dental scenes': the prepared tooth). None by default; the paper's step never reads it.
  std::shared_ptr<const WallField> walls;
};

// Checks the iisph solver's settings (make_model does too); throws std::invalid_argument whose message
// reads "iisph.<field>: <problem>; <fix>".
void check_iisph_params(const IisphParams& p);

// The kernel support and adhesion range of particles on a lattice of spacing s, as every built-in
// scene has them: h = 2 s (the lattice shares of the kernels assume it), the adhesion's A = 1.2 s
// and B = 3 s.
inline void set_lattice_spacing(ModelParams& p, real s) {
  p.h = 2 * s;
  p.adhesion.A = 1.2 * s;
  p.adhesion.B = 3 * s;
}

// Checks `p` and derives the kernel constants, C_d and the grid. Throws std::invalid_argument
// whose message names the offending field and says how to fix it.
Model make_model(const ModelParams& p);

// Checks an adhesion kernel against the kernel support h: A < h < B, eps > zeta > 0; throws
// std::invalid_argument naming the field (make_model checks its adhesion so).
void check_adhesion(const AdhesionParams& a, real h);

// `m` with the adhesion kernel `a` (checked against m's h, its constants derived again), the rest
// of it unchanged: a paste edit of a running Simulation (Simulation::set_paste).
Model with_adhesion(Model m, const AdhesionParams& a);

// C_d of docs/model.md ("Kernels"): 1 / (x*^zeta - x*^eps) with x* = (zeta/eps)^(1/(eps-zeta)).
real adhesion_normalisation(real eps, real zeta);

}  // namespace dentsph
