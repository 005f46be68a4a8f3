// Several sessions side by side (a class on one exercise, or one student over time): a table of
// every session's criteria with their verdicts, a bar chart of each score against its threshold,
// as one self-contained HTML page, and the same table as CSV for a spreadsheet.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dentsph::report {

// One session as the comparison reads it: from a run folder or from the session store.
struct SessionEntry {
  std::string label;          // how the table names it: the student, else the folder's name
  std::string student, exercise, finished_at;
  std::string folder;         // the run folder ("" when unknown)
  std::string report;         // its report.html ("" when none)
  nlohmann::json summary;     // summary.json
  nlohmann::json procedure;   // procedure.json, or null
};

// From a run folder's summary.json and procedure.json. Throws SessionError naming the folder.
SessionEntry session_entry(const std::filesystem::path& dir);

// The criteria compared (criteria.hpp ids), in the table's order.
const std::vector<std::string>& compared_criteria();

// The page; sessions in the order given (sorted by the caller).
std::string class_report_html(const std::vector<SessionEntry>& sessions, const std::string& title);
// The CSV: a header row, then one row per session: label, student, exercise, finished_at,
// folder, then each compared criterion's number (empty when not measured) and verdict.
std::string class_report_csv(const std::vector<SessionEntry>& sessions);

}  // namespace dentsph::report
