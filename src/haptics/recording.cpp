// A session's recording as three CSV files (17 significant digits: doubles read back exactly).
#include "dentsph/haptics/replay.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dentsph/limits.hpp"
#include "dentsph/model.hpp"

namespace dentsph {

namespace {

constexpr const char* kHapticHeader =
    "t,x,y,z,qw,qx,qy,qz,vx,vy,vz,fx,fy,fz,target_x,target_y,target_z,proxy_x,proxy_y,proxy_z,gain,status,pose_sequence";
constexpr const char* kStepsHeader = "step,wall_t,x,y,z,qw,qx,qy,qz,fx,fy,fz";
constexpr const char* kEventsHeader = "step,event";

struct File {
  std::FILE* f;
  explicit File(const std::filesystem::path& p) : f(std::fopen(p.c_str(), "w")) {
    if (!f) throw std::runtime_error(fmt::format("{}: cannot open for writing", p.string()));
  }
  ~File() { std::fclose(f); }
  File(const File&) = delete;
  File& operator=(const File&) = delete;
};

std::string v3(const Vec3& v) { return fmt::format("{:.17g},{:.17g},{:.17g}", v.x, v.y, v.z); }
std::string q4(const Quat& q) { return fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}", q.w, q.x, q.y, q.z); }

// What a column of a recording file holds.
struct Column {
  bool whole = false;   // a count or an index: a whole number in [0, max]
  double max = 0;
};

// A recording's file no larger than the runtime writes (limits.hpp, "files read back").
void require_at_most(const std::filesystem::path& p, std::uint64_t limit) {
  if (const std::string problem = limits::file_size_problem(p.string(), limit, "a recording's file");
      !problem.empty())
    throw std::runtime_error(problem + "; it is not a session's recording: record the session again");
}

// Rows of numbers after a header line that must match; errors name file, line and column. Every
// number must be finite, whole numbers whole and in range, and the unit quaternion starting at
// column `quat` (if any) of unit length: a recording that holds a NaN is refused here, not
// replayed into a comparison of NaN forces.
std::vector<std::vector<double>> read_rows(const std::filesystem::path& p, const char* header, std::uint64_t max_bytes,
                                           const std::vector<Column>& columns, int quat = -1) {
  require_at_most(p, max_bytes);
  std::ifstream in(p);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the recording file", p.string()));
  std::string line;
  std::getline(in, line);
  if (line != header)
    throw std::runtime_error(fmt::format("{}: line 1: expected the header '{}'; is this a dentsph recording?", p.string(), header));
  std::vector<std::string> names;
  {
    std::stringstream hs(header);
    for (std::string name; std::getline(hs, name, ',');) names.push_back(name);
  }
  std::vector<std::vector<double>> rows;
  for (std::size_t ln = 2; std::getline(in, line); ++ln) {
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) {
      const std::size_t c = row.size();
      auto refuse = [&](const std::string& problem) {
        throw std::runtime_error(fmt::format("{}: line {}, column {} ({}): {}; the recording is damaged: record the "
                                             "session again",
                                             p.string(), ln, c + 1, c < names.size() ? names[c] : "extra", problem));
      };
      double v = 0;
      try {
        std::size_t used = 0;
        v = std::stod(cell, &used);
        if (used != cell.size()) throw std::invalid_argument(cell);
      } catch (const std::exception&) {
        refuse(fmt::format("'{}' is not a number", cell.substr(0, 40)));
      }
      if (!std::isfinite(v)) refuse(fmt::format("'{}' is not a finite number", cell.substr(0, 40)));
      if (c < columns.size() && columns[c].whole && !(v >= 0 && v <= columns[c].max && v == std::floor(v)))
        refuse(fmt::format("{:.17g} is not a whole number from 0 to {:.17g}", v, columns[c].max));
      row.push_back(v);
    }
    if (row.size() != columns.size())
      throw std::runtime_error(fmt::format("{}: line {}: {} columns, expected {}", p.string(), ln, row.size(), columns.size()));
    if (quat >= 0) {
      const double n = std::sqrt(row[quat] * row[quat] + row[quat + 1] * row[quat + 1] + row[quat + 2] * row[quat + 2] +
                                 row[quat + 3] * row[quat + 3]);
      if (!(std::abs(n - 1) < 1e-6))
        throw std::runtime_error(fmt::format("{}: line {}, columns {} to {} ({}): the orientation has length {:.6g}, not "
                                             "1; the recording is damaged: record the session again",
                                             p.string(), ln, quat + 1, quat + 4, "qw, qx, qy, qz", n));
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

// `n` columns of real numbers, then whole ones as given.
std::vector<Column> reals(std::size_t n) { return std::vector<Column>(n); }
constexpr double u32 = 4294967295.0, u53 = 9007199254740992.0;  // the largest uint32, and 2^53

}  // namespace

void save_recording(const std::filesystem::path& dir, const Recording& r) {
  std::filesystem::create_directories(dir);
  {
    File f(dir / "haptic.csv");
    fmt::print(f.f, "{}\n", kHapticHeader);
    for (const HapticSample& s : r.haptic)
      fmt::print(f.f, "{:.17g},{},{},{},{},{},{},{:.17g},{},{}\n", s.t, v3(s.device_position), q4(s.device_orientation),
                 v3(s.device_velocity), v3(s.force), v3(s.target), v3(s.proxy_position), s.gain, s.status,
                 s.pose_sequence);
  }
  {
    File f(dir / "steps.csv");
    fmt::print(f.f, "{}\n", kStepsHeader);
    for (const StepSample& s : r.steps)
      fmt::print(f.f, "{},{:.17g},{},{},{}\n", s.step, s.wall_t, v3(s.tool_pose.position), q4(s.tool_pose.orientation),
                 v3(s.tool_force));
  }
  {
    File f(dir / "events.csv");
    fmt::print(f.f, "{}\n", kEventsHeader);
    for (const EventSample& e : r.events) fmt::print(f.f, "{},{}\n", e.step, e.index);
  }
  {
    // Written by the JSON library that reads it back (strings escaped, numbers to the last bit).
    File f(dir / "session.json");
    nlohmann::json session = {{"mode", r.mode},
                              {"haptic_rate_hz", r.haptic_rate_hz},
                              {"force_scale", r.force_scale},
                              {"haptic_dropped", r.haptic_dropped},
                              {"dispense_volume", r.dispense_volume},
                              {"backend", r.backend}};
    if (!r.solver.empty()) session["solver"] = r.solver;  // none: not known (replay takes the scene's)
    if (!r.material.empty()) session["material"] = {{"preset", r.material}, {"temperature_c", r.material_temperature_c}};
    fmt::print(f.f, "{}\n", session.dump());
  }
}

Recording load_recording(const std::filesystem::path& dir) {
  Recording r;
  std::vector<Column> haptic = reals(23);
  haptic[21] = haptic[22] = {true, u32};  // status, pose_sequence
  for (const auto& row : read_rows(dir / "haptic.csv", kHapticHeader, limits::max_recording_haptic_bytes, haptic, 4)) {
    HapticSample s;
    s.t = row[0];
    s.device_position = {row[1], row[2], row[3]};
    s.device_orientation = {row[4], row[5], row[6], row[7]};
    s.device_velocity = {row[8], row[9], row[10]};
    s.force = {row[11], row[12], row[13]};
    s.target = {row[14], row[15], row[16]};
    s.proxy_position = {row[17], row[18], row[19]};
    s.gain = row[20];
    s.status = std::uint32_t(row[21]);
    s.pose_sequence = std::uint32_t(row[22]);
    r.haptic.push_back(s);
  }
  std::vector<Column> steps = reals(12);
  steps[0] = {true, u53};  // step
  for (const auto& row : read_rows(dir / "steps.csv", kStepsHeader, limits::max_recording_steps_bytes, steps, 5)) {
    StepSample s;
    s.step = std::uint64_t(row[0]);
    s.wall_t = row[1];
    s.tool_pose = {{row[2], row[3], row[4]}, {row[5], row[6], row[7], row[8]}};
    s.tool_force = {row[9], row[10], row[11]};
    r.steps.push_back(s);
  }
  for (const auto& row : read_rows(dir / "events.csv", kEventsHeader, limits::max_recording_steps_bytes, {{true, u53}, {true, u32}}))
    r.events.push_back({std::uint64_t(row[0]), std::uint32_t(row[1])});
  // The session's settings, as save_recording writes them (dispense_volume, backend and solver are
  // absent in older recordings: the scene's default, the CPU, the scene's solver).
  if (std::filesystem::exists(dir / "session.json")) require_at_most(dir / "session.json", limits::max_recording_json_bytes);
  if (std::ifstream in(dir / "session.json"); in) {
    const std::string file = (dir / "session.json").string();
    const nlohmann::json s = nlohmann::json::parse(in, nullptr, false);
    if (s.is_discarded() || !s.is_object())
      throw std::runtime_error(fmt::format("{}: not a JSON object; write the recording again", file));
    // A number of the session: finite, at least `lo`.
    auto number = [&](const char* key, double fallback, double lo) {
      if (!s.contains(key)) return fallback;
      const nlohmann::json& v = s[key];
      if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < lo)
        throw std::runtime_error(fmt::format("{}: {}: expected a finite number of at least {}, got {}; the recording "
                                             "is damaged: record the session again",
                                             file, key, lo, v.dump().substr(0, 40)));
      return v.get<double>();
    };
    if (s.contains("mode")) {
      if (!s["mode"].is_string() || (s["mode"] != "direct" && s["mode"] != "coupling"))
        throw std::runtime_error(fmt::format("{}: mode: expected \"direct\" or \"coupling\", got {}; the recording is "
                                             "damaged: record the session again",
                                             file, s["mode"].dump().substr(0, 40)));
      r.mode = s["mode"].get<std::string>();
    }
    r.haptic_rate_hz = number("haptic_rate_hz", r.haptic_rate_hz, 0);
    r.force_scale = number("force_scale", r.force_scale, 0);
    r.haptic_dropped = std::uint64_t(std::min(number("haptic_dropped", double(r.haptic_dropped), 0), u53));
    r.dispense_volume = number("dispense_volume", 0.0, 0);
    if (s.contains("backend")) {
      if (!s["backend"].is_string() || (s["backend"] != "cpu" && s["backend"] != "cuda" && s["backend"] != "cuda-emulation"))
        throw std::runtime_error(fmt::format("{}: backend: expected \"cpu\", \"cuda\" or \"cuda-emulation\", got {}; the "
                                             "recording is damaged: record the session again",
                                             file, s["backend"].dump().substr(0, 40)));
      r.backend = s["backend"].get<std::string>();
    }
    if (s.contains("solver")) {
      if (!s["solver"].is_string() || !solver_from_name(s["solver"].get<std::string>()))
        throw std::runtime_error(fmt::format("{}: solver: expected \"paper\" or \"iisph\", got {}; the recording is "
                                             "damaged: record the session again",
                                             file, s["solver"].dump().substr(0, 40)));
      r.solver = s["solver"].get<std::string>();
    }
    if (s.contains("material")) {
      const nlohmann::json& m = s["material"];
      if (!m.is_object() || !m.contains("preset") || !m["preset"].is_string() || !m.contains("temperature_c") ||
          !m["temperature_c"].is_number())
        throw std::runtime_error(fmt::format("{}: material: expected {{\"preset\": name, \"temperature_c\": C}}, got {}; "
                                             "the recording is damaged: record the session again",
                                             file, m.dump().substr(0, 60)));
      r.material = m["preset"].get<std::string>();
      r.material_temperature_c = m["temperature_c"].get<double>();
    }
  }
  return r;
}

}  // namespace dentsph
