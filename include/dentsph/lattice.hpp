// The mass of a particle of a rest lattice (src/physics/lattice.cpp): the step's, used by every
// scene that samples material on a lattice.
#pragma once

#include "dentsph/model.hpp"

namespace dentsph {

// Particle mass that gives a particle inside an infinite simple cubic lattice of `spacing` the
// density rho0 under the density kernel of `kernel` (the paper's poly6, or the cubic spline where
// the kernel sums the density with it): sum_j m W(r_ij) = rho0. Throws std::invalid_argument for a
// spacing outside h / 10 to h.
real lattice_particle_mass(real rho0, real spacing, const KernelCoeffs& kernel);

}  // namespace dentsph
