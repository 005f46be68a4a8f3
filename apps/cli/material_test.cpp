// `dentsph material-test depth-of-cure [--material PRESET] [--irradiance MW_PER_CM2] [--time S]`,
// `dentsph material-test rheometer|slump|packing|tack|condensation [--material NAME] [--temperature C] [--out DIR]`.
#include "material_test.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <vector>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "dentsph/cure_material.hpp"
#include "dentsph/curing_light.hpp"
#include "dentsph/handling.hpp"
#include "dentsph/paste_presets.hpp"
#include "output_dir.hpp"

namespace dentsph::cli {

void MaterialTestCommand::add_to(CLI::App& app) {
  command_ = app.add_subcommand(
      "material-test", "Virtual material tests: depth-of-cure (ISO 4049); the pastes' handling tests rheometer, slump, packing, tack, condensation");
  command_->require_subcommand(1);
  depth_of_cure_ = command_->add_subcommand(
      "depth-of-cure",
      "ISO 4049 depth of cure: a mould 4 mm across filled, cured from the top, the paste that has not set scraped "
      "away; half the set length");
  depth_of_cure_->add_option("--material", options_.material, "The material preset")
      ->check(CLI::IsMember(cure_material_presets()))
      ->capture_default_str();
  depth_of_cure_->add_option("--irradiance", irradiance_mw_, "The light's irradiance at its window, mW/cm2")
      ->check(CLI::Range(1.0, 10000.0))
      ->capture_default_str();
  depth_of_cure_->add_option("--time", options_.exposure_time, "Exposure time, s")
      ->check(CLI::Range(0.01, 3600.0))
      ->capture_default_str();
  depth_of_cure_->add_option("--spacing", spacing_mm_, "The paste's particle spacing, mm")
      ->check(CLI::Range(0.02, 0.5))
      ->capture_default_str();
  depth_of_cure_->add_option("--mould-length", length_mm_, "The mould's length, mm")
      ->check(CLI::Range(1.0, 50.0))
      ->capture_default_str();
  const char* descriptions[] = {
      "Parallel-plate rheometer: oscillation at 10 rad/s (complex viscosity, phase angle) and steady shear (the flow curve), beside the published ranges",
      "Slump on glass (Lee et al., Dent Mater 2010): a fixed volume let go for 10 s, its aspect ratio height / diameter",
      "Packing: 3 mm and 6 mm flat probes driven at 0.5 mm/s 2 mm into a mould 7 mm across, held 10 s: the stress "
      "under the probe",
      "Probe tack: a 6 mm probe (steel, or --instrument coated) pressed onto the paste at 1 N for 1 s, withdrawn "
      "at 2, 4, 6 and 8 mm/s: the peak pull and the work of separation",
      "Condensation (amalgam, the default here): 1.15 mm and 1.8 mm flat pluggers driven 0.5 mm into a 1 mm "
      "increment on a cavity's floor: the peak stress and force"};
  static_assert(std::size(descriptions) == std::tuple_size_v<decltype(handling_)>);
  for (std::size_t k = 0; k < handling_.size(); ++k) add_handling(*command_, descriptions[k], handling_[k]);
}

void MaterialTestCommand::add_handling(CLI::App& parent, const std::string& description, Handling& h) {
  h.command = parent.add_subcommand(h.name, description);
  h.command->add_option("--material", h.material, fmt::format("The paste: {}", fmt::join(paste_preset_names(), ", ")))
      ->check(CLI::IsMember(paste_preset_names()))
      ->capture_default_str();
  h.command->add_option("--temperature", h.temperature_c, "The paste's temperature, C (10 to 70)")
      ->check(CLI::Range(10.0, 70.0))
      ->capture_default_str();
  h.command->add_option("--out", h.out, "Write result.json and the plots (SVG) into this folder");
  if (h.name == "tack" || h.name == "packing" || h.name == "condensation")
    h.command
        ->add_option("--instrument", h.instrument,
                     fmt::format("The probe's surface: {} (non-stick)", fmt::join(instrument_surface_names(), " or ")))
        ->check(CLI::IsMember(instrument_surface_names()))
        ->capture_default_str();
  if (h.name == "rheometer")
    h.command
        ->add_option("--shear-rates", h.shear_rates,
                     fmt::format("The rates of the flow curve, 1/s at the rim, ascending, at least two (each a steady run; "
                                 "default {}: fewer take less time)",
                                 fmt::join(RheometerOptions{}.shear_rates, ",")))
        ->delimiter(',')
        ->check(CLI::Range(0.01, 1000.0));
  h.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  h.command->add_option("--threads", h.threads, "Threads for the parallel stages")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
}

int MaterialTestCommand::run_handling(const Handling& h) const {
  if (!h.out.empty()) prepare_output_dir(h.out, "--out");  // before the test: never lost at its end
  HandlingRunOptions run;
  run.threads = h.threads;
  run.instrument = h.instrument;
  run.progress = [](const std::string& line) { fmt::print("{}\n", line); };
  const PastePreset preset = paste_preset(h.material, h.temperature_c);
  HandlingResult r;
  if (!h.shear_rates.empty()) {
    RheometerOptions o;
    o.run = run;
    o.shear_rates.assign(h.shear_rates.begin(), h.shear_rates.end());
    try {
      check_rheometer_options(o);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("--shear-rates {}: {}", fmt::join(h.shear_rates, ","), e.what()));
    }
    r = rheometer_test(preset, o);
  } else {
    r = run_handling_test(h.name, preset, run);
  }
  fmt::print("{}", handling_report(r));
  if (!h.out.empty()) {
    write_handling_outputs(h.out, r);
    fmt::print("wrote {}/result.json", h.out);
    for (const HandlingCurve& c : r.curves) fmt::print(", {}.svg", c.file);
    fmt::print("\n");
  }
  return 0;
}

bool MaterialTestCommand::chosen() const { return command_ != nullptr && command_->parsed(); }

int MaterialTestCommand::run() const {
  for (const Handling& h : handling_)
    if (h.command->parsed()) return run_handling(h);
  DepthOfCureOptions o = options_;
  o.irradiance = irradiance_mw_ * W_per_m2_per_mW_per_cm2;
  o.spacing = spacing_mm_ * 1e-3;
  o.mould_length = length_mm_ * 1e-3;
  const DepthOfCureResult r = depth_of_cure_test(o);
  fmt::print("{}", depth_of_cure_report(o, r));
  return 0;
}

}  // namespace dentsph::cli
