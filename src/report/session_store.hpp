// The session store: every session's particulars (student, exercise, when), where its files are
// (the run folder, its recording, its report) and its summary and procedure, indexed in an
// embedded SQLite database, so that a class's or a student's sessions are found without their
// folders (docs/report.md). The schema and its migrations: store_schema.hpp.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "report/class_report.hpp"

namespace dentsph::report {

// A store that cannot be opened, migrated or written. what() names the database and the fix.
class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SessionStore {
 public:
  // Opens the SQLite database `location` (a file, created when missing) and brings its schema to
  // the current version. A postgresql:// address is refused with the reason (StoreError).
  explicit SessionStore(const std::string& location);
  ~SessionStore();
  SessionStore(SessionStore&&) noexcept;
  SessionStore& operator=(SessionStore&&) noexcept;

  // Adds a session; returns its id.
  std::int64_t add(const SessionEntry& session);
  // Adds the session of a run folder (session_entry(dir), its recording when present).
  std::int64_t add_folder(const std::filesystem::path& dir);
  // The sessions of `student` and `exercise` (empty: any), oldest first.
  std::vector<SessionEntry> find(const std::string& student, const std::string& exercise) const;
  int schema_version() const;
  const std::string& location() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace dentsph::report
