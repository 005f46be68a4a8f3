// Screenshots (screenshot.hpp).
#include "screenshot.hpp"

#include <stdexcept>
#include <vector>

#include <epoxy/gl.h>
#include <fmt/format.h>
#include <stb/stb_image_write.h>

namespace dentsph::viewer {

void write_screenshot(const std::filesystem::path& file, int width, int height) {
  std::vector<unsigned char> pixels(std::size_t(width) * std::size_t(height) * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  stbi_flip_vertically_on_write(1);  // OpenGL's rows run bottom up
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  if (!stbi_write_png(file.c_str(), width, height, 3, pixels.data(), width * 3))
    throw std::runtime_error(fmt::format("{}: cannot write the screenshot; check that the folder is writable",
                                         file.string()));
}

}  // namespace dentsph::viewer
