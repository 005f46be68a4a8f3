// The tooth, cavity and procedure options that `dentsph run`, `dentsph replay` and
// `dentsph-viewer` share (--mesh, --cavity, --cavity-width, ..., --long-axis, --mesial,
// --procedure), and the scene they describe.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "dentsph/dental.hpp"
#include "dentsph/paste_presets.hpp"

namespace dentsph::cli {

class DentalOptions {
 public:
  // Adds the options to `app`, each excluding `scene_file` (a scene file says all of it itself);
  // --procedure only when `with_procedure`.
  void add_options(CLI::App& app, CLI::Option* scene_file, bool with_procedure);

  // The tooth the options describe. Throws std::invalid_argument naming the option and the fix
  // for an impossible value (a negative width, a taper of 40 degrees, a proximal box's option
  // without --cavity class2). The axes are checked when the tooth is prepared: a zero or
  // non-finite axis, or a mesial direction along the long axis, is refused by the scenes below,
  // the library's reason after the options' names.
  ToothSpec tooth() const;

  // The filling procedure (--procedure, or the built-in one) on the tooth: what `dentsph run`
  // runs without a scene file.
  Scene procedure_scene() const;
  // The dental scene of the tooth (paste in the cavity, a ball pressing): what the viewer opens.
  Scene filled_scene() const;
  // The same filled with `preset` (none: the scene's own paste) whatever --material says: the
  // viewer's preset chooser.
  Scene filled_scene(const std::optional<PastePreset>& preset) const;
  // A replay's: the recording's paste preset and temperature where --material and --temperature
  // were not given.
  void take_material(const std::string& preset, double temperature_c);
  // The paste preset --material and --temperature name (none without --material). Throws
  // std::invalid_argument naming the option for an unknown preset, a temperature out of range, or
  // --temperature without --material.
  std::optional<PastePreset> preset() const;

 private:
  bool given(std::string_view option) const;  // the option was on the command line
  // The preset `name` at --temperature; std::invalid_argument naming the option.
  PastePreset preset_named(const std::string& name) const;
  std::string mesh_, units_ = "mm", procedure_, kind_, side_;
  std::string material_;  // --material: a paste preset (paste_presets.hpp); empty: the paper's paste
  double temperature_ = 23;  // --temperature: the preset's temperature, C
  std::vector<double> values_;  // one per cavity_fields() entry; given where its option was used
  std::vector<double> long_axis_, mesial_;
  std::vector<CLI::Option*> options_;
};

}  // namespace dentsph::cli
