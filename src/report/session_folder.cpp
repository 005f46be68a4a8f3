// Reading a run folder for the report (session_folder.hpp).
#include "dentsph/report/session_folder.hpp"

#include "dentsph/limits.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>

#include "report/criteria.hpp"
#include "report/grading_picture.hpp"
#include "report/pictures.hpp"
#include "report/session_fields.hpp"

namespace dentsph::report {

namespace {

namespace fs = std::filesystem;

// A run's file is a regular file: a pipe in its place (a FIFO named summary.json) would block the
// report for ever, a folder or a device would read as nothing or as garbage.
void require_regular_file(const fs::path& file) {
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);
  if (fs::exists(st) && !fs::is_regular_file(st))
    throw SessionError(fmt::format("{}: not a regular file (a pipe, a device or a folder); a run writes its own file "
                                   "there: run the session again",
                                   file.string()));
}

// A session folder's files are a run's (limits.hpp, "files read back").
void require_at_most(const fs::path& file, std::uint64_t limit, const char* what) {
  if (const std::string problem = limits::file_size_problem(file.string(), limit, what); !problem.empty())
    throw SessionError(problem + "; it is not the file a run wrote: give the folder a run wrote");
}

std::vector<std::uint8_t> read_bytes(const fs::path& file) {
  require_regular_file(file);
  require_at_most(file, limits::max_session_picture_bytes, "a run's picture");
  std::ifstream in(file, std::ios::binary);
  if (!in) return {};
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

nlohmann::json read_json(const fs::path& file, const char* what) {
  require_regular_file(file);
  require_at_most(file, limits::max_session_json_bytes, what);
  std::ifstream in(file);
  if (!in) throw SessionError(fmt::format("{}: cannot open {}", file.string(), what));
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    // A parse error, or a number out of range (1e30992: found by fuzz_report_folder).
    throw SessionError(fmt::format("{}: not valid JSON ({}); the run that wrote it did not finish: run it again",
                                   file.string(), e.what()));
  }
}

// A CSV row's wanted columns, in the order asked (at most five), held flat.
struct Row {
  static constexpr std::size_t kColumns = 5;
  double v[kColumns] = {};
  double operator[](std::size_t i) const { return v[i]; }
};

// The columns `want` (by header name) of a CSV file of numbers, row by row.
std::vector<Row> read_csv(const fs::path& file, const std::vector<std::string>& want) {
  if (want.size() > Row::kColumns) throw std::logic_error("read_csv: at most five columns");
  require_regular_file(file);
  require_at_most(file, limits::max_session_csv_bytes, "a run's log");
  std::FILE* f = std::fopen(file.c_str(), "r");
  if (!f) throw SessionError(fmt::format("{}: cannot open", file.string()));
  std::vector<Row> rows;
  std::vector<int> column(want.size(), -1);
  char buf[4096];
  int line = 0;
  std::size_t columns = 0;
  while (std::fgets(buf, sizeof buf, f)) {
    ++line;
    std::string text(buf);
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    if (text.empty()) continue;
    if (line == 1) {
      std::vector<std::string> names;
      std::size_t a = 0;
      for (std::size_t b; (b = text.find(',', a)) != std::string::npos; a = b + 1) names.push_back(text.substr(a, b - a));
      names.push_back(text.substr(a));
      columns = names.size();
      for (std::size_t w = 0; w < want.size(); ++w) {
        const auto it = std::find(names.begin(), names.end(), want[w]);
        if (it == names.end()) {
          std::fclose(f);
          throw SessionError(fmt::format("{}: line 1: no column '{}' in the header '{}'; is this a dentsph run's file?",
                                         file.string(), want[w], text));
        }
        column[w] = int(it - names.begin());
      }
      continue;
    }
    std::vector<double> all;
    const char* p = text.c_str();
    while (true) {
      char* end = nullptr;
      const double v = std::strtod(p, &end);
      if (end == p || (*end != ',' && *end != '\0')) {
        std::fclose(f);
        throw SessionError(fmt::format("{}: line {}, column {}: not a number; the file is damaged: run the session again",
                                       file.string(), line, all.size() + 1));
      }
      all.push_back(v);
      if (*end == '\0') break;
      p = end + 1;
    }
    if (all.size() != columns) {
      std::fclose(f);
      throw SessionError(fmt::format("{}: line {}: {} columns, the header has {}; the file is damaged (cut short?)",
                                     file.string(), line, all.size(), columns));
    }
    Row row;
    for (std::size_t w = 0; w < column.size(); ++w) row.v[w] = all[std::size_t(column[w])];
    rows.push_back(row);
  }
  std::fclose(f);
  return rows;
}

double number_or(const nlohmann::json& j, const char* key, double fallback) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : fallback;
}

// Markers from procedure.json's events, on the simulated time axis.
void markers_from_procedure(SessionFolder& s, const std::vector<double>* step_time) {
  if (!s.procedure.is_object()) return;  // no procedure.json: no markers (found by fuzz_report_folder)
  int increments = 0;
  for (const nlohmann::json& e : s.procedure.value("events", nlohmann::json::array())) {
    Marker m;
    m.kind = e.value("kind", "");
    const auto step = e.value("step", std::uint64_t(0));
    m.t = step_time ? (step < step_time->size() ? (*step_time)[step] : (step_time->empty() ? 0 : step_time->back()))
                    : e.value("t_s", 0.0);
    if (m.kind == "dispense")
      m.label = fmt::format("increment {}{}", ++increments, e.value("source", "") == "button" ? " (button)" : "");
    else if (m.kind == "cure")
      m.label = "curing light on";
    else if (m.kind == "light")
      m.label = "curing light on or off (button)";
    else
      m.label = fmt::format("instrument: {}", e.value("tool", "?"));
    s.markers.push_back(m);
  }
}

}  // namespace

Series decimate(const Series& s, std::size_t buckets) {
  const std::size_t n = std::min(s.t.size(), s.f.size());
  if (n <= 2 * buckets || buckets == 0) return s;
  Series out{s.label, {}, {}};
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t lo = b * n / buckets, hi = (b + 1) * n / buckets;
    std::size_t imin = lo, imax = lo;
    for (std::size_t i = lo; i < hi; ++i) {
      if (s.f[i] < s.f[imin]) imin = i;
      if (s.f[i] > s.f[imax]) imax = i;
    }
    for (std::size_t i : {std::min(imin, imax), std::max(imin, imax)}) {
      out.t.push_back(s.t[i]);
      out.f.push_back(s.f[i]);
      if (imin == imax) break;
    }
  }
  return out;
}

SessionFolder read_session(const fs::path& dir) {
  if (!fs::is_directory(dir))
    throw SessionError(fmt::format("{}: no such folder; give the --out folder of a dentsph run", dir.string()));
  SessionFolder s;
  s.dir = dir;
  if (!fs::exists(dir / "summary.json"))
    throw SessionError(fmt::format("{}: no summary.json: not the output folder of a finished dentsph run (give the "
                                   "folder that `dentsph run --out` wrote)",
                                   dir.string()));
  s.summary = read_json(dir / "summary.json", "the run's summary");
  if (!s.summary.is_object() || !s.summary.contains("steps"))
    throw SessionError(fmt::format("{}: not a dentsph run summary (no \"steps\"); give the folder that `dentsph run "
                                   "--out` wrote", (dir / "summary.json").string()));
  check_summary_fields(dir / "summary.json", s.summary);
  s.realtime = s.summary.contains("haptic");
  if (fs::exists(dir / "procedure.json")) {
    s.procedure = read_json(dir / "procedure.json", "the procedure's log");
    check_procedure_fields(dir / "procedure.json", s.procedure);
  }
  const double scale = number_or(s.summary.value("tool", nlohmann::json::object()), "force_scale", 1.0);

  if (fs::exists(dir / "tool_force.csv")) {
    s.time_axis = "simulated time (s)";
    Series f{"force on the instrument (device N)", {}, {}};
    for (const auto& r : read_csv(dir / "tool_force.csv", {"t", "fx", "fy", "fz"})) {
      f.t.push_back(r[0]);
      f.f.push_back(std::sqrt(r[1] * r[1] + r[2] * r[2] + r[3] * r[3]) * scale);
    }
    s.forces.push_back(std::move(f));
    markers_from_procedure(s, nullptr);
  } else if (fs::exists(dir / "recording" / "steps.csv")) {
    s.time_axis = "session time (s)";
    Series sim{"simulated force x force scale (device N)", {}, {}};
    std::vector<double> step_time;
    for (const auto& r : read_csv(dir / "recording" / "steps.csv", {"step", "wall_t", "fx", "fy", "fz"})) {
      sim.t.push_back(r[1]);
      sim.f.push_back(std::sqrt(r[2] * r[2] + r[3] * r[3] + r[4] * r[4]) * scale);
      step_time.push_back(r[1]);
    }
    if (fs::exists(dir / "recording" / "haptic.csv")) {
      Series sent{"force sent to the device (N)", {}, {}};
      for (const auto& r : read_csv(dir / "recording" / "haptic.csv", {"t", "fx", "fy", "fz"})) {
        sent.t.push_back(r[0]);
        sent.f.push_back(std::sqrt(r[1] * r[1] + r[2] * r[2] + r[3] * r[3]));
      }
      s.forces.push_back(std::move(sent));
    }
    s.forces.push_back(std::move(sim));
    if (!s.procedure.is_null()) {
      markers_from_procedure(s, &step_time);
    } else if (fs::exists(dir / "recording" / "events.csv")) {
      int k = 0;
      for (const auto& r : read_csv(dir / "recording" / "events.csv", {"step", "event"})) {
        const auto step = std::size_t(r[0]);
        s.markers.push_back({step < step_time.size() ? step_time[step] : 0.0, "event", fmt::format("event {}", ++k)});
      }
    }
  }
  s.cut_png = read_bytes(dir / kCutPicture);
  s.top_png = read_bytes(dir / kTopPicture);
  s.cut_particles_png = read_bytes(dir / kCutParticlesPicture);
  s.top_particles_png = read_bytes(dir / kTopParticlesPicture);
  if (s.cut_png.empty() && s.top_png.empty()) s.preview_png = read_bytes(dir / "preview.png");
  s.grading_svg = read_bytes(dir / kGradingPicture);
  return s;
}

}  // namespace dentsph::report
