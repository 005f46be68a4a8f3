// `dentsph report`: a run folder's report.html written again from its files, several sessions
// side by side (HTML and CSV), from folders or from the session store; and the session options of
// `dentsph run` (--student, --exercise, --db) that name a session and index it in the store.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "dentsph/scene.hpp"

namespace dentsph::cli {

// --student, --exercise and --db on `dentsph run`.
class SessionOptions {
 public:
  void add_options(CLI::App& run);
  // The names given on the command line replace the scene file's.
  void apply(Scene& scene) const;
  // Before the run: with --db, the run has a folder and the store opens (an SQLite file is created
  // when missing); throws (report::StoreError, std::invalid_argument) otherwise.
  void check(const std::filesystem::path& out_dir) const;
  // Adds the finished run's folder to the store when --db was given (says so on stdout).
  void record(const std::filesystem::path& out_dir) const;

 private:
  std::string student_, exercise_, db_;
};

class ReportCommand {
 public:
  void add_subcommand(CLI::App& app);
  bool chosen() const { return cmd_ && cmd_->parsed(); }
  // Throws report::SessionError (a folder that is not a run folder) and report::StoreError;
  // main turns them into exit status 2.
  int run() const;

 private:
  CLI::App* cmd_ = nullptr;
  std::vector<std::string> dirs_;
  std::string out_, csv_, db_, student_, exercise_, title_;
};

}  // namespace dentsph::cli
