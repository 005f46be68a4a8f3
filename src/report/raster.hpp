// A small z-buffered software rasteriser for the report's pictures: an orthographic camera,
// shaded triangles (each fragment may be discarded by a test on its world position) and lit
// sphere splats for particles. Headless, no GPU, no window: the same pixels everywhere.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "dentsph/vec3.hpp"

namespace dentsph::report {

using Rgb = std::array<std::uint8_t, 3>;

// An orthographic view: `right` and `up` span the picture (unit, orthogonal), depth grows along
// forward = up x right (away from the viewer). `centre` is the world point at the picture's
// middle; `px_per_m` its scale.
struct Camera {
  Vec3 centre, right, up;
  double px_per_m = 1;
  int width = 1, height = 1;

  Vec3 forward() const { return cross(up, right); }
  // Pixel coordinates (x right, y down) and depth (m along forward from the centre).
  Vec3 project(const Vec3& world) const;
  // The world point under pixel (x, y) at depth d.
  Vec3 unproject(double x, double y, double depth) const;
};

// Colour and depth of every pixel; depth +infinity where nothing was drawn.
class Canvas {
 public:
  Canvas(const Camera& camera, Rgb background);

  const Camera& camera() const { return cam_; }
  int width() const { return cam_.width; }
  int height() const { return cam_.height; }
  Rgb pixel(int x, int y) const { return colour_[index(x, y)]; }
  double depth(int x, int y) const { return depth_[index(x, y)]; }
  const std::vector<Rgb>& pixels() const { return colour_; }

  // A fragment at (x, y) of `depth`: written when nearer than what is there.
  void fragment(int x, int y, double depth, Rgb c);
  // A triangle with a normal per corner (interpolated for the light, turned towards the
  // viewer: two-sided), drawn in `base` colour; `keep(world point, barycentric weights of the
  // corners)` may discard fragments.
  using Keep = std::function<bool(const Vec3&, const std::array<double, 3>&)>;
  void triangle(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& n, Rgb base, const Keep& keep = {});
  // A lit sphere of `radius` m at `centre`, depth-tested per pixel.
  void sphere(const Vec3& centre, double radius, Rgb base);
  // A ring of `radius_px` pixels around the world point, drawn over everything (a marker).
  void ring(const Vec3& world, double radius_px, double thickness_px, Rgb c);
  // A filled rectangle over everything (pixel coordinates).
  void rect(int x0, int y0, int x1, int y1, Rgb c);

  // Lambert light from the viewer's upper left, with ambient: the shade of `base` for `normal`.
  Rgb shade(const Vec3& normal, Rgb base) const;

 private:
  std::size_t index(int x, int y) const { return std::size_t(y) * std::size_t(cam_.width) + std::size_t(x); }
  Camera cam_;
  Vec3 light_;
  std::vector<Rgb> colour_;
  std::vector<double> depth_;
};

// Writes the canvas as an RGB PNG (stb_image_write). Throws std::runtime_error naming the file.
void write_png(const std::filesystem::path& file, const Canvas& canvas);
// The PNG bytes of the canvas, for a file or to inline.
std::vector<std::uint8_t> encode_png(const Canvas& canvas);

}  // namespace dentsph::report
