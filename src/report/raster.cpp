// The software rasteriser (raster.hpp): edge functions over each triangle's pixel box, depth
// interpolated linearly (orthographic), spheres as depth-correct splats.
#include "report/raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <stb/stb_image_write.h>

namespace dentsph::report {

namespace {

Vec3 unit(const Vec3& v) {
  const real n = norm(v);
  return n > 0 ? v / n : Vec3{0, 0, 1};
}

std::uint8_t channel(double v) { return std::uint8_t(std::clamp(v + 0.5, 0.0, 255.0)); }

}  // namespace

Vec3 Camera::project(const Vec3& world) const {
  const Vec3 d = world - centre;
  return {0.5 * width + dot(d, right) * px_per_m, 0.5 * height - dot(d, up) * px_per_m, dot(d, forward())};
}

Vec3 Camera::unproject(double x, double y, double depth) const {
  return centre + right * ((x - 0.5 * width) / px_per_m) + up * ((0.5 * height - y) / px_per_m) + forward() * depth;
}

Canvas::Canvas(const Camera& camera, Rgb background)
    : cam_(camera),
      colour_(std::size_t(camera.width) * std::size_t(camera.height), background),
      depth_(colour_.size(), std::numeric_limits<double>::infinity()) {
  if (camera.width < 1 || camera.height < 1 || !(camera.px_per_m > 0))
    throw std::invalid_argument("Canvas: the camera needs a positive size and scale");
  // From the viewer's upper left, a little towards the viewer.
  light_ = unit(-cam_.right * 0.45 + cam_.up * 0.55 - cam_.forward() * 0.7);
}

void Canvas::fragment(int x, int y, double depth, Rgb c) {
  if (x < 0 || y < 0 || x >= cam_.width || y >= cam_.height) return;
  const std::size_t i = index(x, y);
  if (depth < depth_[i]) {
    depth_[i] = depth;
    colour_[i] = c;
  }
}

Rgb Canvas::shade(const Vec3& normal, Rgb base) const {
  Vec3 n = unit(normal);
  if (dot(n, cam_.forward()) > 0) n = -n;  // two-sided: the side facing the viewer
  const double lambert = std::max<double>(0, dot(n, light_));
  const double k = 0.38 + 0.62 * lambert;
  return {channel(base[0] * k), channel(base[1] * k), channel(base[2] * k)};
}

void Canvas::triangle(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& n, Rgb base, const Keep& keep) {
  const Vec3 a = cam_.project(p[0]), b = cam_.project(p[1]), c = cam_.project(p[2]);
  const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (!(std::abs(area) > 1e-12)) return;
  const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
  const int x1 = std::min(cam_.width - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
  const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
  const int y1 = std::min(cam_.height - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const double w0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
      const double w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
      const double w2 = 1 - w0 - w1;
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      const double depth = w0 * a.z + w1 * b.z + w2 * c.z;
      const std::size_t i = index(x, y);
      if (depth >= depth_[i]) continue;
      if (keep && !keep(p[0] * w0 + p[1] * w1 + p[2] * w2, {w0, w1, w2})) continue;
      depth_[i] = depth;
      colour_[i] = shade(n[0] * w0 + n[1] * w1 + n[2] * w2, base);
    }
}

void Canvas::sphere(const Vec3& centre, double radius, Rgb base) {
  const Vec3 c = cam_.project(centre);
  const double r = radius * cam_.px_per_m;
  if (!std::isfinite(c.x) || !std::isfinite(c.y) || !(r > 0)) return;
  const int x0 = std::max(0, int(std::floor(c.x - r))), x1 = std::min(cam_.width - 1, int(std::ceil(c.x + r)));
  const int y0 = std::max(0, int(std::floor(c.y - r))), y1 = std::min(cam_.height - 1, int(std::ceil(c.y + r)));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double dx = (x + 0.5 - c.x) / r, dy = (y + 0.5 - c.y) / r, d2 = dx * dx + dy * dy;
      if (d2 > 1) continue;
      const double dz = std::sqrt(1 - d2);
      // The sphere's normal at this pixel: right * dx - up * dy - forward * dz.
      const Vec3 normal = cam_.right * dx - cam_.up * dy - cam_.forward() * dz;
      fragment(x, y, c.z - dz * radius, shade(normal, base));
    }
}

void Canvas::ring(const Vec3& world, double radius_px, double thickness_px, Rgb c) {
  const Vec3 p = cam_.project(world);
  const double outer = radius_px + 0.5 * thickness_px, inner = radius_px - 0.5 * thickness_px;
  for (int y = std::max(0, int(p.y - outer - 1)); y <= std::min(cam_.height - 1, int(p.y + outer + 1)); ++y)
    for (int x = std::max(0, int(p.x - outer - 1)); x <= std::min(cam_.width - 1, int(p.x + outer + 1)); ++x) {
      const double d = std::hypot(x + 0.5 - p.x, y + 0.5 - p.y);
      if (d >= inner && d <= outer) colour_[index(x, y)] = c;
    }
}

void Canvas::rect(int x0, int y0, int x1, int y1, Rgb c) {
  for (int y = std::max(0, y0); y <= std::min(cam_.height - 1, y1); ++y)
    for (int x = std::max(0, x0); x <= std::min(cam_.width - 1, x1); ++x) colour_[index(x, y)] = c;
}

std::vector<std::uint8_t> encode_png(const Canvas& canvas) {
  std::vector<std::uint8_t> rgb;
  rgb.reserve(canvas.pixels().size() * 3);
  for (const Rgb& p : canvas.pixels()) rgb.insert(rgb.end(), p.begin(), p.end());
  std::vector<std::uint8_t> png;
  stbi_write_png_to_func(
      [](void* ctx, void* data, int size) {
        auto* out = static_cast<std::vector<std::uint8_t>*>(ctx);
        const auto* bytes = static_cast<const std::uint8_t*>(data);
        out->insert(out->end(), bytes, bytes + size);
      },
      &png, canvas.width(), canvas.height(), 3, rgb.data(), canvas.width() * 3);
  if (png.empty()) throw std::runtime_error("encode_png: stb_image_write could not encode the picture");
  return png;
}

void write_png(const std::filesystem::path& file, const Canvas& canvas) {
  const std::vector<std::uint8_t> png = encode_png(canvas);
  std::FILE* f = std::fopen(file.c_str(), "wb");
  const bool ok = f && std::fwrite(png.data(), 1, png.size(), f) == png.size();
  if (f) std::fclose(f);
  if (!ok) throw std::runtime_error(fmt::format("{}: cannot write the picture", file.string()));
}

}  // namespace dentsph::report
