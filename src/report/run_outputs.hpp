// What a run leaves for a tutor beside the engineer's files, written at its end: the session's
// particulars added to summary.json ("session": student, exercise, finished_at), the pictures of
// a dental scene (tooth_cut.png, tooth_top.png, with the summary's voids ringed),
// procedure.json and report.html (docs/report.md). The offline run, the realtime runtime,
// `dentsph replay --out` and the viewer's --summary call it.
#pragma once

#include <filesystem>
#include <span>
#include <string>

#include "dentsph/scene.hpp"
#include "report/pictures.hpp"
#include "report/procedure_log.hpp"

namespace dentsph::report {

// `dir` holds the run's summary.json (and its force files) already. Returns the surface's grading
// for a person (surface_grade_report; empty without a tooth). Throws std::runtime_error naming a
// file that cannot be written.
std::string finish_run(const std::filesystem::path& dir, const Scene& scene, const State& state, const ProcedureLog& log);

// The same from particle positions and roles alone (the viewer's last snapshot), with no
// increments measured.
std::string finish_run(const std::filesystem::path& dir, const Scene& scene, std::span<const Vec3> positions,
                std::span<const Role> roles, const ProcedureLog& log);

// Adds "session" {student, exercise (when the scene names them), finished_at (now, UTC)} to
// dir/summary.json.
void stamp_summary(const std::filesystem::path& dir, const Scene& scene);

}  // namespace dentsph::report
