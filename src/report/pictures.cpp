// The section and the view from above (pictures.hpp).
#include "report/pictures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dentsph/io/role_colours.hpp"
#include "dentsph/mesh_normals.hpp"
#include "report/tooth_surface.hpp"

namespace dentsph::report {

namespace {

constexpr double mm = 1e-3;

Rgb rgb(std::array<float, 3> c) {
  return {std::uint8_t(c[0] * 255 + 0.5f), std::uint8_t(c[1] * 255 + 0.5f), std::uint8_t(c[2] * 255 + 0.5f)};
}

struct Box {
  Vec3 lo{std::numeric_limits<real>::max(), std::numeric_limits<real>::max(), std::numeric_limits<real>::max()};
  Vec3 hi{-std::numeric_limits<real>::max(), -std::numeric_limits<real>::max(), -std::numeric_limits<real>::max()};
  void add(const Vec3& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
};

// [a, b] around the cavity's [c0, c1] with `margin`, within the tooth's [t0, t1] (padded).
std::pair<double, double> window(double c0, double c1, double t0, double t1, double margin, double pad) {
  return {std::max(c0 - margin, t0 - pad), std::min(c1 + margin, t1 + pad)};
}

Camera make_camera(const Vec3& centre, const Vec3& right, const Vec3& up, double w_m, double h_m, int width) {
  Camera c;
  c.centre = centre;
  c.right = right;
  c.up = up;
  c.px_per_m = width / w_m;
  c.width = width;
  c.height = std::max(1, int(std::lround(h_m * c.px_per_m)));
  return c;
}

void draw_particles(Canvas& canvas, std::span<const Vec3> pos, const ParticleColour& colour, double radius,
                    const std::function<bool(const Vec3&)>& clip) {
  for (std::size_t i = 0; i < pos.size(); ++i) {
    if (!is_finite(pos[i]) || (clip && !clip(pos[i]))) continue;
    if (const std::optional<Rgb> c = colour(i)) canvas.sphere(pos[i], radius, *c);
  }
}

void draw_markers(Canvas& canvas, const PictureOptions& o) {
  for (std::size_t k = 0; k < o.markers.size(); ++k) {
    const double r = k < o.marker_radii.size() ? o.marker_radii[k] * canvas.camera().px_per_m : 0;
    canvas.ring(o.markers[k], std::max(7.0, r + 4), 2.5, kMarker);
  }
}

// A 1 mm bar with end ticks in the lower left corner.
void scale_bar(Canvas& canvas) {
  const int len = int(std::lround(mm * canvas.camera().px_per_m));
  const int x0 = 12, y = canvas.height() - 14;
  const Rgb ink = {40, 40, 40};
  canvas.rect(x0, y, x0 + len, y + 2, ink);
  canvas.rect(x0, y - 5, x0 + 1, y + 2, ink);
  canvas.rect(x0 + len - 1, y - 5, x0 + len, y + 2, ink);
}

// Where the plane (depth 0 of the camera) lies inside the closed mesh, filled in `colour` where
// `keep` holds for the world point: by the even-odd rule over the mesh's section, row by row.
template <class Mesh, class Keep>
void fill_section(Canvas& canvas, const Mesh& mesh, Rgb colour, Keep&& keep) {
  const Camera& cam = canvas.camera();
  struct Seg {
    double x0, y0, x1, y1;  // pixels
  };
  std::vector<Seg> segs;
  for (const auto& t : mesh.triangles) {
    Vec3 q[3];
    for (int v = 0; v < 3; ++v) q[v] = cam.project(mesh.vertices[t[v]]);
    Vec3 hit[2];
    int n = 0;
    for (int e = 0; e < 3 && n < 2; ++e) {
      const Vec3 &a = q[e], &b = q[(e + 1) % 3];
      if ((a.z < 0) != (b.z < 0)) hit[n++] = a + (b - a) * (a.z / (a.z - b.z));
    }
    if (n == 2) segs.push_back({hit[0].x, hit[0].y, hit[1].x, hit[1].y});
  }
  std::vector<double> xs;
  for (int y = 0; y < canvas.height(); ++y) {
    const double py = y + 0.5;
    xs.clear();
    for (const Seg& s : segs)
      if ((s.y0 <= py) != (s.y1 <= py)) xs.push_back(s.x0 + (py - s.y0) / (s.y1 - s.y0) * (s.x1 - s.x0));
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2)
      for (int x = std::max(0, int(std::ceil(xs[k] - 0.5))); x <= std::min(canvas.width() - 1, int(std::floor(xs[k + 1] - 0.5))); ++x)
        if (keep(cam.unproject(x + 0.5, py, 0))) canvas.fragment(x, y, 0, colour);
  }
}

// The section's cut face: where the plane lies inside the prepared tooth (outside the cavity), in
// dentine colour.
void cut_face(Canvas& canvas, const PreparedTooth& tooth) {
  fill_section(canvas, tooth.tooth().mesh(), kDentine,
               [&](const Vec3& p) { return tooth.cavity_distance(p).distance > 0; });
}

// The paste's surface in its colour, lit by each corner's normal (the mean of its triangles'
// normals, weighted by their area); `keep` may discard fragments by their world point.
void draw_surface(Canvas& canvas, const SurfaceMesh& mesh, Rgb colour, const std::function<bool(const Vec3&)>& keep) {
  const std::vector<Vec3> normal = vertex_normals(mesh.vertices, mesh.triangles);
  Canvas::Keep k;
  if (keep) k = [&](const Vec3& p, const std::array<double, 3>&) { return keep(p); };
  for (const auto& t : mesh.triangles)
    canvas.triangle({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]},
                    {normal[t[0]], normal[t[1]], normal[t[2]]}, colour, k);
}

}  // namespace

ParticleColour colour_by_role(std::span<const Role> roles, bool paste) {
  return [roles, paste](std::size_t i) -> std::optional<Rgb> {
    if (i >= roles.size() || roles[i] == Role::boundary || (!paste && roles[i] == Role::material)) return std::nullopt;
    return rgb(io::role_colour(roles[i]));
  };
}

ToothPictures draw_tooth_pictures(const PreparedTooth& tooth, std::span<const Vec3> positions,
                                  const ParticleColour& colour, const PictureOptions& o) {
  const ToothFrame& fr = tooth.frame();
  Box cav, all;
  const Bounds cb = tooth.cavity_bounds();
  for (int c = 0; c < 8; ++c)
    cav.add(fr.to_local({c & 1 ? cb.max.x : cb.min.x, c & 2 ? cb.max.y : cb.min.y, c & 4 ? cb.max.z : cb.min.z}));
  for (const Vec3& v : tooth.tooth().mesh().vertices) all.add(fr.to_local(v));
  const Vec3 mid = 0.5 * (cav.lo + cav.hi);
  const double radius = 0.5 * o.spacing;
  const ToothSurface surface = tooth_surface(tooth);

  // The section: the plane through the cavity's middle across the bucco-lingual axis, seen along
  // +y (right = mesio-distal x, up = the long axis z); everything nearer than the plane removed.
  const auto [x0, x1] = window(cav.lo.x, cav.hi.x, all.lo.x, all.hi.x, 3 * mm, 0.4 * mm);
  const double z0 = std::max(cav.lo.z - 2.5 * mm, all.lo.z - 0.4 * mm), z1 = all.hi.z + 1.5 * mm;
  const Vec3 cut_centre = fr.to_world({0.5 * (x0 + x1), mid.y, 0.5 * (z0 + z1)});
  Canvas cut(make_camera(cut_centre, fr.x, fr.z, x1 - x0, z1 - z0, o.width), kBackground);
  const double slab = -0.5 * o.spacing;  // particles up to half a spacing before the plane
  const auto behind = [&](const Vec3& p) { return dot(p - cut_centre, fr.y) >= 0; };
  draw_tooth(cut, surface, kEnamel, behind);
  cut_face(cut, tooth);
  const Rgb paste = rgb(io::role_colour(Role::material));
  if (o.paste_surface) {
    draw_surface(cut, *o.paste_surface, paste, behind);
    fill_section(cut, *o.paste_surface, kPasteSection, [](const Vec3&) { return true; });
  }
  draw_particles(cut, positions, colour, radius, [&](const Vec3& p) { return dot(p - cut_centre, fr.y) >= slab; });
  draw_markers(cut, o);
  scale_bar(cut);

  // From above: right = x, up = y, depth along -z.
  const auto [tx0, tx1] = window(cav.lo.x, cav.hi.x, all.lo.x, all.hi.x, 3.5 * mm, 0.4 * mm);
  const auto [ty0, ty1] = window(cav.lo.y, cav.hi.y, all.lo.y, all.hi.y, 3.5 * mm, 0.4 * mm);
  const Vec3 top_centre = fr.to_world({0.5 * (tx0 + tx1), 0.5 * (ty0 + ty1), all.hi.z + 2 * mm});
  Canvas top(make_camera(top_centre, fr.x, fr.y, tx1 - tx0, ty1 - ty0, o.width), kBackground);
  draw_tooth(top, surface, kEnamel);
  if (o.paste_surface) draw_surface(top, *o.paste_surface, paste, {});
  draw_particles(top, positions, colour, radius, {});
  draw_markers(top, o);
  scale_bar(top);
  const double px_per_mm = cut.camera().px_per_m * mm;
  return {std::move(cut), std::move(top), px_per_mm};
}

void write_tooth_pictures(const std::filesystem::path& dir, const PreparedTooth& tooth,
                          std::span<const Vec3> positions, const ParticleColour& colour,
                          const PictureOptions& options, bool particles) {
  const ToothPictures p = draw_tooth_pictures(tooth, positions, colour, options);
  write_png(dir / (particles ? kCutParticlesPicture : kCutPicture), p.cut);
  write_png(dir / (particles ? kTopParticlesPicture : kTopPicture), p.top);
}

}  // namespace dentsph::report
