// The session store: every session's particulars (student, exercise, when), where its files are
// (the run folder, its recording, its report) and its summary and procedure, so that a class's or
// a student's sessions are found without their folders (docs/report.md). In an embedded SQLite
// file by default, or on a PostgreSQL server (a postgresql:// address) that many workstations
// share; a session the server cannot take (unreachable, or lost mid-write) is kept in a local
// spool and sent when the store is next reached. The schema and its migrations: store_schema.hpp.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "dentsph/report/class_report.hpp"

namespace dentsph::report {

// A store that cannot be opened, migrated, read or written. what() names the database (a
// password in its address masked) and the fix.
class StoreError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class StoreBackend;

class SessionStore {
 public:
  // `location`: a file (SQLite, created when missing) or a PostgreSQL address: postgresql:// (or
  // postgres://), or libpq's key-value form ("host=db.school dbname=dentsph user=tutor").
  // `spool_dir`: where a PostgreSQL store keeps what it could not send (empty: $DENTSPH_STORE_SPOOL,
  // else ~/.local/state/dentsph). Opening a PostgreSQL store sends what its spool holds.
  explicit SessionStore(const std::string& location, const std::filesystem::path& spool_dir = {});
  ~SessionStore();
  SessionStore(SessionStore&&) noexcept;
  SessionStore& operator=(SessionStore&&) noexcept;

  // Adds a session; returns its id, or 0 when a PostgreSQL server could not take it and it was
  // kept in the spool (pending() counts those).
  std::int64_t add(const SessionEntry& session);
  // Adds the session of a run folder (session_entry(dir), its paths made absolute).
  std::int64_t add_folder(const std::filesystem::path& dir);
  // The sessions of `student` and `exercise` (empty: any), oldest first.
  std::vector<SessionEntry> find(const std::string& student, const std::string& exercise) const;
  int schema_version() const;
  // Sessions waiting in the spool for the server (0 for SQLite).
  std::size_t pending() const;
  const std::string& location() const;

 private:
  std::string location_;
  std::unique_ptr<StoreBackend> backend_;
};

// `location` with a password in it replaced by ***: a URI's user:password@ and password= parameter,
// a key-value address's password=.
std::string masked_location(const std::string& location);
// A postgresql:// or postgres:// URI, or a libpq key-value address (it begins with a libpq keyword
// and '=': host, dbname, user, password, port, ...).
bool is_postgres_location(const std::string& location);

}  // namespace dentsph::report
