// The surface of a prepared tooth as triangles a rasteriser draws: the tooth's mesh where it lies
// outside the cavity, and the cavity's walls and floors (its implicit shape, triangulated by
// marching tetrahedra over its bounds) where they lie inside the tooth. Each triangle keeps what
// the picture needs to cut it exactly at the other surface, fragment by fragment.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "dentsph/tooth.hpp"
#include "report/raster.hpp"

namespace dentsph::report {

struct ToothSurface {
  // The cavity's walls and floors: corners (world, m), unit normals, and the tooth's signed
  // distance at each corner (a wall's fragment is drawn where the interpolated value is < 0).
  struct Wall {
    std::array<Vec3, 3> p, n;
    std::array<double, 3> tooth_distance;
  };
  std::vector<Wall> walls;
  const PreparedTooth* tooth = nullptr;
  std::vector<Vec3> vertex_normals;  // of tooth->tooth().mesh(), area-weighted
};

// Builds the walls with cells of `cell` m (0: a fortieth of the cavity's largest extent, at least
// 0.05 mm). The tooth must outlive the result.
ToothSurface tooth_surface(const PreparedTooth& tooth, double cell = 0);

// Draws the surface in `enamel` colour. `clip(world)` false discards a fragment (a section's
// removed half); empty: nothing is clipped.
void draw_tooth(Canvas& canvas, const ToothSurface& surface, Rgb enamel,
                const std::function<bool(const Vec3&)>& clip = {});

}  // namespace dentsph::report
