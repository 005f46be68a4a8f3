// The iisph solver (docs/model.md, "The iisph solver"): implicit incompressible SPH (Ihmsen et al.
// 2014, relaxed Jacobi) with backward-Euler viscosity and the paper's adhesion bonds, on the grid
// machinery of the paper's step (src/step: cell keys, sort, reorder, neighbour lists with a skin).
// Its stages, one file each, in the order iisph_step.cpp calls them:
//
//   rows.cpp        the material particles in cell order, the tool's velocity over the step
//   tool_pairs.cpp  the tool's neighbours, found every step (the lists leave the tool out)
//   pairs.cpp       every particle's density, and its row: the neighbours within h with their kernel
//                   gradient and viscosity weight; bonds form below A
//   advection.cpp   adhesion of the bonded pairs (bonds break past B), gravity: the velocity v*
//   surface_tension.cpp  the paste's cohesion, curvature and wetting of walls (Akinci 2013), into v*
//   pressure_jacobi.cpp    the pressure (relaxed Jacobi, p >= 0): every particle's density at the end of the
//                   step where its equation of state puts it; v* + dt a_p
//   pressure_cg.cpp the same equations by projected conjugate gradients (iisph.pressure_solve "cg")
//   viscous_pressure.cpp  the pressure a viscous paste needs to stay incompressible (Uzawa, a step
//                   an iteration): its force before the viscosity, its update after
//   viscosity.cpp   backward-Euler viscosity by conjugate gradients: v**
//   rheology.cpp    a non-Newtonian material's effective viscosity from its shear rate (Picard)
//   interface.cpp   paste pulled from the instrument harder than their contact's strength slips
//   finish.cpp      velocity and position, the tool's move, diagnostics, the tool wrench
//
// Every stage is a loop over rows (or particles) in which each writes only its own entries and sums
// in a fixed order, so every thread count gives the same result bit for bit.
#pragma once

#include <chrono>
#include <memory>

#include "dentsph/model.hpp"
#include "dentsph/solver.hpp"
#include "dentsph/state.hpp"
#include "dentsph/step.hpp"
#include "solver/scratch.hpp"

namespace dentsph::iisph {

// The iisph solver object (iisph_solver.cpp): its scratch, its step and its properties. The
// registry's factory (registry.cpp).
std::unique_ptr<StepSolver> make_solver();

// One step of the iisph solver with its scratch `x` (sized for `state`: IisphScratch::resize). Where
// the last step's fastest paste would cross more than cfl h in dt (a squeeze against set paste or a
// wall), it takes substeps() equal steps instead, counted as one (diagnostics.substeps).
void step(const Model& model, State& state, IisphScratch& x, const StepOptions& options);
// How many: ceil(max|v| dt / (cfl h)) of the last step, 1 to kMaxSubsteps.
inline constexpr int kMaxSubsteps = 16;
int substeps(const Model& model, const State& state);

// rows.cpp: lists the material and the tool particles (after a rebuild).
void list_material(const State& state, IisphScratch& x);
// rows.cpp: each tool particle's velocity over this step (to state.tool_pose), the boundary at rest,
// and their entries in the solver's per-particle arrays.
void prepare_particles(const Model& model, State& state, IisphScratch& x, int threads);
// pairs.cpp: the density of every particle and its pair row; material and tool particles form bonds
// with the material closer than A.
void compute_pairs(const Model& model, State& state, IisphScratch& x, int threads, bool build_lists);
// tool_pairs.cpp: each tool particle's neighbours within h, and each other particle's tool
// neighbours; returns the neighbours beyond a tool particle's capacity (none expected).
std::uint64_t find_tool_pairs(const Model& model, State& state, IisphScratch& x, int threads);
// rows.cpp: the rows of this step's pressure solve: material, and the boundary and tool particles
// with material neighbours (the others get pressure 0).
void list_active_rows(State& state, IisphScratch& x);
// advection.cpp: breaks bonds past B, adhesion, gravity: v* of material rows; the viscosity and
// divergence terms of the boundary and tool neighbours, fixed for the step.
void advect(const Model& model, State& state, IisphScratch& x, int threads);
// surface_tension.cpp: with iisph.surface_tension > 0, the paste's surface tension and wetting of
// walls (Akinci, Akinci & Teschner 2013) added to v* of material rows; nothing without.
void surface_tension(const Model& model, State& state, IisphScratch& x, int threads);
// Akinci's gamma_ij = kSurfaceTensionScale sigma / (rho0_i rho0_j h^2) for a surface tension sigma
// (N/m): the scale fitted to Laplace's law, a ball of paste's pressure 2 sigma / R
// (tests/physics/test_surface_tension.cpp; docs/model.md, "Surface tension and wetting").
inline constexpr real kSurfaceTensionScale = 14.7;
// Whether a material of the model is non-Newtonian (its viscosity depends on the flow: rheology.cpp).
inline bool has_rheology(const Model& model) { return model.materials.first_non_newtonian().has_value(); }
// rheology.cpp: each material particle's effective viscosity at the shear rate of the velocities
// `v` of its material neighbours, and every row's viscosity weights, their diagonal (visc_block) and
// the boundary's and tool's terms (at state.vel) weighed with it. Returns the largest relative change of a
// particle's viscosity (infinity the first time in a step: `first`, which also keeps the unit weights).
real update_viscosity(const Model& model, State& state, IisphScratch& x, int threads, const Vec3* v, bool first);
// rheology.cpp: particle i's viscosity (Pa s) at shear rate `gamma`: its material's law, or where the
// cure changed it (kCuredMaterial) the cure's viscosity for a Newtonian paste and, for a paste with
// a flow law, the law's whole flow curve times the factor the cure gave its consistency.
real particle_viscosity(const Model& model, const State& state, std::uint32_t i, real gamma);
// viscous_pressure.cpp (iisph.viscous_pressure > 0): the viscous pressure's force added to v* + dt a_p
// before the viscosity solve (x.v_star, x.v_a), and after it its Uzawa update from the density v**
// gives at the step's end.
void push_viscous_pressure(const Model& model, State& state, IisphScratch& x, int threads);
void update_viscous_pressure(const Model& model, State& state, IisphScratch& x, int threads);
// interface.cpp: after the viscosity solve, each paste particle whose tension against the
// instrument (its instrument pairs' viscous pull less the pressure's push, along their mean line) is
// over the contact's strength (Material::interface_strength) times V^(2/3) has those pairs' coupling
// weakened by the factor that brings it there (row weights, visc_diag, visc_block, visc_fixed; the
// factor in x.interface_scale). `first`: the step's first pass (sets every factor to 1). Returns how
// many particles it weakened, and how many of them for the first time this step; the caller solves
// again where any were.
struct InterfacePass {
  std::uint32_t weakened = 0, first_time = 0;
};
InterfacePass cap_tool_pull(const Model& model, State& state, IisphScratch& x, int threads, bool first);
// The passes of cap_tool_pull and solve a step takes at most.
inline constexpr int kInterfacePasses = 3;
// viscosity.cpp: the backward-Euler viscosity, model.iisph.viscosity_iterations conjugate-gradient
// iterations, or fewer where iisph.viscosity_tolerance is reached.
void implicit_viscosity(const Model& model, State& state, IisphScratch& x, int threads,
                        std::chrono::steady_clock::time_point deadline);
// The pressure solve, by model.iisph.pressure_solve: relaxed Jacobi (pressure_jacobi.cpp) or projected
// conjugate gradients (pressure_cg.cpp). Each leaves every material particle's pressure acceleration
// in x.accel, v* + dt a_p in x.v_star and x.v_a, and its iterations and errors in state.diagnostics.
// Past `deadline` (StepOptions::deadline) a solve stops after its least iterations once its error is
// within kDeadlineErrorFactor of its targets, and sets state.diagnostics.on_deadline.
using Deadline = std::chrono::steady_clock::time_point;
// Past its deadline a solve stops only where its error is at most this many times its target (the
// pressure's mean and largest density error, the viscosity's relative residual); beyond that it goes
// on to its budget as it does without a deadline. With the least iterations alone a cut step was
// left with mean density errors of up to 65 (6,500%), and the built-in procedure under `run
// --realtime --solve-deadline 1e-6` diverged in one run of six (docs/model.md, "The pressure solve").
inline constexpr real kDeadlineErrorFactor = 10;
// The loosest relative residual an inexact Picard iteration's viscosity solve stops at, over
// iisph.viscosity_tolerance (IisphParams::rheology_forcing).
inline constexpr real kPicardLoosest = 10;
void solve_pressure_jacobi(const Model& model, State& state, IisphScratch& x, int threads, Deadline deadline);
void solve_pressure_cg(const Model& model, State& state, IisphScratch& x, int threads, Deadline deadline);
inline void solve_pressure(const Model& model, State& state, IisphScratch& x, int threads, Deadline deadline) {
  if (model.iisph.pressure_solve == PressureSolve::cg)
    solve_pressure_cg(model, state, x, threads, deadline);
  else
    solve_pressure_jacobi(model, state, x, threads, deadline);
}
// Whether `deadline` has passed (never reads the clock for the default, which never comes).
inline bool past(Deadline deadline) {
  return deadline != Deadline::max() && std::chrono::steady_clock::now() > deadline;
}
// Whether a solve whose error is `error` against its target `target` stops at `deadline` now: the
// deadline has passed and the error is within kDeadlineErrorFactor of the target (every solve of the
// step asks this, after its least iterations).
inline bool stops_at_deadline(real error, real target, Deadline deadline) {
  return error <= kDeadlineErrorFactor * target && past(deadline);
}
// finish.cpp: v = v** + dt a_p, r += dt v; the tool to its pose; outputs, diagnostics, wrench.
void finish(const Model& model, State& state, const IisphScratch& x, int threads);

}  // namespace dentsph::iisph
