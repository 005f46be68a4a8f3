// WallField: the signed distance to a scene's fixed walls (the prepared tooth) sampled on a grid,
// for the iisph solver's position-level wall projection (docs/model.md, "Walls at large steps").
// The walls' particles hold paste out through its pressure; at a step of 1.5 to 2 ms a particle
// pressed hard against the wall can pass between them in one step. After each step, a material
// particle closer to the wall than `clearance` (or inside it) is moved out along the distance's
// gradient to `clearance`, and its velocity into the wall removed.
//
// The distance is sampled at the corners of cubic cells and interpolated trilinearly; outside the
// grid's box there is no wall. Corners farther from the walls than a block of 4 cells' diagonal plus
// the clearance are interpolated from a grid 4 times coarser (nothing is projected there), so that
// the cost goes with the walls' area rather than the box's volume. Immutable; queries are safe from any number of threads.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "dentsph/vec3.hpp"

namespace dentsph {

// The trilinear interpolation of distances sampled on the corners of cubic cells (`n` corners along
// each axis, x fastest, the first at `origin`, 1 / cell = `inv_cell`) at p, and its gradient
// (unnormalised); false outside the grid (or p not a number). WallField's and ContactField's.
bool sample_grid(std::span<const float> phi, const int n[3], const Vec3& origin, real inv_cell, const Vec3& p,
                 real& distance, Vec3& gradient);

class WallField {
 public:
  // Samples `distance` (m, negative inside the walls) on the corners of cells of edge `cell` (m)
  // covering [lo, hi]; particles keep `clearance` (m) from the walls. Throws
  // std::invalid_argument for an empty box, a cell that is not positive or a grid of more than
  // `max_nodes` corners.
  WallField(const std::function<real(const Vec3&)>& distance, Vec3 lo, Vec3 hi, real cell, real clearance,
            std::int64_t max_nodes = 64'000'000);

  // The interpolated signed distance at p and its gradient (unnormalised); false outside the grid.
  bool sample(const Vec3& p, real& distance, Vec3& gradient) const;
  real clearance() const { return clearance_; }
  // The grid's box: outside it, sample() knows nothing.
  Vec3 lo() const { return origin_; }
  Vec3 hi() const { return origin_ + Vec3{real(n_[0] - 1), real(n_[1] - 1), real(n_[2] - 1)} * cell_; }
  std::int64_t nodes() const { return std::int64_t(phi_.size()); }

  // Moves `pos` out to the clearance and removes the velocity into the wall when `pos` is closer to
  // the wall than the clearance; returns whether it moved.
  bool project(Vec3& pos, Vec3& vel) const;

 private:
  static constexpr int kBlock = 4;  // cells along a block of the coarse-to-fine sampling
  Vec3 origin_;
  real cell_, inv_cell_, clearance_;
  int n_[3];
  std::vector<float> phi_;  // m, x fastest
};

}  // namespace dentsph
