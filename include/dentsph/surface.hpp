// The paste as a surface (docs/outputs.md, "The paste's surface"): the particles rasterised by
// OpenVDB into a narrow-band level set, each a sphere of radius_per_spacing times the spacing (0.9:
// the spheres of a lattice cover its cells' centres, 0.87 spacings from their corners, so the
// union has no gaps), smoothed by a mean filter, and meshed (openvdb::tools::volumeToMesh)
// inset_per_spacing inside the union's surface. The inset is fitted: 0.235 spacings puts a lattice
// block's faces half a spacing outside its outer particles and its enclosed volume at the
// particles' n s^3 (measured 0.01% under at a voxel of a third of a spacing;
// tests/unit/test_surface.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "dentsph/state.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph {

struct SurfaceMesh {
  std::vector<Vec3> vertices;                           // m, the particles' frame
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
  real voxel = 0;                                       // m, the level set's voxel
  real volume = 0;                                      // m^3 the triangles enclose
  bool empty() const { return triangles.empty(); }
};

struct SurfaceParams {
  real voxels_per_spacing = 3;     // the voxel is the spacing over this (3: a third of a spacing)
  real radius_per_spacing = 0.9;   // each particle's sphere
  real inset_per_spacing = 0.235;   // the mesh this far inside the spheres' union (fitted above)
  int smoothing = 1;               // mean-filter passes over the level set
};

// The surface of spheres about `centres` (m) of particles `spacing` apart (m). No centres: an empty
// mesh. Throws std::invalid_argument naming the problem for a spacing that is not positive and
// finite, parameters out of their ranges (voxels_per_spacing 1 to 8, radius_per_spacing 0.5 to 2,
// inset_per_spacing 0 to half the radius, smoothing 0 to 10) or a centre that is not finite.
SurfaceMesh particle_surface(std::span<const Vec3> centres, real spacing, const SurfaceParams& params = {});

// The positions whose role is material (the paste; a caller that maps set paste to material has it
// too), finite and within [lo, hi]: the paste a surface is made of.
std::vector<Vec3> paste_within(std::span<const Vec3> positions, std::span<const Role> roles, const Vec3& lo,
                               const Vec3& hi);

// The surface of the paste of `state` (State::is_paste: material and paste that has set) within the
// box [lo, hi] (m; the model's domain: paste flung far from it, or not at a finite position, as a
// diverged run leaves it, has no surface).
SurfaceMesh paste_surface(const State& state, real spacing, const Vec3& lo, const Vec3& hi,
                          const SurfaceParams& params = {});

}  // namespace dentsph
