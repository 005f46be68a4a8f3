// The paste's generalised Newtonian viscosity (docs/model.md, "Rheology"), shared by the solver and
// its tests: the effective viscosity of a Herschel-Bulkley material at a shear rate, regularised by
// a cap, and the shear rate of a velocity gradient.
#pragma once

#include <algorithm>
#include <cmath>

#include "dentsph/material.hpp"

namespace dentsph::rheology {

// The cap of a non-Newtonian material's viscosity: max_viscosity, or 1000 mu where it is 0.
inline real viscosity_cap(const Material& m) { return m.max_viscosity > 0 ? m.max_viscosity : 1000 * m.mu; }

// Pa s at shear rate `gamma` (1/s): mu for a Newtonian material; otherwise
// min(cap, mu gamma^(n - 1) + yield_stress / gamma), the cap at rest (gamma 0). The stress
// mu_eff gamma is the Herschel-Bulkley law's wherever the paste flows faster than the cap allows
// (gamma > yield_stress / cap for a Bingham paste), and the cap's Newtonian stress below: a paste
// under its yield stress creeps at the cap's viscosity instead of standing still (the regularisation
// of Bercovier & Engelman 1980, a bi-viscous law).
inline real effective_viscosity(const Material& m, real gamma) {
  if (newtonian(m)) return m.mu;
  const real cap = viscosity_cap(m);
  if (!(gamma > 0)) return cap;
  const real flowing = (m.flow_index == 1 ? m.mu : m.mu * std::pow(gamma, m.flow_index - 1)) + m.yield_stress / gamma;
  return std::min(cap, flowing);
}

// The shear rate sqrt(2 D:D) of the velocity gradient L (L[a][b] = d v_a / d x_b), D its symmetric
// part: gamma for a simple shear v_x = gamma y.
inline real shear_rate(const real L[3][3]) {
  real dd = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const real d = 0.5 * (L[a][b] + L[b][a]);
      dd += d * d;
    }
  return std::sqrt(2 * dd);
}

}  // namespace dentsph::rheology
