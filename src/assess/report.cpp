// Assessment::report() and assessment_json(): the metrics as text for people and as JSON for
// the run summary.
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "dentsph/assess.hpp"

namespace dentsph {

namespace {

// JSON has no NaN or infinity: such a value is written as null.
nlohmann::json number(real v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace

std::string Assessment::report() const {
  std::string out = fmt::format(
      "filling: {:.1f}% of the {:.2f} mm^3 cavity filled, {} void{} ({:.3f} mm^3{}){}, "
      "overfill {:.2f} mm^3\n",
      100 * fill_fraction, cavity_volume_mm3, void_count, void_count == 1 ? "" : "s",
      void_volume_mm3,
      void_count > 1 ? fmt::format(", largest {:.3f} mm^3", largest_void_mm3) : std::string(),
      pore_count > 0 ? fmt::format(" and {} pore{} under {:.3f} mm^3 ({:.3f} mm^3, below the model's resolution)",
                                   pore_count, pore_count == 1 ? "" : "s", min_void_mm3, pore_volume_mm3)
                     : std::string(),
      overfill_mm3);
  out += fmt::format(
      "material: {} particles, {} leaked (in the tooth or off the domain), {} lost, {} outside "
      "the assessed box\n",
      material_particles, leaked_particles, lost_particles, outside_particles);
  out += fmt::format(
      "tool: peak {:.3g} N, mean {:.3g} N simulated (on a device at force scale {:.3g}: peak {:.3g} N, mean "
      "{:.3g} N) over {:.3g} s of contact; {:.3g} s simulated (voxels of {:.3g} mm)\n",
      peak_tool_force_N, mean_tool_force_N, force_scale, peak_device_force_N, mean_device_force_N, contact_s,
      duration_s, voxel_mm);
  return out;
}

std::string assessment_json(const Assessment& a) {
  nlohmann::json j;
  j["fill_fraction"] = number(a.fill_fraction);
  j["void_count"] = a.void_count;
  j["void_volume_mm3"] = number(a.void_volume_mm3);
  j["largest_void_mm3"] = number(a.largest_void_mm3);
  j["voids"] = nlohmann::json::array();
  for (const VoidPlace& v : a.voids)
    j["voids"].push_back({{"centre_mm", {number(v.centre_mm.x), number(v.centre_mm.y), number(v.centre_mm.z)}},
                          {"volume_mm3", number(v.volume_mm3)},
                          {"wall_distance_mm", number(v.wall_distance_mm)},
                          {"against", v.against}});
  j["pore_count"] = a.pore_count;
  j["pore_volume_mm3"] = number(a.pore_volume_mm3);
  j["min_void_mm3"] = number(a.min_void_mm3);
  j["overfill_mm3"] = number(a.overfill_mm3);
  j["leaked_particles"] = a.leaked_particles;
  j["lost_particles"] = a.lost_particles;
  j["outside_particles"] = a.outside_particles;
  j["material_particles"] = a.material_particles;
  j["peak_tool_force_N"] = number(a.peak_tool_force_N);
  j["mean_tool_force_N"] = number(a.mean_tool_force_N);
  j["force_scale"] = number(a.force_scale);
  j["peak_device_force_N"] = number(a.peak_device_force_N);
  j["mean_device_force_N"] = number(a.mean_device_force_N);
  j["contact_s"] = number(a.contact_s);
  j["duration_s"] = number(a.duration_s);
  j["cavity_volume_mm3"] = number(a.cavity_volume_mm3);
  j["filled_volume_mm3"] = number(a.filled_volume_mm3);
  j["voxel_mm"] = number(a.voxel_mm);
  return j.dump(2);
}

}  // namespace dentsph
