// A picture of the particles a person can look at without ParaView: a PNG with two panels, a
// cut through the middle seen from the side and the whole scene seen from above, particles
// drawn as shaded discs coloured by role (material blue, boundary sand, tool orange).
#pragma once

#include <filesystem>

#include "dentsph/state.hpp"

namespace dentsph::io {

// `up` is the scene's vertical (against gravity); the side panel cuts a slab two kernel radii
// thick through the material's centre. Throws std::runtime_error naming the file if it cannot
// be written.
void write_preview_png(const std::filesystem::path& file, const State& state, const Vec3& up, real slab_half_width,
                       int panel_size = 480);

}  // namespace dentsph::io
