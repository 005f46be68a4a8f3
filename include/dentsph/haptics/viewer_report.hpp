// The report of a viewer session (dentsph-viewer --summary FILE): its last snapshot's particles,
// its assessment and, under a device, the haptic runtime's sections and recording, written as a
// run folder (FILE's name without its extension, plus "_report") with report.html in it.
#pragma once

#include <filesystem>
#include <span>

#include <nlohmann/json.hpp>

#include "dentsph/haptics.hpp"
#include "dentsph/scene.hpp"

namespace dentsph {

// The folder a viewer summary's report goes in: "shot.json" -> "shot_report".
std::filesystem::path viewer_report_dir(const std::filesystem::path& summary_file);

// Writes the folder (summary.json in a run's format, the pictures, the recording and
// procedure.json under a device, report.html); returns report.html's path. `viewer_summary` is
// what the viewer wrote to its --summary file; `realtime` the runtime's result under a device.
std::filesystem::path write_viewer_report(const std::filesystem::path& summary_file, const Scene& scene,
                                          std::span<const Vec3> positions, std::span<const Role> roles,
                                          const nlohmann::json& viewer_summary, const RealtimeResult* realtime);

}  // namespace dentsph
