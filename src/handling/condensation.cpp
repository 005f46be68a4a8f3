// The condensation test (include/dentsph/handling.hpp; docs/model.md, "Handling tests"): a flat
// plugger driven into an increment of paste on the floor of a cylindrical cavity, as an amalgam is
// condensed, on the packing test's rig (a finer spacing: the smaller plugger is 1.15 mm across).
#include <fmt/format.h>

#include "dentsph/handling.hpp"
#include "handling/rig.hpp"

namespace dentsph {

HandlingResult condensation_test(const PastePreset& preset, const CondensationOptions& o) {
  if (o.plugger_diameters.empty() || !(o.spacing > 0) || !(o.speed > 0) || !(o.depth > 0) || !(o.dt > 0) ||
      !(o.increment > o.depth))
    throw std::invalid_argument(
        "condensation: give at least one plugger, a positive spacing, speed, depth and dt, and an increment thicker "
        "than the stroke");
  for (real d : o.plugger_diameters)
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
  for (real d : o.plugger_diameters) {
    handling::MouldRig rig = handling::mould_rig(preset, o.spacing, o.cavity_diameter, o.increment, d, o.dt,
                                                 instrument_interface_strength(o.run.instrument));
    const handling::ProbePress run = handling::press_probe(rig, d, o.speed, o.depth, 0, o.dt, o.run, "condensation");
    const std::string plugger = fmt::format("{:g} mm plugger", d * 1e3);
    const real force = run.peak_force;
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
  r.notes.push_back(fmt::format(
      "a {:g} mm increment on the floor of a cavity {:g} mm across ({:g} mm spacing); the plugger driven {:g} mm into "
      "it at {:g} mm/s (assumed: a condensing stroke); the stress is the paste's force on the plugger over its "
      "face's area; the paste is not densified (a real amalgam's condensation also expresses mercury and closes "
      "voids, which the model has not)",
      o.increment * 1e3, o.cavity_diameter * 1e3, o.spacing * 1e3, o.depth * 1e3, o.speed * 1e3));
  return r;
}

}  // namespace dentsph
