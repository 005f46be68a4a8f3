// What a run leaves for a tutor beside the engineer's files, written at its end: the session's
// particulars added to summary.json ("session": student, exercise, finished_at), the pictures of
// a dental scene (tooth_cut.png, tooth_top.png, with the summary's voids ringed),
// procedure.json and report.html (docs/report.md). The offline run, the realtime runtime and
// `dentsph replay --out` end in end_run, the viewer's --summary in finish_run.
#pragma once

#include <filesystem>
#include <span>
#include <string>

#include "dentsph/scene.hpp"
#include "dentsph/simulation.hpp"
#include "report/pictures.hpp"
#include "report/procedure_log.hpp"

namespace dentsph::report {

// The end of every run (the offline run, the realtime runtime, `dentsph replay --out`): writes
// `summary` as summary.json and the state as preview.png into `dir` (which holds the run's force
// files already), then what finish_run writes. Returns the surface's grading for a person
// (surface_grade_report; empty without a tooth). Throws std::runtime_error naming a file that
// cannot be written.
std::string end_run(const std::filesystem::path& dir, const Scene& scene, const State& state, const RunSummary& summary,
                    const ProcedureLog& log);

// What a run leaves for a tutor, from particle positions and roles alone (the viewer's last
// snapshot, whose summary the viewer writes), with no increments measured.
std::string finish_run(const std::filesystem::path& dir, const Scene& scene, std::span<const Vec3> positions,
                std::span<const Role> roles, const ProcedureLog& log);

// Adds "session" {student, exercise (when the scene names them), finished_at (now, UTC)} to
// dir/summary.json.
void stamp_summary(const std::filesystem::path& dir, const Scene& scene);

}  // namespace dentsph::report
