// The handling tests' rigs (rig.hpp).
#include "handling/rig.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "dentsph/paste_presets.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/step.hpp"

namespace dentsph::handling {

ModelParams rig_params(real s, const Vec3& lo, const Vec3& hi, real dt, const Vec3& gravity) {
  ModelParams p;
  p.dt = dt;
  set_lattice_spacing(p, s);
  p.gravity = gravity;
  p.domain_min = lo;
  p.domain_max = hi;
  p.solver = Solver::iisph;
  p.iisph.pressure_solve = PressureSolve::cg;
  p.iisph.max_iterations = 200;
  p.iisph.viscosity_tolerance = 1e-4;
  p.iisph.viscosity_iterations = 500;
  p.iisph.viscous_pressure = kPresetViscousPressure;
  return p;
}

Material wall_beside(const Material& paste) { return Material{paste.mu, 1.5 * paste.Kp, paste.rho0, 0}; }

HandlingResult result_of(const std::string& test, const PastePreset& preset) {
  HandlingResult r;
  r.test = test;
  r.material = preset.name;
  r.temperature_c = preset.temperature_c;
  return r;
}

void rig_step(const Model& model, State& state, const HandlingRunOptions& run, const std::string& test) {
  step(model, state, StepOptions{run.threads, nullptr});
  if (state.diagnostics.non_finite != 0)
    throw std::runtime_error(fmt::format("the {} test: {} particles' state is not finite at t = {:.3f} s", test,
                                         state.diagnostics.non_finite, state.time));
  if (tool_force_exploded(state.tool_wrench))
    throw std::runtime_error(fmt::format("the {} test: the tool force reached {:.3g} N at t = {:.3f} s: the solve diverged",
                                         test, norm(state.tool_wrench.force), state.time));
}

MouldRig mould_rig(const PastePreset& preset, real s, real mould_diameter, real mould_depth, real probe_diameter,
                   real dt, real probe_strength) {
  const real Rm = 0.5 * mould_diameter, a = 0.5 * probe_diameter;
  const int nz = int(std::lround(mould_depth / s));
  const int reach = int(std::ceil(Rm / s)) + 3;
  const int probe_layers = int(std::lround(3e-3 / s));
  const real L = reach + 2;
  MouldRig rig{make_model(rig_params(s, Vec3{-L, -L, -6} * s, Vec3{L, L, nz + probe_layers + 12.0} * s, dt,
                                     Vec3{0, 0, -9.81})),
               {}, s};
  const Material& paste = preset.paste;
  const Material steel = wall_beside(paste);
  Material probe = steel;
  probe.interface_strength = probe_strength;
  const real m = lattice_particle_mass(paste.rho0, s, rig.model.kernel);
  std::vector<ParticleInit> ps;
  for (int k = -2; k < nz + 2; ++k)
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) {
        const Vec3 x{i * s, j * s, (k + 0.5) * s};
        const real r = std::hypot(x.x, x.y);
        const bool floor = k < 0 && r < Rm + 2 * s, wall = k >= 0 && r >= Rm && r < Rm + 2 * s;
        if (floor || wall) ps.push_back(make_particle(Role::boundary, x, m, steel));
        if (k >= 0 && k < nz && r < Rm) ps.push_back(make_particle(Role::material, x, m, paste));
      }
  // The probe's face a spacing above the paste's surface (z = nz s).
  const real face0 = nz * s + s;
  for (int k = 0; k < probe_layers; ++k)
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) {
        const Vec3 x{i * s, j * s, face0 + (k + 0.5) * s};
        const real r = std::hypot(x.x, x.y);
        if (r < a) ps.push_back(make_particle(Role::tool, x, m, probe));
      }
  rig.state.add_particles(rig.model, ps);
  return rig;
}

ProbePress press_probe(MouldRig& rig, real probe_diameter, real speed, real depth, real hold, real dt,
                       const HandlingRunOptions& run, const std::string& test) {
  State& st = rig.state;
  const real a = 0.5 * probe_diameter, area = std::numbers::pi * a * a;
  const real travel = rig.face_gap + depth, t_stop = travel / speed, t_end = t_stop + hold;
  ProbePress r;
  real end_sum = 0;
  int end_count = 0;
  while (st.time < t_end - 0.5 * dt) {
    const real next = st.time + dt;
    st.tool_pose = Pose{Vec3{0, 0, -std::min(travel, speed * next)}, Quat{}};
    rig_step(rig.model, st, run, test);
    const real stress = st.tool_wrench.force.z / area * 1e-6;
    r.t.push_back(st.time);
    r.stress.push_back(stress);
    if (stress > r.peak) r.peak = stress, r.peak_force = st.tool_wrench.force.z;
    if (hold > 0 && st.time > t_stop + 0.5 * hold + 1e-9) end_sum += stress, ++end_count;  // the hold's second half
  }
  r.end = end_count > 0 ? end_sum / end_count : 0;
  return r;
}

}  // namespace dentsph::handling
