// Assessment of a filling: how much of a prepared cavity the material fills, the empty regions
// it encloses, the excess above the margin, the material that leaked or was lost, and the tool
// force. Computed on a voxelisation of the cavity and a band above it, built once from the
// PreparedTooth; assess() is fast enough for a viewer to call live. docs/assessment.md gives
// the definitions and why they were chosen. Lengths in metres unless a name says otherwise.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dentsph/force_stats.hpp"
#include "dentsph/tooth.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph {

class State;
struct Model;

struct AssessParams {
  real spacing = default_tooth_spacing;  // m, material particle spacing: a particle is spacing^3
  real voxel = 0;                        // m, voxel edge; 0: spacing / 2 (at least spacing / 8)
  real band_side = 2e-3;                 // m, overfill band beyond the cavity's bounds, each side
  real band_up = 2e-3;                   // m, overfill band above the cavity's bounds
  real fill_level = 0.5;      // a voxel is filled where the material's colour field is >= this
  real wall_standoff = 0;     // m, 0: spacing. Voxels nearer the prepared surface than this
                              // are judged this far from it (the SPH gap at a wall)
  real leak_depth = 0;        // m, 0: spacing / 2. Material deeper in the tooth has leaked
  real lost_distance = 5e-3;  // m, material farther than this from the cavity's bounds is lost
  // mm^3, enclosed regions smaller than this are porosity, not voids; 0: one particle's volume
  // (spacing^3), what the model resolves
  real min_void_mm3 = 0;
};

// Where an enclosed void lies, for a tutor: in the tooth frame, in mm.
struct VoidPlace {
  Vec3 centre_mm;              // mean of its cavity voxels: x mesio-distal, y bucco-lingual, z
                               // along the long axis (0 at the occlusal reference, < 0 below)
  real volume_mm3 = 0;         // its cavity voxels
  real wall_distance_mm = 0;   // from its centre to the nearest wall or floor of the cavity
  // "floor" or "wall" when it touches the preparation (its centre within its equivalent radius
  // plus a spacing of it; floor where that surface faces up the long axis within 45 degrees),
  // otherwise "bulk" (inside the filling).
  std::string against;
};

// The metrics of one state. Volumes in mm^3 (the unit a dentist reads), forces in N.
struct Assessment {
  real fill_fraction = 0;     // filled cavity voxels / cavity voxels, in [0, 1]
  int void_count = 0;         // enclosed empty regions reaching into the cavity, of at least
                              // min_void_mm3
  real void_volume_mm3 = 0;   // their volume inside the cavity
  real largest_void_mm3 = 0;  // the largest of them
  std::vector<VoidPlace> voids;  // each of them, in the order found
  // Enclosed empty regions reaching into the cavity but smaller than min_void_mm3 (one
  // particle's volume by default): porosity below what the model resolves, not a defect.
  int pore_count = 0;
  real pore_volume_mm3 = 0;   // their volume inside the cavity
  real min_void_mm3 = 0;      // the smallest void counted (AssessParams::min_void_mm3, resolved)
  real overfill_mm3 = 0;      // filled voxels outside the cavity and the tooth, in the band
  std::uint32_t leaked_particles = 0;    // deeper than leak_depth in the tooth, or off the domain
  std::uint32_t lost_particles = 0;      // non-finite, or farther than lost_distance
  std::uint32_t outside_particles = 0;   // none of these and outside the voxelised box
  std::uint32_t material_particles = 0;  // all material particles
  // Forces: *_tool_force_N are simulated newtons (the force on the tool in the simulation, from
  // the ForceStats passed in); *_device_force_N are the same rendered on a haptic device, times
  // force_scale (Scene::force_scale, device N per simulated N). docs/outputs.md, "Units".
  real peak_tool_force_N = 0;            // simulated N, from the ForceStats passed in
  real mean_tool_force_N = 0;            // simulated N, mean while in contact, from the ForceStats
  real force_scale = 1;                  // device N per simulated N
  real peak_device_force_N = 0;          // device N: peak_tool_force_N * force_scale
  real mean_device_force_N = 0;          // device N: mean_tool_force_N * force_scale
  real contact_s = 0;                    // s, tool in contact, from the ForceStats
  real duration_s = 0;                   // s, simulated time of the state
  real cavity_volume_mm3 = 0;            // the voxelised cavity
  real filled_volume_mm3 = 0;            // its filled part
  real voxel_mm = 0;                     // mm, voxel edge

  // A short human-readable report, three lines ending in newlines.
  std::string report() const;
};

// The assessment as a JSON object (the run summary's "assessment"); every field above.
std::string assessment_json(const Assessment& a);

// The voxelisation of one prepared tooth's cavity and the band above it, in the tooth frame,
// built once (its cost: docs/assessment.md, "The voxels"); assess() is then cheap beside it. Immutable: copies share the voxels, assess() may run on any number of
// threads. Throws std::invalid_argument for parameters out of range (the message names the field).
class CavityAssessor {
 public:
  explicit CavityAssessor(const PreparedTooth& tooth, const AssessParams& params = {});

  // The metrics of the material particles of `state`; duration_s is state.time, the force
  // fields come from `forces` (simulated N), rendered on a device at `force_scale`.
  Assessment assess(const State& state, const Model& model, const ForceStats& forces = {},
                    real force_scale = 1) const;

  const AssessParams& params() const;  // with the defaults resolved
  const PreparedTooth& tooth() const;
  real voxel() const;               // m
  std::array<int, 3> dims() const;  // voxels along the frame's x, y, z
  std::uint32_t cavity_voxels() const;
  real cavity_volume() const;  // m^3, cavity voxels times voxel^3

  struct Impl;

 private:
  std::shared_ptr<const Impl> impl_;
};

}  // namespace dentsph
