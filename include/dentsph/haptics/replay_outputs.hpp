// `dentsph replay RECORDING --out DIR`: the replayed session written as a run folder, so that it
// gets the same report as an offline run: summary.json (the simulation's, as an offline run's:
// its solver's statistics, its cure, the assessment), tool_force.csv, and through end_run
// preview.png, the pictures, procedure.json (each increment's particles known here, so their
// thickness is measured) and report.html.
#pragma once

#include <filesystem>
#include <vector>

#include "dentsph/backend.hpp"
#include "dentsph/haptics/recording.hpp"
#include "dentsph/scene.hpp"

namespace dentsph {

// Replays `recording` into `scene` (replay_steps) and writes `dir`; returns the tool forces.
std::vector<Vec3> replay_to_folder(const Scene& scene, const Recording& recording, int threads,
                                   const std::filesystem::path& dir, Backend backend = Backend::cpu);

}  // namespace dentsph
