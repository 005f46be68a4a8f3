// The packing test (include/dentsph/handling.hpp; docs/model.md, "Handling tests"): a flat probe
// (the tool: a solid cylinder of particles 3 mm tall) is driven down
// at a constant speed into paste filling a cylindrical mould level with its rim, to a depth below
// the surface, and held there. The paste's force on the probe over the probe's face is the packing
// stress. The mould's floor and wall are boundary particles two layers deep; gravity acts.
#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "dentsph/handling.hpp"
#include "handling/rig.hpp"

namespace dentsph {

namespace {

handling::ProbePress press(const PastePreset& preset, real probe_diameter, const PackingOptions& o) {
  handling::MouldRig rig = handling::mould_rig(preset, o.spacing, o.mould_diameter, o.mould_depth, probe_diameter, o.dt,
                                               instrument_interface_strength(o.run.instrument));
  const handling::ProbePress r = handling::press_probe(rig, probe_diameter, o.speed, o.depth, o.hold, o.dt, o.run, "packing");
  if (o.run.progress)
    o.run.progress(fmt::format("packing: {} under a {:g} mm probe: peak {:.3g} MPa, {:.3g} MPa after the hold",
                               preset.name, probe_diameter * 1e3, r.peak, r.end));
  return r;
}

}  // namespace

HandlingResult packing_test(const PastePreset& preset, const PackingOptions& o) {
  if (o.probe_diameters.empty() || !(o.spacing > 0) || !(o.speed > 0) || !(o.depth > 0) || !(o.hold >= 0) ||
      !(o.dt > 0) || !(o.mould_depth > o.depth))
    throw std::invalid_argument(
        "packing: give at least one probe, a positive spacing, speed, depth and dt, and a mould deeper than the press");
  for (real d : o.probe_diameters)
    if (!(d > 2 * o.spacing) || !(d < o.mould_diameter - 2 * o.spacing))
      throw std::invalid_argument(fmt::format(
          "packing: a {:g} mm probe must be wider than two spacings and narrower than the mould less two", d * 1e3));
  HandlingResult r = handling::result_of("packing", preset);
  HandlingCurve curve;
  curve.file = "packing";
  curve.title = fmt::format("Packing: {} at {:g} C, {:g} mm/s to {:g} mm, held {:g} s", preset.name,
                            preset.temperature_c, o.speed * 1e3, o.depth * 1e3, o.hold);
  curve.x_label = "time (s)";
  curve.y_label = "stress under the probe (MPa)";
  for (real d : o.probe_diameters) {
    const handling::ProbePress run = press(preset, d, o);
    const std::string probe = fmt::format("{:g} mm probe", d * 1e3);
    r.figures.push_back({"peak stress, " + probe, run.peak, "MPa", std::array<real, 2>{0.12, 4.21},
                         "flat-probe packing stresses of resin composites, 0.12 to 4.21 MPa, packables high and "
                         "flowables low (e.g. Elbishari, Satterthwaite & Silikas, Int J Mol Sci 2011)"});
    r.figures.push_back({"stress after the hold over the peak, " + probe, run.peak > 0 ? run.end / run.peak : 0, "",
                         std::nullopt,
                         "published: the stress relaxes over the hold (a viscoelastic paste); a purely viscous "
                         "paste's falls at once to what its yield stress and weight hold"});
    curve.series.push_back({probe, run.t, run.stress, false});
  }
  r.curves.push_back(curve);
  r.notes.push_back(fmt::format("a mould {:g} mm across and {:g} mm deep filled level with its rim ({:g} mm spacing); "
                                "the stress is the paste's force on the probe over its face's area",
                                o.mould_diameter * 1e3, o.mould_depth * 1e3, o.spacing * 1e3));
  return r;
}

}  // namespace dentsph
