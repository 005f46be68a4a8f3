// A session's recording as three CSV files (17 significant digits: doubles read back exactly).
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dentsph/haptics/recording.hpp"

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

// Rows of numbers after a header line that must match; errors name file, line and column.
std::vector<std::vector<double>> read_rows(const std::filesystem::path& p, const char* header, std::size_t columns) {
  std::ifstream in(p);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the recording file", p.string()));
  std::string line;
  std::getline(in, line);
  if (line != header)
    throw std::runtime_error(fmt::format("{}: line 1: expected the header '{}'; is this a dentsph recording?", p.string(), header));
  std::vector<std::vector<double>> rows;
  for (int ln = 2; std::getline(in, line); ++ln) {
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) {
      try {
        std::size_t used = 0;
        row.push_back(std::stod(cell, &used));
        if (used != cell.size()) throw std::invalid_argument(cell);
      } catch (const std::exception&) {
        throw std::runtime_error(fmt::format("{}: line {}, column {}: '{}' is not a number", p.string(), ln,
                                             row.size() + 1, cell));
      }
    }
    if (row.size() != columns)
      throw std::runtime_error(fmt::format("{}: line {}: {} columns, expected {}", p.string(), ln, row.size(), columns));
    rows.push_back(std::move(row));
  }
  return rows;
}

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
    const nlohmann::json session = {{"mode", r.mode},
                                    {"haptic_rate_hz", r.haptic_rate_hz},
                                    {"force_scale", r.force_scale},
                                    {"haptic_dropped", r.haptic_dropped},
                                    {"dispense_volume", r.dispense_volume},
                                    {"backend", r.backend}};
    fmt::print(f.f, "{}\n", session.dump());
  }
}

Recording load_recording(const std::filesystem::path& dir) {
  Recording r;
  for (const auto& row : read_rows(dir / "haptic.csv", kHapticHeader, 23)) {
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
  for (const auto& row : read_rows(dir / "steps.csv", kStepsHeader, 12)) {
    StepSample s;
    s.step = std::uint64_t(row[0]);
    s.wall_t = row[1];
    s.tool_pose = {{row[2], row[3], row[4]}, {row[5], row[6], row[7], row[8]}};
    s.tool_force = {row[9], row[10], row[11]};
    r.steps.push_back(s);
  }
  for (const auto& row : read_rows(dir / "events.csv", kEventsHeader, 2))
    r.events.push_back({std::uint64_t(row[0]), std::uint32_t(row[1])});
  // The session's settings, as save_recording writes them (dispense_volume and backend are absent
  // in older recordings: the scene's default, the CPU).
  if (std::ifstream in(dir / "session.json"); in) {
    const nlohmann::json s = nlohmann::json::parse(in, nullptr, false);
    if (s.is_discarded() || !s.is_object())
      throw std::runtime_error(fmt::format("{}: not a JSON object; write the recording again", (dir / "session.json").string()));
    r.mode = s.value("mode", r.mode);
    r.haptic_rate_hz = s.value("haptic_rate_hz", r.haptic_rate_hz);
    r.force_scale = s.value("force_scale", r.force_scale);
    r.haptic_dropped = s.value("haptic_dropped", r.haptic_dropped);
    r.dispense_volume = s.value("dispense_volume", 0.0);
    r.backend = s.value("backend", std::string("cpu"));
  }
  return r;
}

}  // namespace dentsph
