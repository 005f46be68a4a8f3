// The session store in an embedded SQLite file: the default store, and the local keeping of
// sessions a PostgreSQL server could not take (postgres_store.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "report/store_backend.hpp"

struct sqlite3;

namespace dentsph::report {

class SqliteStore final : public StoreBackend {
 public:
  // Opens (creating) the file and migrates it to the current schema; throws StoreError.
  explicit SqliteStore(std::string location);
  ~SqliteStore() override;
  SqliteStore(const SqliteStore&) = delete;
  SqliteStore& operator=(const SqliteStore&) = delete;

  std::int64_t add(const SessionEntry& e) override;
  std::vector<SessionEntry> find(const std::string& student, const std::string& exercise) const override;
  int schema_version() const override;
  // Every session with its id, oldest id first; and one removed (the spool's sending).
  std::vector<std::pair<std::int64_t, SessionEntry>> all() const;
  void remove(std::int64_t id);

  [[noreturn]] void fail(const std::string& what) const;
  sqlite3* db() const { return db_; }

 private:
  void exec(const std::string& sql, const std::string& what);
  std::string location_;
  sqlite3* db_ = nullptr;
};

}  // namespace dentsph::report
