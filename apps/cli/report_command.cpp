#include "report_command.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>

#include <fmt/format.h>

#include "dentsph/report/class_report.hpp"
#include "dentsph/report/session_folder.hpp"
#include "dentsph/report/session_report.hpp"
#include "dentsph/report/session_store.hpp"
#include "option_checks.hpp"
#include "progress.hpp"

namespace dentsph::cli {

namespace {

void write_file(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write", file.string()));
}

// Calls `each(k)` for k in [0, n) with a progress bar on stderr when there are many.
template <class F>
void with_progress(std::size_t n, F each) {
  ProgressReporter progress;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < n; ++k) {
    each(k);
    if (n >= 5) {
      const double w = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      progress({k + 1, n, 0, w, w / double(k + 1) * double(n - k - 1)});
    }
  }
}

// --db: an empty address is refused, not taken for none.
CLI::Validator store_address() {
  return CLI::Validator(
      [](const std::string& v) {
        return v.find_first_not_of(" \t") == std::string::npos
                   ? std::string("an empty session store address: give an SQLite file (sessions.sqlite) or a "
                                 "PostgreSQL address (postgresql://user@host/dentsph)")
                   : std::string();
      },
      "STORE");
}

// Whether `target` is a file a run wrote in `folder` (anything there but a page or table of one's
// own: the run's report.html, tool_force.csv, its recording and particles are its files too).
bool run_folder_file(const std::filesystem::path& folder, const std::filesystem::path& target) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path f = fs::weakly_canonical(folder, ec), t = fs::weakly_canonical(target, ec);
  if (ec || f.empty()) return false;
  const fs::path rel = t.lexically_relative(f);
  if (rel.empty() || rel.native().rfind("..", 0) == 0) return false;  // outside the folder
  if (!fs::exists(t)) return false;  // a new file beside the run's: nothing lost
  const std::string name = rel.filename().string(), top = rel.begin()->string(), ext = rel.extension().string();
  if (top == "recording" || top == "particles") return true;
  if (name == "report.html" || name == "tool_force.csv") return true;
  return ext != ".html" && ext != ".csv";
}

}  // namespace

void SessionOptions::add_options(CLI::App& run) {
  run.add_option("--student", student_, "Who runs the session (the report's title; the session store's index)")
      ->check(person_text());
  run.add_option("--exercise", exercise_, "Which exercise the session is (the report; the session store's index)")
      ->check(person_text());
  run.add_option("--db", db_,
                 "Index the finished session in this session store (an SQLite file, created when missing, or a "
                 "PostgreSQL address)")
      ->check(store_address());
}

void SessionOptions::check(const std::filesystem::path& out_dir) const {
  if (db_.empty()) return;
  if (out_dir.empty()) throw std::invalid_argument("--db needs the run's folder: give --out DIR");
  // Opening it says now what would otherwise be said after the session (a folder that does not
  // exist, a file that is not a session store, one from a newer dentsph): refused before the run.
  report::SessionStore store(db_);
}

void SessionOptions::apply(Scene& scene) const {
  if (!student_.empty()) scene.student = student_;
  if (!exercise_.empty()) scene.exercise = exercise_;
}

void SessionOptions::record(const std::filesystem::path& out_dir) const {
  if (db_.empty()) return;
  if (out_dir.empty()) throw std::invalid_argument("--db needs the run's folder: give --out DIR");
  report::SessionStore store(db_);
  const std::int64_t id = store.add_folder(out_dir);
  if (id > 0)
    fmt::print("session {} of {} added to the session store {}\n", id, out_dir.string(), report::masked_location(db_));
  else
    fmt::print("the session store {} cannot be reached: the session of {} is kept locally ({} waiting) and sent when "
               "the store is next reached\n",
               report::masked_location(db_), out_dir.string(), store.pending());
}

void ReportCommand::add_subcommand(CLI::App& app) {
  cmd_ = app.add_subcommand("report",
                            "Write a run folder's report.html again, or compare sessions (folders, or --db with "
                            "--student / --exercise) in one HTML page and a CSV");
  cmd_->add_option("dirs", dirs_, "Run folders (the --out of dentsph run)");
  cmd_->add_option("--out", out_, "Compare the sessions in this HTML file (and a CSV beside it)");
  cmd_->add_option("--csv", csv_, "The comparison's CSV (default: --out with .csv)");
  cmd_->add_option("--db", db_, "Take the sessions from this session store (an SQLite file dentsph run --db made, or a "
                                "PostgreSQL address)")
      ->check(store_address());
  cmd_->add_option("--student", student_, "With --db: this student's sessions");
  cmd_->add_option("--exercise", exercise_, "With --db: this exercise's sessions");
  cmd_->add_option("--title", title_, "The comparison's title");
}

int ReportCommand::run() const {
  if (!db_.empty() && !dirs_.empty()) throw std::invalid_argument("report: give run folders or --db, not both");
  if (db_.empty() && dirs_.empty())
    throw std::invalid_argument("report: give one or more run folders (dentsph run --out DIR), or --db FILE");
  if (db_.empty() && (!student_.empty() || !exercise_.empty()))
    throw std::invalid_argument("report: --student and --exercise choose sessions of a store: give --db FILE");
  if (out_.empty() && !db_.empty()) throw std::invalid_argument("report --db: give --out FILE.html for the comparison");
  // The comparison's CSV: --csv, or --out with .csv.
  std::filesystem::path csv = csv_;
  if (csv.empty() && !out_.empty()) csv = std::filesystem::path(out_).replace_extension(".csv");
  // The comparison never overwrites what it reads: a run folder's own files (its summary.json
  // became HTML, exit 0), nor the one with the other.
  if (!out_.empty()) {
    for (const auto& [option, target] : {std::pair<std::string, std::filesystem::path>{"--out", out_}, {"--csv", csv}}) {
      for (const std::string& d : dirs_)
        if (run_folder_file(d, target))
          throw std::invalid_argument(fmt::format("{} {}: that is a file of the run folder {}, which the report reads; "
                                                  "write the comparison elsewhere (e.g. --out class.html)",
                                                  option, target.string(), d));
    }
    if (std::filesystem::weakly_canonical(out_) == std::filesystem::weakly_canonical(csv))
      throw std::invalid_argument(fmt::format("--csv {}: the same file as --out; give another", csv.string()));
  }

  if (out_.empty()) {  // each folder's report.html again
    with_progress(dirs_.size(), [&](std::size_t k) {
      const std::filesystem::path file = report::write_session_report(dirs_[k]);
      if (dirs_.size() < 5) fmt::print("wrote {}\n", file.string());
    });
    if (dirs_.size() >= 5) fmt::print("wrote report.html in {} folders\n", dirs_.size());
    return 0;
  }

  std::vector<report::SessionEntry> sessions;
  std::string title = title_;
  if (!db_.empty()) {
    // Reading: a file that is not there is a mistyped name, not a store to make.
    if (!report::is_postgres_location(db_) && !std::filesystem::exists(db_))
      throw std::invalid_argument(fmt::format("--db {}: no such session store; give the file dentsph run --db wrote",
                                              db_));
    const report::SessionStore store(db_);
    sessions = store.find(student_, exercise_);
    if (sessions.empty())
      throw std::invalid_argument(fmt::format("{}: no session{}{}: check the names (dentsph run --student NAME "
                                              "--exercise NAME --db {})",
                                              db_, student_.empty() ? "" : " of student '" + student_ + "'",
                                              exercise_.empty() ? "" : " in exercise '" + exercise_ + "'", db_));
    if (title.empty())
      title = !student_.empty() ? "Sessions of " + student_ + (exercise_.empty() ? "" : ", " + exercise_)
                                : "Sessions of " + exercise_;
  } else {
    sessions.resize(dirs_.size());
    with_progress(dirs_.size(), [&](std::size_t k) { sessions[k] = report::session_entry(dirs_[k]); });
    if (title.empty()) title = fmt::format("{} sessions side by side", sessions.size());
  }
  if (title.empty()) title = "Sessions side by side";
  write_file(out_, report::class_report_html(sessions, title));
  write_file(csv, report::class_report_csv(sessions));
  fmt::print("wrote {} and {} ({} sessions)\n", out_, csv.string(), sessions.size());
  return 0;
}

}  // namespace dentsph::cli
