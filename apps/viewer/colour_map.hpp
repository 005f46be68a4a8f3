// Particle colours: by role, or a scalar field (pressure, density, speed, bond count, the paste's
// degree of conversion under the curing light) through a
// perceptually ordered colour map with a range. Pure functions: tested without a window.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "dentsph/state.hpp"

namespace dentsph::viewer {

using Rgb = std::array<float, 3>;  // each in [0, 1]

enum class ColourBy { role, pressure, density, speed, bonds, conversion };
inline constexpr std::array<ColourBy, 6> kColourModes = {ColourBy::role,  ColourBy::pressure, ColourBy::density,
                                                        ColourBy::speed, ColourBy::bonds,    ColourBy::conversion};
const char* colour_by_name(ColourBy c);   // "role", "pressure", ...
const char* colour_by_unit(ColourBy c);   // "Pa", "kg/m^3", "m/s", "bonds", "DC" (degree of conversion), ""
// The mode of a name; throws std::invalid_argument naming the choices.
ColourBy colour_by_from_name(const std::string& name);

// The role colours: paste blue, boundary sand, tool orange (as in the preview images).
Rgb role_colour(Role r);
// Viridis-like map of t in [0, 1] (clamped; NaN maps to magenta so it cannot hide).
Rgb colour_map(float t);

struct Range {
  float lo = 0, hi = 1;
};
// The 2nd and 98th percentiles of `values` over the material particles (the walls' and tool's
// values would otherwise set the scale), widened to a non-empty range; {0, 1} with no material.
Range auto_range(std::span<const float> values, std::span<const Role> roles);

// Colours of every particle ([n] RGB) for `mode`: material by the field, boundary and tool in
// their role colours (muted) so the paste stands out.
void particle_colours(ColourBy mode, std::span<const float> field, std::span<const Role> roles, Range range,
                      std::vector<float>& rgb_out);

}  // namespace dentsph::viewer
