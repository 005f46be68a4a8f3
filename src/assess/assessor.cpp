// CavityAssessor: the voxelisation built once, and assess(): sort the material particles into
// lost, leaked and assessed, spread the assessed ones into the colour field, threshold it
// (reading voxels at a wall the standoff away from it), count filled cavity and air voxels,
// open the space the tool takes, and find the enclosed empty regions.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "assess/colour_field.hpp"
#include "assess/voids.hpp"
#include "assess/voxels.hpp"
#include "dentsph/assess.hpp"
#include "dentsph/model.hpp"
#include "dentsph/state.hpp"

namespace dentsph {

struct CavityAssessor::Impl {
  PreparedTooth tooth;
  AssessParams params;  // defaults resolved
  assess::VoxelGrid grid;
  Bounds keep;  // m, world: material outside this box is lost
};

namespace {

constexpr real mm = 1e-3, mm3 = mm * mm * mm;

void require(bool ok, const char* field, real value, const char* what) {
  if (!ok) throw std::invalid_argument(fmt::format("AssessParams: {} = {} {}", field, value, what));
}

AssessParams resolved(AssessParams p) {
  const real s = p.spacing;
  require(std::isfinite(s) && s > 0, "spacing", s, "m must be > 0 (the material spacing)");
  if (p.voxel == 0) p.voxel = s / 2;
  require(p.voxel >= s / 8 && p.voxel <= 2 * s, "voxel", p.voxel,
          "m must be between spacing / 8 and 2 spacing (0: spacing / 2)");
  require(std::isfinite(p.band_side) && p.band_side >= 0, "band_side", p.band_side,
          "m must be >= 0");
  require(std::isfinite(p.band_up) && p.band_up >= 0, "band_up", p.band_up, "m must be >= 0");
  require(p.fill_level > 0 && p.fill_level < 1, "fill_level", p.fill_level,
          "must be in (0, 1) (0.5: where the particles' volume ends)");
  if (p.wall_standoff == 0) p.wall_standoff = s;
  require(std::isfinite(p.wall_standoff) && p.wall_standoff > 0 && p.wall_standoff <= 4 * s,
          "wall_standoff", p.wall_standoff, "m must be in (0, 4 spacings] (0: one spacing)");
  if (p.leak_depth == 0) p.leak_depth = s / 2;
  require(std::isfinite(p.leak_depth) && p.leak_depth > 0, "leak_depth", p.leak_depth,
          "m must be > 0 (0: half a spacing)");
  require(std::isfinite(p.lost_distance) && p.lost_distance > 0, "lost_distance", p.lost_distance,
          "m must be > 0");
  if (p.min_void_mm3 == 0) p.min_void_mm3 = s * s * s / mm3;
  require(std::isfinite(p.min_void_mm3) && p.min_void_mm3 > 0, "min_void_mm3", p.min_void_mm3,
          "mm^3 must be > 0 (0: one particle's volume, spacing^3)");
  return p;
}

// Empty voxels whose centre lies within one spacing of a tool particle become open space. The
// tool's particles are about a spacing apart on its surface, so these balls cover the surface
// without gaps and the flood fill reaches the tool's inside from them.
void mark_tool(const assess::VoxelGrid& g, real spacing, const std::vector<Vec3>& tool,
               std::vector<std::uint8_t>& mark) {
  const real r2 = spacing * spacing;
  for (const Vec3& q : tool) {
    int a[3], b[3];
    bool outside = false;
    for (int d = 0; d < 3; ++d) {
      const real lo = (q[d] - spacing - g.origin[d]) / g.edge - 0.5,
                 hi = (q[d] + spacing - g.origin[d]) / g.edge - 0.5;
      if (!(hi >= 0 && lo <= g.n[d] - 1)) {
        outside = true;
        break;
      }
      a[d] = std::max(0, int(std::ceil(lo)));
      b[d] = std::min(g.n[d] - 1, int(std::floor(hi)));
    }
    if (outside) continue;
    for (int k = a[2]; k <= b[2]; ++k)
      for (int j = a[1]; j <= b[1]; ++j)
        for (int i = a[0]; i <= b[0]; ++i) {
          const std::size_t v = g.index(i, j, k);
          if (mark[v] == assess::kEmpty && norm2(g.centre(i, j, k) - q) <= r2)
            mark[v] = assess::kOpen;
        }
  }
}

}  // namespace

CavityAssessor::CavityAssessor(const PreparedTooth& tooth, const AssessParams& params) {
  auto impl = std::make_shared<Impl>(Impl{tooth, resolved(params), {}, {}});
  const AssessParams& p = impl->params;
  const ToothFrame& f = tooth.frame();
  // The cavity's bounds in the frame: the world box's corners (tight when the frame is aligned
  // with the world axes, as the built-in crown's is; a little larger otherwise).
  const Bounds cb = tooth.cavity_bounds();
  constexpr real inf = std::numeric_limits<real>::infinity();
  Bounds local{{inf, inf, inf}, {-inf, -inf, -inf}};
  for (int k = 0; k < 8; ++k) {
    const Vec3 c = f.to_local(
        {k & 1 ? cb.max.x : cb.min.x, k & 2 ? cb.max.y : cb.min.y, k & 4 ? cb.max.z : cb.min.z});
    local.min = {std::min(local.min.x, c.x), std::min(local.min.y, c.y),
                 std::min(local.min.z, c.z)};
    local.max = {std::max(local.max.x, c.x), std::max(local.max.y, c.y),
                 std::max(local.max.z, c.z)};
  }
  // Two voxels of tooth below the floor, so no cavity voxel touches the box's faces there; the
  // band above and around the outline holds the overfill.
  const real pad = 2 * p.voxel;
  const Bounds box{local.min - Vec3{p.band_side + pad, p.band_side + pad, pad},
                   local.max + Vec3{p.band_side + pad, p.band_side + pad, p.band_up + pad}};
  impl->grid = assess::voxelise(tooth, box, p.voxel, p.wall_standoff, p.leak_depth);
  const Vec3 lost{p.lost_distance, p.lost_distance, p.lost_distance};
  impl->keep = {cb.min - lost, cb.max + lost};
  impl_ = std::move(impl);
}

const AssessParams& CavityAssessor::params() const { return impl_->params; }
const PreparedTooth& CavityAssessor::tooth() const { return impl_->tooth; }
real CavityAssessor::voxel() const { return impl_->grid.edge; }
std::array<int, 3> CavityAssessor::dims() const {
  return {impl_->grid.n[0], impl_->grid.n[1], impl_->grid.n[2]};
}
std::uint32_t CavityAssessor::cavity_voxels() const { return impl_->grid.cavity_voxels; }
real CavityAssessor::cavity_volume() const {
  const real v = impl_->grid.edge;
  return impl_->grid.cavity_voxels * v * v * v;
}

Assessment CavityAssessor::assess(const State& state, const Model& model, const ForceStats& forces,
                                  real force_scale) const {
  using namespace assess;
  const Impl& m = *impl_;
  const VoxelGrid& g = m.grid;
  const AssessParams& p = m.params;
  const ToothFrame& fr = m.tooth.frame();
  Assessment a;

  // Each material particle is lost, leaked, or assessed (spread into the field); assessed ones
  // outside the box are also counted as outside.
  std::vector<Vec3> assessed, tool;
  assessed.reserve(state.size());
  for (std::uint32_t i = 0; i < state.size(); ++i) {
    if (state.role[i] == Role::tool && is_finite(state.pos[i]))
      tool.push_back(fr.to_local(state.pos[i]));
    if (!state.is_paste(i)) continue;  // moving paste, or paste that has set
    ++a.material_particles;
    const Vec3& w = state.pos[i];
    if (!is_finite(w) || !inside(w, m.keep.min, m.keep.max)) {
      ++a.lost_particles;
      continue;
    }
    if (!inside(w, model.domain_min, model.domain_max)) {
      ++a.leaked_particles;
      continue;
    }
    const Vec3 q = fr.to_local(w);
    const real u[3] = {(q.x - g.origin.x) / g.edge, (q.y - g.origin.y) / g.edge,
                       (q.z - g.origin.z) / g.edge};
    const bool in_box =
        u[0] >= 0 && u[1] >= 0 && u[2] >= 0 && u[0] < g.n[0] && u[1] < g.n[1] && u[2] < g.n[2];
    bool leaked;
    if (in_box) {
      const std::uint8_t c = g.cell[g.index(int(u[0]), int(u[1]), int(u[2]))];
      leaked = (c & kDeep) || ((c & kUnsure) && m.tooth.distance(w).distance < -p.leak_depth);
    } else {
      leaked = m.tooth.distance(w).distance < -p.leak_depth;
      a.outside_particles += !leaked;
    }
    if (leaked)
      ++a.leaked_particles;
    else
      assessed.push_back(q);
  }

  std::vector<float> field(g.size(), 0.0f);
  splat(g, p.spacing, assessed, field);
  // 1 where a cavity or air voxel is empty; voxels at a wall read the field at their probe.
  std::vector<std::uint8_t> mark(g.size());
  const float level = float(p.fill_level);
  for (std::size_t v = 0; v < g.size(); ++v)
    mark[v] = (g.cell[v] & kClassMask) != kTooth && field[v] < level ? kEmpty : kSolid;
  for (const Probe& pr : g.probes)
    mark[pr.voxel] = sample(g, field, pr.at) < p.fill_level ? kEmpty : kSolid;
  std::uint32_t filled_cavity = 0, filled_air = 0;
  for (std::size_t v = 0; v < g.size(); ++v) {
    const std::uint8_t c = g.cell[v] & kClassMask;
    filled_cavity += c == kCavity && mark[v] == kSolid;
    filled_air += c == kAir && mark[v] == kSolid;
  }
  mark_tool(g, p.spacing, tool, mark);

  const real v3 = g.edge * g.edge * g.edge;  // m^3
  const auto min_void = std::uint32_t(std::max(1.0, std::ceil(p.min_void_mm3 * mm3 / v3 - 1e-9)));
  const Voids voids = find_voids(g, mark, min_void);

  a.fill_fraction = g.cavity_voxels ? real(filled_cavity) / g.cavity_voxels : 0;
  a.void_count = voids.count;
  a.void_volume_mm3 = voids.cavity_voxels * v3 / mm3;
  a.largest_void_mm3 = voids.largest * v3 / mm3;
  a.pore_count = voids.pores;
  a.pore_volume_mm3 = voids.pore_cavity_voxels * v3 / mm3;
  a.min_void_mm3 = p.min_void_mm3;
  for (const Voids::Region& r : voids.regions) {
    VoidPlace v;
    const Vec3 local = g.origin + Vec3{(r.i + 0.5) * g.edge, (r.j + 0.5) * g.edge, (r.k + 0.5) * g.edge};
    v.centre_mm = local / mm;
    v.volume_mm3 = r.cavity_voxels * v3 / mm3;
    // In the cavity the prepared tooth's distance is the distance to its walls and floor; its
    // gradient there points away from the nearest of them.
    const SurfacePoint wall = m.tooth.distance(fr.to_world(local));
    v.wall_distance_mm = std::max<real>(0, wall.distance) / mm;
    const real radius_mm = std::cbrt(3 * v.volume_mm3 / (4 * 3.14159265358979323846));
    if (v.wall_distance_mm > radius_mm + p.spacing / mm)
      v.against = "bulk";
    else
      v.against = dot(wall.normal, fr.z) > std::sqrt(0.5) ? "floor" : "wall";
    a.voids.push_back(v);
  }
  a.overfill_mm3 = filled_air * v3 / mm3;
  a.peak_tool_force_N = forces.peak_N;
  a.mean_tool_force_N = forces.mean_N();
  a.force_scale = force_scale;
  a.peak_device_force_N = a.peak_tool_force_N * force_scale;
  a.mean_device_force_N = a.mean_tool_force_N * force_scale;
  a.contact_s = forces.contact_s;
  a.duration_s = state.time;
  a.cavity_volume_mm3 = g.cavity_voxels * v3 / mm3;
  a.filled_volume_mm3 = filled_cavity * v3 / mm3;
  a.voxel_mm = g.edge / mm;
  return a;
}

}  // namespace dentsph
