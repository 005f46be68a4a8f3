// `dentsph material-test depth-of-cure [--material PRESET] [--irradiance MW_PER_CM2] [--time S]`.
#include "material_test.hpp"

#include <fmt/format.h>

#include "dentsph/cure_material.hpp"
#include "dentsph/curing_light.hpp"

namespace dentsph::cli {

void MaterialTestCommand::add_to(CLI::App& app) {
  command_ = app.add_subcommand("material-test", "Virtual material tests: depth-of-cure (ISO 4049)");
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
}

bool MaterialTestCommand::chosen() const { return command_ != nullptr && command_->parsed(); }

int MaterialTestCommand::run() const {
  DepthOfCureOptions o = options_;
  o.irradiance = irradiance_mw_ * W_per_m2_per_mW_per_cm2;
  o.spacing = spacing_mm_ * 1e-3;
  o.mould_length = length_mm_ * 1e-3;
  const DepthOfCureResult r = depth_of_cure_test(o);
  fmt::print("{}", depth_of_cure_report(o, r));
  return 0;
}

}  // namespace dentsph::cli
