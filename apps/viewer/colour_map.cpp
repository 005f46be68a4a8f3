// Colour maps (colour_map.hpp).
#include "colour_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "dentsph/io/role_colours.hpp"

namespace dentsph::viewer {

const char* colour_by_name(ColourBy c) {
  switch (c) {
    case ColourBy::role: return "role";
    case ColourBy::pressure: return "pressure";
    case ColourBy::density: return "density";
    case ColourBy::speed: return "speed";
    case ColourBy::bonds: return "bonds";
    case ColourBy::conversion: return "conversion";
  }
  return "?";
}

const char* colour_by_unit(ColourBy c) {
  switch (c) {
    case ColourBy::role: return "";
    case ColourBy::pressure: return "Pa";
    case ColourBy::density: return "kg/m^3";
    case ColourBy::speed: return "m/s";
    case ColourBy::bonds: return "bonds";
    case ColourBy::conversion: return "DC";  // degree of conversion
  }
  return "";
}

ColourBy colour_by_from_name(const std::string& name) {
  for (ColourBy c : kColourModes)
    if (name == colour_by_name(c)) return c;
  throw std::invalid_argument(
      fmt::format("colour mode '{}' is unknown; use one of role, pressure, density, speed, bonds, conversion", name));
}

Rgb role_colour(Role r) { return io::role_colour(r); }

Rgb colour_map(float t) {
  if (!std::isfinite(t)) return {1, 0, 1};
  t = std::clamp(t, 0.f, 1.f);
  // Viridis at nine stops, linearly interpolated.
  static constexpr std::array<Rgb, 9> stops = {{{0.267f, 0.005f, 0.329f},
                                                {0.283f, 0.141f, 0.458f},
                                                {0.254f, 0.265f, 0.530f},
                                                {0.207f, 0.372f, 0.553f},
                                                {0.164f, 0.471f, 0.558f},
                                                {0.128f, 0.567f, 0.551f},
                                                {0.135f, 0.659f, 0.518f},
                                                {0.478f, 0.821f, 0.318f},
                                                {0.993f, 0.906f, 0.144f}}};
  const float x = t * float(stops.size() - 1);
  const int k = std::min(int(x), int(stops.size()) - 2);
  const float f = x - float(k);
  Rgb c;
  for (int i = 0; i < 3; ++i) c[i] = stops[k][i] * (1 - f) + stops[k + 1][i] * f;
  return c;
}

Range auto_range(std::span<const float> values, std::span<const Role> roles) {
  std::vector<float> v;
  for (std::size_t i = 0; i < values.size() && i < roles.size(); ++i)
    if (roles[i] == Role::material && std::isfinite(values[i])) v.push_back(values[i]);
  if (v.empty()) return {0, 1};
  auto at = [&](double q) {
    const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
    return v[k];
  };
  Range r{at(0.02), at(0.98)};
  if (!(r.hi > r.lo)) {
    const float pad = std::max(1e-6f, std::abs(r.lo) * 0.05f);
    r = {r.lo - pad, r.hi + pad};
  }
  return r;
}

void particle_colours(ColourBy mode, std::span<const float> field, std::span<const Role> roles, Range range,
                      std::vector<float>& rgb_out) {
  const std::size_t n = roles.size();
  rgb_out.resize(3 * n);
  const float span = range.hi > range.lo ? range.hi - range.lo : 1.f;
  for (std::size_t i = 0; i < n; ++i) {
    Rgb c = role_colour(roles[i]);
    if (mode != ColourBy::role) {
      if (roles[i] == Role::material && i < field.size()) {
        c = colour_map((field[i] - range.lo) / span);
      } else {
        for (float& x : c) x = 0.55f + 0.45f * x;  // walls and tool muted towards grey-white
      }
    }
    rgb_out[3 * i] = c[0];
    rgb_out[3 * i + 1] = c[1];
    rgb_out[3 * i + 2] = c[2];
  }
}

}  // namespace dentsph::viewer
