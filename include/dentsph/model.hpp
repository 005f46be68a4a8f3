// Model: everything that stays fixed during a step (MODEL.md; cf. MuJoCo's mjModel).
// Build one with make_model(); its derived constants are filled in and checked there.
#pragma once

#include <cstdint>
#include <string>

#include "dentsph/vec3.hpp"

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
};

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
};

// Checks `p` and derives the kernel constants, C_d and the grid. Throws std::invalid_argument
// whose message names the offending field and says how to fix it.
Model make_model(const ModelParams& p);

// C_d of MODEL.md: 1 / (x*^zeta - x*^eps) with x* = (zeta/eps)^(1/(eps-zeta)).
real adhesion_normalisation(real eps, real zeta);

}  // namespace dentsph
