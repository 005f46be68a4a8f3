// Fuzz target: a run's session folder as `dentsph report` reads it (report::read_session) and the
// page it makes of it (report::session_report_html). The input is the folder's files, parted by a
// line "=====": summary.json, tool_force.csv, procedure.json, recording/steps.csv,
// recording/haptic.csv and recording/events.csv, in that order (an empty part, or fewer parts:
// those files are absent). A broken folder is refused with a SessionError naming the file; any other exception,
// a crash or a sanitizer's report is a finding (the first robustness round found raw library
// exceptions here: a JSON type error, "basic_filebuf::underflow", "cannot use value() with null").
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "dentsph/report/session_folder.hpp"
#include "dentsph/report/session_report.hpp"
#include "fuzz_support.hpp"
#include "fuzz_targets.hpp"

namespace dentsph::fuzz {

int report_folder(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  static const char* const files[] = {"summary.json",        "tool_force.csv",       "procedure.json",
                                      "recording/steps.csv", "recording/haptic.csv", "recording/events.csv"};
  const fs::path dir = scratch_dir() / "run";
  std::error_code ec;
  fs::remove_all(dir, ec);
  fs::create_directories(dir / "recording");
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static constexpr std::string_view cut = "\n=====\n";
  std::size_t at = 0;
  for (const char* file : files) {
    if (at > text.size()) break;
    const std::size_t end = std::min(text.find(cut, at), text.size());
    if (end > at) write_file(dir / file, data + at, end - at);  // an empty part: the file is absent
    at = end + cut.size();
  }
  try {
    const report::SessionFolder s = report::read_session(dir);
    (void)report::session_report_html(s);
  } catch (const report::SessionError&) {
  }
  return 0;
}

}  // namespace dentsph::fuzz
