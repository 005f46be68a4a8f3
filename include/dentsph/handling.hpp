// Virtual handling tests of the filling pastes (docs/model.md, "Handling tests"): each reproduces a
// published protocol on particles (its geometry, speed and the quantity measured) with a preset
// (paste_presets.hpp) and gives its figures beside the published range and source.
// `dentsph material-test rheometer|slump|packing|tack|condensation --material NAME [--out DIR]` runs them; with
// --out each writes result.json and its curves as SVG plots.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dentsph/paste_presets.hpp"

namespace dentsph {

// One measured figure beside what was published.
struct HandlingFigure {
  std::string name;                       // e.g. "viscosity at 10 /s"
  real value = 0;
  std::string unit;                       // e.g. "Pa s"
  std::optional<std::array<real, 2>> range;  // the published range [low, high], where one is published
  std::string source;                     // where the range comes from, or why there is none
  // Whether the value lies in the range (true where there is none).
  bool in_range() const { return !range || (value >= (*range)[0] && value <= (*range)[1]); }
};

// A curve the test measured (plotted as `file`.svg), with the model's own law or the published
// points as further series.
struct HandlingSeries {
  std::string name;
  std::vector<real> x, y;
  bool dashed = false;  // drawn dashed: a law or a reference, not a measurement
};
struct HandlingCurve {
  std::string file;     // the plot's file name without its extension, e.g. "flow_curve"
  std::string title;
  std::string x_label, y_label;  // with their units
  bool log_x = false, log_y = false;
  std::vector<HandlingSeries> series;
  bool legend_right = false;  // the legend in the upper right corner (else the upper left)
  // A published range drawn as a bar at x: [x, low, high].
  std::optional<std::array<real, 3>> range_bar;
};

struct HandlingResult {
  std::string test;      // one of handling_test_names()
  std::string material;  // the preset's name
  real temperature_c = 23;
  std::vector<HandlingFigure> figures;
  std::vector<HandlingCurve> curves;
  std::vector<std::string> notes;  // what a reader must know to read the figures (calibrations, departures)
  const HandlingFigure& figure(const std::string& name) const;  // std::out_of_range naming it
};

// What every test takes besides its geometry.
struct HandlingRunOptions {
  int threads = 1;
  // The surface of the probe, plugger or plate the paste meets: instrument_surface_names() ("steel",
  // or "coated": non-stick). Its contact's strength (Material::interface_strength) limits a pull.
  std::string instrument = "steel";
  std::function<void(const std::string&)> progress;  // a line per stage, where set
};

// The parallel-plate rheometer: a disc of paste between a fixed plate and a turning one. In
// oscillation (Lee, Son & Um, Dent Mater 2003), the plate turned back and forth at 10 rad/s: the
// storage and loss moduli from the torque's first harmonic, the complex viscosity and the phase
// angle. In steady shear (the flow curve), at each rim shear rate the torque over the same quarter
// turn of the plate, read as the viscosity at the rim's shear rate with the Weissenberg-Rabinowitsch
// correction for parallel plates. Every torque divided by the rheometer's constant measured, as a
// real rheometer's is, with a Newtonian standard of the same form.
struct RheometerOptions {
  HandlingRunOptions run;
  std::vector<real> shear_rates{1, 2, 5, 10, 20, 50, 100};  // 1/s at the rim, ascending, at least two
  real spacing = 0.3e-3;       // m (the dental paste's)
  int radius_spacings = 14;    // the disc's radius R
  int gap_layers = 6;          // the paste's layers; the gap H between the plates' first layers is one more
  // The oscillation (docs/model.md, "Handling tests"): the plate turned back and forth at `frequency`
  // to the rim's strain amplitude, for `cycles` periods (the first let go by: the stress builds up).
  real frequency = 10;         // rad/s
  real strain_amplitude = 1;   // at the rim
  int cycles = 3;
};
// Throws std::invalid_argument for options rheometer_test cannot run: fewer than two shear rates,
// rates not positive and ascending, an impossible rig (rheometer_test checks them so first).
void check_rheometer_options(const RheometerOptions& options);
HandlingResult rheometer_test(const PastePreset& preset, const RheometerOptions& options = {});

// The slump test of Lee et al. (Dent Mater 2010): a fixed volume of paste (here a cylinder as tall
// as it is wide) let go on a glass plate, slumping for 10 s under gravity; the aspect ratio
// height / diameter at the end.
struct SlumpOptions {
  HandlingRunOptions run;
  real diameter = 3e-3;   // m, of the cylinder (its height is the same)
  real duration = 10;     // s
  real spacing = 0.3e-3;  // m
  real dt = 10e-3;        // s, at most (the velocity limit may take smaller steps)
};
HandlingResult slump_test(const PastePreset& preset, const SlumpOptions& options = {});

// The packing test: a flat probe driven at 0.5 mm/s 2 mm deep into paste filling a mould 7 mm
// across and 5 mm deep, then held still for 10 s; the stress under the probe (its force over its
// face's area) at its peak and as it relaxes over the hold, for a 3 mm and a 6 mm probe (the 6 mm
// one leaves the paste half a millimetre to the mould's wall: the wall effect).
struct PackingOptions {
  HandlingRunOptions run;
  std::vector<real> probe_diameters{3e-3, 6e-3};  // m
  real mould_diameter = 7e-3;  // m
  real mould_depth = 5e-3;     // m, filled level with its rim
  real speed = 0.5e-3;         // m/s
  real depth = 2e-3;           // m below the paste's surface
  real hold = 10;              // s
  real spacing = 0.3e-3;       // m
  real dt = 0.02;              // s
};
HandlingResult packing_test(const PastePreset& preset, const PackingOptions& options = {});

// The probe-tack test of Kaleem, Satterthwaite & Watts: a 6 mm steel probe pressed onto paste
// filling the packing test's mould until it bears `press_force`, held there `press_time`, then
// withdrawn at each speed; the peak pull-off force and the work of separation (the pull's force
// integrated over the probe's travel) at each speed.
struct TackOptions {
  HandlingRunOptions run;
  std::vector<real> speeds{2e-3, 4e-3, 6e-3, 8e-3};  // m/s
  real probe_diameter = 6e-3;  // m
  real mould_diameter = 7e-3;  // m
  real mould_depth = 5e-3;     // m
  real press_force = 1;        // N
  real press_speed = 0.5e-3;   // m/s, down onto the paste and on until the probe bears press_force (at most 2 mm in)
  real press_time = 1;         // s, the probe held where it bore press_force
  real pull_distance = 1.5e-3;  // m (the adhesion's reach is 0.9 mm)
  real spacing = 0.3e-3;       // m
  real dt = 5e-3;              // s
};
HandlingResult tack_test(const PastePreset& preset, const TackOptions& options = {});

// The condensation of an amalgam: a flat plugger driven into a 1 mm increment on the floor of a
// cavity 4 mm across, as a practitioner condenses it; the peak stress under the plugger (its force
// over its face's area) and the peak force, for a 1.15 mm and a 1.8 mm plugger. For a paste that
// sets by itself (its cure preset self_setting: the amalgam), the working window too: the
// `window_plugger` condensing the paste at each of `ages` (s after mixing) before its gel point, its
// flow curve raised by the setting (setting_viscosity_factor), and the working time, the age at which
// the peak stress has doubled; no window where `ages` is empty.
struct CondensationOptions {
  HandlingRunOptions run;
  std::vector<real> plugger_diameters{1.15e-3, 1.8e-3};  // m
  real cavity_diameter = 4e-3;  // m
  real increment = 1e-3;        // m, the paste's thickness on the cavity's floor
  real speed = 1e-3;            // m/s, the plugger's (assumed: a condensing stroke)
  real depth = 0.5e-3;          // m into the increment
  real spacing = 0.1e-3;        // m
  real dt = 5e-3;               // s
  std::vector<real> ages{0, 120, 180, 210, 240, 270, 300, 330};  // s after mixing
  real window_plugger = 1.8e-3;  // m
};
HandlingResult condensation_test(const PastePreset& preset, const CondensationOptions& options = {});

// The test named `test` (one of handling_test_names(): "rheometer", "slump", "packing", "tack",
// "condensation") with default options but `run`.
// std::invalid_argument naming the choices for another name.
HandlingResult run_handling_test(const std::string& test, const PastePreset& preset, const HandlingRunOptions& run);
const std::vector<std::string>& handling_test_names();

// The figures as a table for people: name, value, published range, in range or not, source.
std::string handling_report(const HandlingResult& result);
// {"test", "material", "temperature_c", "figures": [{"name", "value", "unit", "range": [low, high] or
// null, "in_range", "source"}], "curves": [{"file", ...}], "notes": [...]}.
std::string handling_result_json(const HandlingResult& result);
// Writes result.json and each curve's SVG plot into `dir` (created). std::runtime_error naming a
// file that cannot be written.
void write_handling_outputs(const std::filesystem::path& dir, const HandlingResult& result);

}  // namespace dentsph
