// The iisph solver's own data (iisph.hpp lists its stages): each particle's row of neighbours and
// the per-row numbers of the pressure solve and the viscosity, kept by the iisph solver object.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "dentsph/state.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph {

// One neighbour within h of a particle, as the iisph solver's pair pass leaves it. Stored in single
// precision (20 bytes instead of 40): the rows are the solver's largest memory stream (a material
// row holds about 30 of them and every pressure iteration and viscosity iteration sweeps them), and
// a kernel weight's seventh digit is far below the solve's tolerance (docs/model.md). Sums over
// them are taken in double precision.
struct SolverPair {
  float gx = 0, gy = 0, gz = 0;  // m_j gradW_cubic(r_i - r_j), kg/m^4
  float visc = 0;      // (mu_i + mu_j)/2 m_j lapW_visc(r) / rho_j, Pa s / m^5 (rho_j: the pair pass's density,
                       // rest density for boundary and tool; material rows only); with a non-Newtonian
                       // material, c_ij of the projected form (rheology.cpp)
  std::uint32_t j = 0; // the neighbour's index
  Vec3 grad() const { return {real(gx), real(gy), real(gz)}; }
};

// Sums a pass of the cg pressure solve takes over its rows (pressure_cg.cpp): `sum` added, `max` the
// largest (-inf over no rows; exact in any order of blocks, so every thread count gives the same).
struct PressureSums {
  real sum[6] = {0, 0, 0, 0, 0, 0};
  real max = -std::numeric_limits<real>::infinity();
  PressureSums& operator+=(const PressureSums& o) {
    for (int k = 0; k < 6; ++k) sum[k] += o.sum[k];
    if (o.max > max) max = o.max;
    return *this;
  }
};

// The iisph solver's scratch, the iisph solver object's own (iisph_solver.cpp), sized by its
// resize() when particles were added or removed (a step allocates nothing). Every particle has a
// row (indexed like the particles, cell order): a material particle's lists every neighbour within
// h, a boundary or tool particle's its material neighbours (the pressure solve's constraints are
// every particle's density; only material moves).
struct IisphScratch {
  static constexpr int kPairStride = 64;  // neighbours within h kept per row
  std::vector<std::uint32_t> material;       // [material] the material particles, cell order (at a rebuild)
  std::vector<std::uint32_t> active;         // [<= n] the rows of the pressure solve this step: material, and
                                             // boundary and tool particles with material neighbours
  std::uint32_t active_count = 0;
  std::vector<SolverPair> pairs;             // [n * kPairStride]: material neighbours from the front, boundary
                                             // and tool neighbours from the back
  std::vector<std::uint8_t> n_material, n_other;  // [n] entries at each end
  // [n] per row:
  std::vector<Vec3> grad_sum;        // S_i = sum_j m_j gradW_ij over every neighbour (material rows)
  std::vector<real> diag_x;          // a_ii = -dt^2 / rho_i^2 diag_x (pressure_jacobi.cpp)
  std::vector<real> visc_diag;       // material rows: sum_j of the row's visc
  std::vector<Vec3> visc_fixed;      // material rows: sum over boundary and tool neighbours of visc v_j
  std::vector<real> div_fixed;       // material rows: sum over boundary and tool neighbours of v_j . m_j gradW_ij
  std::vector<Vec3> normal;          // material: h sum_j V_j gradW_ij, the paste's surface normal (surface tension)
  std::vector<Vec3> v_star;          // material: velocity after gravity and adhesion, then after the pressure
  std::vector<real> source;          // target density - max(rho_adv, target)
  std::vector<Vec3> tool_force;      // N, tool particles: adhesion on them
  std::vector<real> inv_rho;         // 1 / rho (this step's density)
  std::vector<real> q;               // p / rho^2
  // The viscous pressure's p / rho^2 this step by particle (viscous_pressure.cpp; 0 for walls and the
  // tool; empty without iisph.viscous_pressure). The pressure itself is the State's.
  std::vector<real> q_viscous;
  bool with_viscous_pressure = false;  // sized for it (a model that turns it on or off is sized again)
  std::vector<Vec3> accel;           // m/s^2, pressure acceleration of material (0 for the rest; after the
                                     // solve, the viscous pressure's: viscous_pressure.cpp)
  std::vector<Vec3> v_a;             // m/s, v* then v* + dt a_p then v** (boundary, tool: their velocity)
  std::vector<Vec3> cg_p, cg_r, cg_ap;  // the viscosity's conjugate gradients: direction, residual, A p
  // The interface's (interface.cpp): the factor its contact's strength weakened each material
  // particle's coupling to the instrument by this step (1: not at all); valid where the step's
  // diagnostics count any (StepDiagnostics::interface_capped).
  std::vector<real> interface_scale;
  // A non-Newtonian material's (rheology.cpp), sized only where the model has one (`rheology`):
  bool rheology = false;
  std::vector<float> visc_unit;      // [n * kPairStride] each row entry's weight without the viscosity:
                                     // 2 (d + 2) r / ((r^2 + 0.01 h^2) m_j |W'(r)| rho_j), d = 3
  std::vector<real> mu_eff;          // [n] Pa s, each material particle's effective viscosity
  std::vector<Vec3> visc_block;      // [n] material rows: sum_j c_ij g_ij,k^2 per component k
  std::vector<Vec3> partial;         // [n / kSumBlock + 1] sums of fixed blocks of rows (solver/block_sum.hpp)
  // The cg pressure solve's (pressure_cg.cpp), in its scaled unknowns y = sqrt(H_ii) q:
  std::vector<real> pc_scale;        // sqrt(H_ii) of each active row
  std::vector<real> pc_y, pc_g;      // the unknown and the gradient of the quadratic it minimises
  std::vector<real> pc_dir;          // the search direction, as q (p / rho^2): 0 outside the solve
  std::vector<real> pc_hp;           // H times the direction, scaled
  std::vector<PressureSums> pc_partial;  // [n / kSumBlock + 1] its sums of blocks of rows
  static constexpr int kSumBlock = 64;
  // The tool's neighbours, found every step (solver/tool_pairs.cpp): the tool moves farther in a
  // step than the neighbour lists' skin allows, so its particles are left out of the lists and of
  // their rebuild's criterion.
  static constexpr int kToolStride = 128;    // neighbours within h kept per tool particle
  std::vector<std::uint32_t> tools;          // [tool] the tool particles, cell order (at a rebuild)
  std::vector<std::uint32_t> tool_list;      // [tool * kToolStride] each one's neighbours within h
  std::vector<std::uint16_t> tool_count;     // [tool] entries of tool_list (kToolStride + 1: overflowed)
  std::vector<std::uint32_t> link_start;     // [n + 1] the other particles' tool neighbours: those of i
  std::vector<std::uint32_t> link_fill;      // [n]     are link_tool[link_start[i], link_start[i + 1])
  std::vector<std::uint32_t> link_tool;      // [tool * kToolStride]

  // Sizes every array for the particles of `state` (scratch.cpp), those of a non-Newtonian material
  // where `with_rheology`, the viscous pressure's where `with_viscous` (kept where particles
  // were added, zero again where any were removed: their ids changed).
  void resize(const State& state, bool with_rheology, bool with_viscous);
  std::size_t bytes() const;
};

}  // namespace dentsph
