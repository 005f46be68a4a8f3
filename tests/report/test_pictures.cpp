// The report's pictures: the tooth's surface drawn (enamel and the section's dentine), the paste
// in its colour, a picture that changes with what is in the cavity, markers where asked.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "dentsph/dental.hpp"
#include "dentsph/scene.hpp"
#include "report/pictures.hpp"

namespace dentsph::report {
namespace {

int count(const Canvas& c, Rgb want, int tol = 0) {
  int n = 0;
  for (const Rgb& p : c.pixels())
    n += std::abs(p[0] - want[0]) <= tol && std::abs(p[1] - want[1]) <= tol && std::abs(p[2] - want[2]) <= tol;
  return n;
}

// Pixels whose hue is the paste's blue (blue well above red), whatever the shading.
int bluish(const Canvas& c) {
  int n = 0;
  for (const Rgb& p : c.pixels()) n += p[2] > p[0] + 60 && p[2] > p[1] + 20;
  return n;
}

// Pixels in the enamel's hue at any light: red >= green >= blue, warm, not grey.
int enamel_like(const Canvas& c) {
  int n = 0;
  for (const Rgb& p : c.pixels()) n += p[0] >= p[1] && p[1] >= p[2] && p[0] - p[2] >= 8 && p != kBackground;
  return n;
}

struct Filled {
  Scene scene = default_dental_scene();
  State state = make_state(scene);
  std::vector<Vec3> pos() const { return {state.pos.begin(), state.pos.end()}; }
};

TEST(ReportPictures, ToothSurfaceAndPasteAreDrawn) {
  Filled f;
  const auto pos = f.pos();
  PictureOptions o;
  o.spacing = f.scene.material_spacing;
  const ToothPictures p = draw_tooth_pictures(*f.scene.tooth, pos, colour_by_role(f.state.role), o);
  const double cut_px = p.cut.width() * p.cut.height(), top_px = p.top.width() * p.top.height();
  // The tooth covers a good part of both pictures; the section shows its cut face.
  EXPECT_GT(enamel_like(p.top), 0.3 * top_px);
  EXPECT_GT(count(p.cut, kDentine), 0.15 * cut_px);
  // The paste fills the cavity: blue in both, the cavity's outline being about 3 x 5 mm.
  const double mm2 = p.px_per_mm * p.px_per_mm;
  EXPECT_GT(bluish(p.top), 0.5 * 3 * 5 * mm2);
  EXPECT_GT(bluish(p.cut), 0.5 * 5 * 2 * mm2);
  // The scale bar: 1 mm of dark ink in the lower left corner.
  const int bar_y = p.top.height() - 13;
  int ink = 0;
  for (int x = 0; x < p.top.width() / 3; ++x) ink += p.top.pixel(x, bar_y) == Rgb{40, 40, 40};
  EXPECT_NEAR(ink, p.top.camera().px_per_m * 1e-3, 2.5);
  if (const char* dir = std::getenv("DENTSPH_PICTURE_DIR")) {  // to look at them
    write_png(std::filesystem::path(dir) / "test_cut.png", p.cut);
    write_png(std::filesystem::path(dir) / "test_top.png", p.top);
  }
}

// The paste as its surface (dentsph/surface.hpp) instead of its particles: from above the surface
// covers the lattice's cells that its spheres (half a spacing across) cover pi / 4 of, so 4 / pi
// times their blue (within 10%; measured 1.275 against 1.273), and the section's cut through the
// paste shows in its dark blue over most of the cavity's section.
TEST(ReportPictures, ThePastesSurfaceStandsForItsParticles) {
  Filled f;
  const auto pos = f.pos();
  PictureOptions o;
  o.spacing = f.scene.material_spacing;
  const ToothPictures spheres = draw_tooth_pictures(*f.scene.tooth, pos, colour_by_role(f.state.role), o);
  std::vector<Vec3> paste;
  for (std::uint32_t i = 0; i < f.state.size(); ++i)
    if (f.state.role[i] == Role::material) paste.push_back(f.state.pos[i]);
  const SurfaceMesh surface = particle_surface(paste, o.spacing);
  o.paste_surface = &surface;
  const ToothPictures p = draw_tooth_pictures(*f.scene.tooth, pos, colour_by_role(f.state.role, /*paste=*/false), o);
  EXPECT_NEAR(double(bluish(p.top)) / bluish(spheres.top), 4 / M_PI, 0.1 * 4 / M_PI);
  const double mm2 = p.px_per_mm * p.px_per_mm;
  EXPECT_GT(count(p.cut, kPasteSection), 0.5 * 5 * 2 * mm2) << "the paste's cut face";
  EXPECT_EQ(count(spheres.cut, kPasteSection), 0);
  if (const char* dir = std::getenv("DENTSPH_PICTURE_DIR")) {  // to look at them
    write_png(std::filesystem::path(dir) / "test_surface_cut.png", p.cut);
    write_png(std::filesystem::path(dir) / "test_surface_top.png", p.top);
  }
}

TEST(ReportPictures, AnEmptyCavityShowsItsWallsNotPaste) {
  Filled f;
  const auto pos = f.pos();
  PictureOptions o;
  o.spacing = f.scene.material_spacing;
  const std::vector<Role> none(f.state.role.size(), Role::boundary);  // nothing drawn
  const ToothPictures empty = draw_tooth_pictures(*f.scene.tooth, pos, colour_by_role(none), o);
  EXPECT_EQ(bluish(empty.top), 0);
  EXPECT_EQ(bluish(empty.cut), 0);
  // The walls and floor are drawn: no background shows through the cavity from above.
  const Camera& cam = empty.top.camera();
  const Vec3 floor_centre = f.scene.tooth->frame().to_world({0, 0, -1e-3});
  const Vec3 px = cam.project(floor_centre);
  EXPECT_NE(empty.top.pixel(int(px.x), int(px.y)), kBackground);
  EXPECT_TRUE(std::isfinite(empty.top.depth(int(px.x), int(px.y))));
  // ... and the floor lies lower than the occlusal surface beside the cavity (depth grows down).
  const Vec3 beside = cam.project(f.scene.tooth->frame().to_world({0, 3.0e-3, 0}));
  EXPECT_GT(empty.top.depth(int(px.x), int(px.y)), empty.top.depth(int(beside.x), int(beside.y)) + 1e-3);
}

TEST(ReportPictures, MarkersAndColoursComeFromTheCaller) {
  Filled f;
  const auto pos = f.pos();
  PictureOptions o;
  o.spacing = f.scene.material_spacing;
  o.markers = {f.scene.tooth->frame().to_world({0, 0, -1e-3})};
  const Rgb green = {20, 200, 40};
  const ToothPictures p = draw_tooth_pictures(
      *f.scene.tooth, pos, [&](std::size_t i) -> std::optional<Rgb> {
        if (f.state.role[i] != Role::material) return std::nullopt;
        return green;
      },
      o);
  EXPECT_GT(count(p.top, kMarker), 50);
  EXPECT_GT(count(p.cut, kMarker), 50);
  int greenish = 0;
  for (const Rgb& c : p.top.pixels()) greenish += c[1] > c[0] + 60 && c[1] > c[2] + 60;
  EXPECT_GT(greenish, 1000);
  EXPECT_EQ(bluish(p.top), 0);
}

}  // namespace
}  // namespace dentsph::report
