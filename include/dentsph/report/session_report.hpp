// report.html of one session: what a tutor reads in a minute. The pictures of the filling, the
// force on the instrument over time with the procedure's events marked and the device's limit,
// each criterion with its number, verdict and rule (criteria.hpp), the haptic loop's health for
// a realtime session, and the run's particulars. One self-contained file (docs/report.md).
#pragma once

#include <filesystem>
#include <string>

#include "dentsph/report/session_folder.hpp"

namespace dentsph::report {

// The page of a session folder's files.
std::string session_report_html(const SessionFolder& session);

// Reads `dir` (read_session) and writes dir/report.html; returns its path. Throws SessionError
// for a folder that cannot be read, std::runtime_error when the file cannot be written.
std::filesystem::path write_session_report(const std::filesystem::path& dir);

}  // namespace dentsph::report
