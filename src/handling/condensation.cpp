// The condensation test (include/dentsph/handling.hpp; docs/model.md, "Handling tests"): a flat
// plugger driven into an increment of paste on the floor of a cylindrical cavity, as an amalgam is
// condensed, on the packing test's rig (a finer spacing: the smaller plugger is 1.15 mm across).
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "dentsph/cure_material.hpp"
#include "dentsph/handling.hpp"
#include "handling/rig.hpp"

namespace dentsph {

namespace {

// The paste with its whole flow curve (consistency, yield stress, cap) raised by the setting's factor
// f, as the simulation raises a setting particle's (docs/model.md, "Presets").
PastePreset set_by(const PastePreset& preset, real f) {
  PastePreset p = preset;
  p.paste.mu *= f;
  p.paste.yield_stress *= f;
  p.paste.max_viscosity *= f;
  return p;
}

// The working window: the window plugger condensing the paste at each age before its gel point, and
// the age at which the peak stress has doubled (linear between the ages that straddle it). Ages
// whose paste is the same (the working time's, unset) are condensed once: `fresh_peak`, the window
// plugger's peak on the fresh paste where the test's own pluggers measured it (NaN otherwise).
void working_window(const PastePreset& preset, const CondensationOptions& o, real fresh_peak, HandlingResult& r) {
  const CureMaterial cure = cure_material_preset(preset.cure);
  if (!cure.self_setting || o.ages.empty()) return;
  const real gel = gel_age(cure);
  HandlingCurve curve;
  curve.file = "condensation_window";
  curve.title = fmt::format("Working window: {} under a {:g} mm plugger", preset.name, o.window_plugger * 1e3);
  curve.x_label = "time since mixing (s)";
  curve.y_label = "peak stress under the plugger (MPa)";
  HandlingSeries series{"peak stress", {}, {}, false};
  const std::string source = fmt::format(
      "the paste's setting (cure preset {}: no change for {:g} s, then set with a time constant of {:g} s, its "
      "gel point at {:.0f} s): an amalgam's working time is about 3 minutes, from which the {:g} s was set (a "
      "calibration, not a prediction)",
      preset.cure, cure.working_time, cure.set_time_constant, gel, cure.working_time);
  std::vector<std::pair<real, real>> condensed;  // (the setting's factor, the peak it gave)
  if (std::isfinite(fresh_peak)) condensed.emplace_back(1, fresh_peak);
  real fresh = 0, working = -1;
  for (real age : o.ages) {
    if (!(age >= 0)) throw std::invalid_argument(fmt::format("condensation: an age of {} s since mixing is negative", age));
    if (age >= gel) break;  // set: rigid, not condensed
    const real f = setting_viscosity_factor(cure, conversion_from_age(cure, age));
    const auto same = std::find_if(condensed.begin(), condensed.end(), [f](const auto& c) { return c.first == f; });
    real peak = 0;
    if (same != condensed.end()) {
      peak = same->second;
    } else {
      handling::MouldRig rig = handling::mould_rig(set_by(preset, f), o.spacing, o.cavity_diameter, o.increment,
                                                   o.window_plugger, o.dt, instrument_interface_strength(o.run.instrument));
      peak = handling::press_probe(rig, o.window_plugger, o.speed, o.depth, 0, o.dt, o.run, "condensation").peak;
      condensed.emplace_back(f, peak);
    }
    if (o.run.progress)
      o.run.progress(fmt::format("condensation: {} {:g} s after mixing: peak {:.3g} MPa", preset.name, age, peak));
    if (series.x.empty()) fresh = peak;
    if (working < 0 && !series.x.empty() && peak >= 2 * fresh && series.y.back() < 2 * fresh)
      working = series.x.back() + (age - series.x.back()) * (2 * fresh - series.y.back()) / (peak - series.y.back());
    series.x.push_back(age);
    series.y.push_back(peak);
    r.figures.push_back({fmt::format("peak stress {:g} s after mixing, {:g} mm plugger", age, o.window_plugger * 1e3),
                         peak, "MPa", std::nullopt, source});
  }
  if (working >= 0)
    r.figures.push_back({"working time: the condensing stress doubled", working, "s", std::nullopt, source});
  else
    r.notes.push_back(fmt::format("the peak stress did not double over the ages condensed (up to {:g} s)",
                                  series.x.empty() ? 0 : series.x.back()));
  r.notes.push_back(fmt::format("the working window: the paste condensed at each age as it was then (its whole flow "
                                "curve raised by its setting); it sets rigid at its gel point, {:.0f} s after mixing",
                                gel));
  curve.series.push_back(std::move(series));
  r.curves.push_back(std::move(curve));
}

}  // namespace

HandlingResult condensation_test(const PastePreset& preset, const CondensationOptions& o) {
  if (o.plugger_diameters.empty() || !(o.spacing > 0) || !(o.speed > 0) || !(o.depth > 0) || !(o.dt > 0) ||
      !(o.increment > o.depth))
    throw std::invalid_argument(
        "condensation: give at least one plugger, a positive spacing, speed, depth and dt, and an increment thicker "
        "than the stroke");
  std::vector<real> pluggers = o.plugger_diameters;
  if (!o.ages.empty()) pluggers.push_back(o.window_plugger);
  for (real d : pluggers)
    if (!(d > 4 * o.spacing) || !(d < o.cavity_diameter - 2 * o.spacing))
      throw std::invalid_argument(fmt::format(
          "condensation: a {:g} mm plugger must be wider than four spacings and narrower than the cavity less two",
          d * 1e3));
  HandlingResult r = handling::result_of("condensation", preset);
  HandlingCurve curve;
  curve.file = "condensation";
  curve.title = fmt::format("Condensation: {} at {:g} C, {:g} mm/s into a {:g} mm increment", preset.name,
                            preset.temperature_c, o.speed * 1e3, o.increment * 1e3);
  curve.x_label = "plugger's travel (mm)";
  curve.y_label = "stress under the plugger (MPa)";
  real fresh_peak = std::numeric_limits<real>::quiet_NaN();  // the window plugger's, if it is one of them
  for (real d : o.plugger_diameters) {
    handling::MouldRig rig = handling::mould_rig(preset, o.spacing, o.cavity_diameter, o.increment, d, o.dt,
                                                 instrument_interface_strength(o.run.instrument));
    const handling::ProbePress run = handling::press_probe(rig, d, o.speed, o.depth, 0, o.dt, o.run, "condensation");
    const std::string plugger = fmt::format("{:g} mm plugger", d * 1e3);
    const real force = run.peak_force;
    if (d == o.window_plugger) fresh_peak = run.peak;
    if (o.run.progress)
      o.run.progress(fmt::format("condensation: {} under a {}: peak {:.3g} MPa ({:.3g} N)", preset.name, plugger,
                                 run.peak, force));
    r.figures.push_back({"peak stress, " + plugger, run.peak, "MPa", std::array<real, 2>{4, 9},
                         "condensation stresses of amalgam as practitioners apply them, 4 to 9 MPa with 1.15 to "
                         "1.8 mm pluggers (J Dent Res 1987; Eur J Oral Sci 1995)"});
    r.figures.push_back({"peak force, " + plugger, force, "N", std::nullopt,
                         "practitioners condense with about 9.5 N (1.15 mm plugger) and 10.4 N (1.8 mm): a hand's "
                         "force, not the paste's resistance; shown for scale"});
    HandlingSeries s{plugger, {}, run.stress, false};
    for (real t : run.t) s.x.push_back(std::max(real(0), o.speed * t - rig.face_gap) * 1e3);
    curve.series.push_back(s);
  }
  curve.range_bar = std::array<real, 3>{o.depth * 1e3, 4, 9};
  r.curves.push_back(curve);
  working_window(preset, o, fresh_peak, r);
  r.notes.push_back(fmt::format(
      "a {:g} mm increment on the floor of a cavity {:g} mm across ({:g} mm spacing); the plugger driven {:g} mm into "
      "it at {:g} mm/s (assumed: a condensing stroke); the stress is the paste's force on the plugger over its "
      "face's area; the paste is not densified (a real amalgam's condensation also expresses mercury and closes "
      "voids, which the model has not)",
      o.increment * 1e3, o.cavity_diameter * 1e3, o.spacing * 1e3, o.depth * 1e3, o.speed * 1e3));
  return r;
}

}  // namespace dentsph
