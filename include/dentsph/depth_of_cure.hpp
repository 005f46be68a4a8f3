// The virtual depth-of-cure test of ISO 4049 (docs/model.md, "Curing"): a cylindrical mould 4 mm
// across is filled with paste, cured from the top with the light's window on the paste, the paste
// that has not set is scraped away, and the depth of cure is half the length of the set cylinder.
// `dentsph material-test depth-of-cure` runs it.
#pragma once

#include <cstdint>
#include <string>

#include "dentsph/cure_material.hpp"

namespace dentsph {

struct DepthOfCureOptions {
  std::string material = "composite";  // a cure_material_preset
  real irradiance = 1e4;               // W/m^2 at the light's window (1e4 = 1000 mW/cm^2)
  real exposure_time = 20;             // s
  real mould_diameter = 4e-3;          // m (ISO 4049: 4 mm)
  real mould_length = 10e-3;           // m: longer than any cured length, so the paste's base stays soft
  real spacing = 0.1e-3;               // m, the paste's lattice
  real light_diameter = 8e-3;          // m, wider than the mould
  real cure_dt = 0.05;                 // s per cure update (the paste is at rest: no step in between)
};

struct DepthOfCureResult {
  CureMaterial material;
  PublishedDepthOfCure published;      // depth 0 when the preset has no published value
  real cured_length = 0;               // m, of the set cylinder left after scraping
  real depth = 0;                      // m, ISO 4049 depth of cure: cured_length / 2
  real top_dose = 0;                   // J/m^2 at the top layer
  bool set_to_bottom = false;          // the whole mould set: its length, not the light, limited it
  std::uint32_t particles = 0, scraped = 0;
};

// Runs the test. Throws std::invalid_argument for an unknown material, one that is not light-cured
// (the message says so), or a non-positive option.
DepthOfCureResult depth_of_cure_test(const DepthOfCureOptions& options);
// The result for people: the depth, the cured length, the published value and the difference.
std::string depth_of_cure_report(const DepthOfCureOptions& options, const DepthOfCureResult& result);

}  // namespace dentsph
