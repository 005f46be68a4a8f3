// The paste's surface by OpenVDB (dentsph/surface.hpp): the level set and its mesh are the
// library's; this file only hands it the particles and reads back the triangles.
#include "dentsph/surface.hpp"

#include <cmath>
#include <mutex>
#include <vector>
#include <stdexcept>

#include <fmt/format.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Filter.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/VolumeToMesh.h>

namespace dentsph {

namespace {

// The particle list ParticlesToLevelSet reads (in voxels' world units: metres).
struct Spheres {
  using PosType = openvdb::Vec3R;
  std::span<const Vec3> centres;
  double radius = 0;
  std::size_t size() const { return centres.size(); }
  void getPos(std::size_t n, openvdb::Vec3R& x) const { x = {centres[n].x, centres[n].y, centres[n].z}; }
  void getPosRad(std::size_t n, openvdb::Vec3R& x, openvdb::Real& r) const {
    getPos(n, x);
    r = radius;
  }
};

constexpr real kRminVoxels = 0.5;

void check(std::span<const Vec3> centres, real spacing, const SurfaceParams& p) {
  auto bad = [](const std::string& what) { throw std::invalid_argument("paste surface: " + what); };
  if (!(std::isfinite(spacing) && spacing > 0)) bad(fmt::format("spacing {} m: give the particles' spacing, > 0", spacing));
  if (!(p.voxels_per_spacing >= 1 && p.voxels_per_spacing <= 8))
    bad(fmt::format("voxels_per_spacing {}: give 1 to 8 (3: a voxel of a third of a spacing)", p.voxels_per_spacing));
  if (!(p.radius_per_spacing >= 0.5 && p.radius_per_spacing <= 2))
    bad(fmt::format("radius_per_spacing {}: give 0.5 to 2 (0.9 by default)", p.radius_per_spacing));
  if (!(p.inset_per_spacing >= 0 && p.inset_per_spacing <= 0.5 * p.radius_per_spacing))
    bad(fmt::format("inset_per_spacing {}: give 0 to half the radius, {} (0.235: fitted to a lattice block's volume)",
                    p.inset_per_spacing, 0.5 * p.radius_per_spacing));
  // The spheres rasterised (radius less inset) below half a voxel, ParticlesToLevelSet's Rmin here,
  // would be left out without a word: an empty surface.
  if (const real voxels = (p.radius_per_spacing - p.inset_per_spacing) * p.voxels_per_spacing; voxels < kRminVoxels)
    bad(fmt::format("radius_per_spacing less inset_per_spacing is {} voxels: give at least {} (more voxels_per_spacing, "
                    "or a smaller inset)",
                    voxels, kRminVoxels));
  if (p.smoothing < 0 || p.smoothing > 10) bad(fmt::format("smoothing {}: give 0 to 10 mean-filter passes", p.smoothing));
  for (std::size_t i = 0; i < centres.size(); ++i)
    if (!is_finite(centres[i])) bad(fmt::format("particle {} is not at a finite position", i));
}

}  // namespace

SurfaceMesh particle_surface(std::span<const Vec3> centres, real spacing, const SurfaceParams& p) {
  check(centres, spacing, p);
  static std::once_flag init;
  std::call_once(init, [] { openvdb::initialize(); });
  SurfaceMesh mesh;
  mesh.voxel = spacing / p.voxels_per_spacing;
  if (centres.empty()) return mesh;
  // In units of the spacing, so that the level set's numbers are the same at any scale.
  std::vector<Vec3> scaled(centres.size());
  for (std::size_t i = 0; i < centres.size(); ++i) scaled[i] = centres[i] / spacing;
  // The surface lies inset_per_spacing inside the union of spheres of radius_per_spacing: it is the
  // union of spheres of the radius less the inset (a union's distance is its nearest centre's less
  // the radius), rasterised as such and meshed at zero. The narrow band: two voxels each side of it,
  // the mean filter's stencil and the mesher's one voxel. (Rasterising the full spheres in a band of
  // three voxels and meshing the inset level visited three times the voxels a sphere.)
  const float half_width = 2;
  openvdb::FloatGrid::Ptr grid = openvdb::createLevelSet<openvdb::FloatGrid>(1 / p.voxels_per_spacing, half_width);
  openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*grid);
  raster.setRmin(kRminVoxels);  // every sphere here is larger (check())
  raster.rasterizeSpheres(Spheres{scaled, p.radius_per_spacing - p.inset_per_spacing});
  raster.finalize(/*prune=*/true);
  if (p.smoothing > 0) {
    // A mean filter of the distances (a 3-voxel box, `smoothing` passes). Its zero level is what is
    // meshed, so the distances need not be made distances again after it (LevelSetFilter::mean does,
    // at twice the cost).
    openvdb::tools::Filter<openvdb::FloatGrid> filter(*grid);
    filter.mean(/*width=*/1, p.smoothing);
  }
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> tris;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*grid, points, tris, quads, /*isovalue=*/0.0, /*adaptivity=*/0.0);
  mesh.vertices.reserve(points.size());
  for (const openvdb::Vec3s& q : points) mesh.vertices.push_back(Vec3{q[0], q[1], q[2]} * spacing);
  // volumeToMesh winds its polygons clockwise seen from outside: reversed here.
  mesh.triangles.reserve(tris.size() + 2 * quads.size());
  for (const openvdb::Vec3I& t : tris) mesh.triangles.push_back({t[0], t[2], t[1]});
  for (const openvdb::Vec4I& q : quads) {
    mesh.triangles.push_back({q[0], q[2], q[1]});
    mesh.triangles.push_back({q[0], q[3], q[2]});
  }
  // The volume the triangles enclose (the divergence theorem), in the spacing's units for precision.
  real volume = 0;
  for (const auto& t : mesh.triangles) {
    const openvdb::Vec3s &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
    volume += (real(a[0]) * (real(b[1]) * c[2] - real(b[2]) * c[1]) + real(a[1]) * (real(b[2]) * c[0] - real(b[0]) * c[2]) +
               real(a[2]) * (real(b[0]) * c[1] - real(b[1]) * c[0])) / 6;
  }
  mesh.volume = volume * spacing * spacing * spacing;
  return mesh;
}

std::vector<Vec3> paste_within(std::span<const Vec3> positions, std::span<const Role> roles, const Vec3& lo,
                               const Vec3& hi) {
  std::vector<Vec3> paste;
  for (std::size_t i = 0; i < positions.size() && i < roles.size(); ++i)
    if (roles[i] == Role::material && is_finite(positions[i]) && inside(positions[i], lo, hi)) paste.push_back(positions[i]);
  return paste;
}

SurfaceMesh paste_surface(const State& state, real spacing, const Vec3& lo, const Vec3& hi, const SurfaceParams& p) {
  std::vector<Vec3> paste;
  for (std::uint32_t i = 0; i < state.size(); ++i) {
    if (state.is_paste(i) && is_finite(state.pos[i]) && inside(state.pos[i], lo, hi)) paste.push_back(state.pos[i]);
  }
  return particle_surface(paste, spacing, p);
}

}  // namespace dentsph
