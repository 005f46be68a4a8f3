#include "dentsph/io/role_colours.hpp"
#include "io/preview.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>
#include <stb/stb_image_write.h>

namespace dentsph::io {

namespace {

using Rgb = std::array<std::uint8_t, 3>;

Rgb colour_of(Role r) {
  const std::array<float, 3> c = role_colour(r);
  return {std::uint8_t(c[0] * 255 + 0.5f), std::uint8_t(c[1] * 255 + 0.5f), std::uint8_t(c[2] * 255 + 0.5f)};
}

struct Panel {
  std::vector<Rgb> pixels;
  int size;
  explicit Panel(int n) : pixels(std::size_t(n) * n, Rgb{250, 250, 250}), size(n) {}

  // A disc at (px, py) of radius r pixels, brighter towards its upper left (a lit sphere).
  void disc(real px, real py, real r, Rgb c) {
    const int x0 = std::max(0, int(px - r)), x1 = std::min(size - 1, int(px + r));
    const int y0 = std::max(0, int(py - r)), y1 = std::min(size - 1, int(py + r));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const real dx = (x - px) / r, dy = (y - py) / r, d2 = dx * dx + dy * dy;
        if (d2 > 1) continue;
        const real light = 0.55 + 0.45 * std::max<real>(0, (-dx - dy) * 0.5 + std::sqrt(1 - d2) * 0.7);
        pixels[std::size_t(y) * size + x] = {std::uint8_t(std::min<real>(255, c[0] * light)),
                                             std::uint8_t(std::min<real>(255, c[1] * light)),
                                             std::uint8_t(std::min<real>(255, c[2] * light))};
      }
  }
};

}  // namespace

void write_preview_png(const std::filesystem::path& file, const State& s, const Vec3& up_in, real slab_half_width,
                       int n) {
  // An orthonormal frame: v up, u right, w towards the viewer of the side panel.
  Vec3 v = norm(up_in) > 0 ? up_in / norm(up_in) : Vec3{0, 0, 1};
  Vec3 u = cross(std::abs(v.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}, v);
  u = u / norm(u);
  const Vec3 w = cross(u, v);

  // Centre on the material (or everything), scale to the extent of 99% of the finite particles
  // (a few particles flung far away would otherwise shrink the picture to a dot).
  Vec3 centre;
  int counted = 0;
  for (std::uint32_t i = 0; i < s.size(); ++i)
    if (s.is_paste(i) && is_finite(s.pos[i])) centre += s.pos[i], ++counted;
  if (counted == 0)
    for (std::uint32_t i = 0; i < s.size(); ++i)
      if (is_finite(s.pos[i])) centre += s.pos[i], ++counted;
  if (counted > 0) centre = centre / counted;
  std::vector<real> extents;
  for (std::uint32_t i = 0; i < s.size(); ++i)
    if (is_finite(s.pos[i])) {
      const Vec3 d = s.pos[i] - centre;
      extents.push_back(std::max({std::abs(dot(d, u)), std::abs(dot(d, v)), std::abs(dot(d, w))}));
    }
  real extent = 0;
  if (!extents.empty()) {
    const auto k = extents.begin() + std::ptrdiff_t(std::min(extents.size() - 1, extents.size() * 99 / 100));
    std::nth_element(extents.begin(), k, extents.end());
    extent = *k;
  }
  extent = extent > 0 ? extent * 1.05 : 1;
  const real scale = 0.5 * n / extent;  // pixels per metre
  const real radius = std::max<real>(1.5, 0.5 * slab_half_width * scale);

  // Draw far to near (painter's order).
  auto draw = [&](Panel& p, const Vec3& right, const Vec3& upward, const Vec3& depth, bool slab) {
    std::vector<std::uint32_t> order;
    for (std::uint32_t i = 0; i < s.size(); ++i)
      if (is_finite(s.pos[i]) && (!slab || std::abs(dot(s.pos[i] - centre, depth)) <= slab_half_width))
        order.push_back(i);
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t a, std::uint32_t b) { return dot(s.pos[a], depth) < dot(s.pos[b], depth); });
    for (std::uint32_t i : order) {
      const Vec3 d = s.pos[i] - centre;
      p.disc(0.5 * n + dot(d, right) * scale, 0.5 * n - dot(d, upward) * scale, radius,
             colour_of(s.is_paste(i) ? Role::material : s.role[i]));  // set paste is still paste
    }
  };
  Panel side(n), top(n);
  draw(side, u, v, w, true);
  draw(top, u, -w, v, false);

  // Side by side with a 4-pixel gutter.
  const int width = 2 * n + 4;
  std::vector<std::uint8_t> image(std::size_t(width) * n * 3, 255);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (int c = 0; c < 3; ++c) {
        image[(std::size_t(y) * width + x) * 3 + c] = side.pixels[std::size_t(y) * n + x][c];
        image[(std::size_t(y) * width + x + n + 4) * 3 + c] = top.pixels[std::size_t(y) * n + x][c];
      }
  if (!stbi_write_png(file.c_str(), width, n, 3, image.data(), width * 3))
    throw std::runtime_error(fmt::format("{}: cannot write the preview image", file.string()));
}

}  // namespace dentsph::io
