// The colour of each particle role in every picture the project draws (preview.png, the viewer):
// paste blue, boundary sand, tool orange. RGB in [0, 1].
#pragma once

#include <array>

#include "dentsph/state.hpp"

namespace dentsph::io {

inline std::array<float, 3> role_colour(Role r) {
  switch (r) {
    case Role::material: return {0.16f, 0.43f, 0.86f};
    case Role::boundary: return {0.84f, 0.75f, 0.55f};
    case Role::tool: return {0.94f, 0.51f, 0.12f};
  }
  return {1, 0, 1};
}

}  // namespace dentsph::io
