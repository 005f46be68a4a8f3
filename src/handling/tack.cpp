// The probe-tack test (include/dentsph/handling.hpp; docs/model.md, "Handling tests"), after the
// stickiness method of Kaleem, Satterthwaite & Watts: on the mould rig (rig.hpp) the 6 mm probe is
// lowered onto the paste (its face to the paste's surface) and on until it bears the press force,
// held where it is, then withdrawn at a
// constant speed. The paste pulls the probe back (drawn up with it by the no-slip viscous coupling,
// up to what its contact with the probe carries, Material::interface_strength, the smaller of the
// paste's and the probe's surface's): the peak of that pull is the tack force, its integral over
// the probe's travel the work of separation. The pressure never pulls (the solve's pressures are
// not negative), so no suction is modelled.
#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "dentsph/handling.hpp"
#include "handling/rig.hpp"

namespace dentsph {

namespace {

struct Pull {
  std::vector<real> travel, force;  // mm from where the pull started, N (the pull: positive down)
  real peak = 0;                    // N
  real work = 0;                    // N mm
};

Pull pull(const PastePreset& preset, real speed, const TackOptions& o) {
  handling::MouldRig rig = handling::mould_rig(preset, o.spacing, o.mould_diameter, o.mould_depth, o.probe_diameter, o.dt,
                                               instrument_interface_strength(o.run.instrument));
  State& st = rig.state;
  const real max_travel = rig.face_gap + 2e-3;
  // Down onto the paste (its face at the paste's surface: the paste's first layer bonds to it, a
  // spacing from the probe's) and on until it bears the press force.
  real z = 0;
  while ((z < rig.face_gap || st.tool_wrench.force.z < o.press_force) && z < max_travel) {
    z = std::min(max_travel, z + o.press_speed * o.dt);
    st.tool_pose = Pose{Vec3{0, 0, -z}, Quat{}};
    handling::rig_step(rig.model, st, o.run, "tack");
  }
  Pull p;
  // Held there.
  for (real t = 0; t < o.press_time - 0.5 * o.dt; t += o.dt) handling::rig_step(rig.model, st, o.run, "tack");
  // Withdrawn.
  const real z0 = z;
  for (real up = 0; up < o.pull_distance - 1e-12;) {
    const real before = up;
    up = std::min(o.pull_distance, up + speed * o.dt);
    st.tool_pose = Pose{Vec3{0, 0, -(z0 - up)}, Quat{}};
    handling::rig_step(rig.model, st, o.run, "tack");
    const real f = -st.tool_wrench.force.z;  // the paste pulling the probe down
    p.travel.push_back(up * 1e3);
    p.force.push_back(f);
    p.peak = std::max(p.peak, f);
    p.work += std::max<real>(0, f) * (up - before) * 1e3;  // N mm over this step's travel
  }
  if (o.run.progress)
    o.run.progress(fmt::format("tack: {} withdrawn at {:g} mm/s: peak {:.3g} N, work {:.3g} N mm", preset.name,
                               speed * 1e3, p.peak, p.work));
  return p;
}

}  // namespace

HandlingResult tack_test(const PastePreset& preset, const TackOptions& o) {
  if (o.speeds.empty() || !(o.spacing > 0) || !(o.dt > 0) || !(o.press_force > 0) || !(o.press_speed > 0) ||
      !(o.press_time >= 0) || !(o.pull_distance > 0))
    throw std::invalid_argument("tack: give at least one speed and a positive spacing, dt, press force, press speed and "
                                "pull distance");
  for (real v : o.speeds)
    if (!(v > 0)) throw std::invalid_argument("tack: every withdrawal speed must be > 0");
  (void)instrument_interface_strength(o.run.instrument);  // an unknown surface refused before any run
  if (!(o.probe_diameter > 2 * o.spacing) || !(o.probe_diameter < o.mould_diameter - 2 * o.spacing))
    throw std::invalid_argument("tack: the probe must be wider than two spacings and narrower than the mould less two");
  HandlingResult r = handling::result_of("tack", preset);
  HandlingCurve curve;
  curve.file = "tack";
  curve.title = fmt::format("Tack: {} at {:g} C, a {:g} mm {} probe withdrawn", preset.name, preset.temperature_c,
                            o.probe_diameter * 1e3, o.run.instrument);
  curve.x_label = "probe's travel from the paste (mm)";
  curve.legend_right = true;
  curve.y_label = "the paste's pull on the probe (N)";
  const std::string source = "Kaleem, Satterthwaite & Watts, the probe-tack stickiness of unset resin composites: a 6 mm "
                             "steel probe withdrawn at 2 to 8 mm/s, the values rising with the speed";
  for (real v : o.speeds) {
    const Pull p = pull(preset, v, o);
    const std::string at = fmt::format("at {:g} mm/s", v * 1e3);
    r.figures.push_back({"peak tack force " + at, p.peak, "N", std::array<real, 2>{0.47, 3.68}, source});
    r.figures.push_back({"work of separation " + at, p.work, "N mm", std::array<real, 2>{0.11, 2.84}, source});
    curve.series.push_back({at, p.travel, p.force, false});
  }
  r.curves.push_back(curve);
  r.notes.push_back(fmt::format(
      "the probe lowered at {:g} mm/s until it bore {:g} N, held {:g} s, withdrawn {:g} mm; a mould {:g} mm across and "
      "{:g} mm deep ({:g} mm spacing); the pressure cannot pull, so no suction is modelled",
      o.press_speed * 1e3, o.press_force, o.press_time, o.pull_distance * 1e3, o.mould_diameter * 1e3,
      o.mould_depth * 1e3, o.spacing * 1e3));
  const real strength =
      contact_strength(preset.paste.interface_strength, instrument_interface_strength(o.run.instrument));
  r.notes.push_back(
      strength > 0 ? fmt::format("a {} probe: the paste's contact with it carries {:g} kPa at most (the interface "
                                 "strength; docs/model.md, \"Tack\"), the published ranges are for steel",
                                 o.run.instrument, strength * 1e-3)
                   : fmt::format("a {} probe: the paste's contact with it holds whatever the tension (no interface "
                                 "strength)",
                                 o.run.instrument));
  return r;
}

}  // namespace dentsph
