// Screenshots of the viewer's framebuffer as PNG (stb_image_write).
#pragma once

#include <filesystem>

namespace dentsph::viewer {

// Reads the current framebuffer (width x height, RGB) and writes it, top row first. Throws
// std::runtime_error naming the file when it cannot be written.
void write_screenshot(const std::filesystem::path& file, int width, int height);

}  // namespace dentsph::viewer
