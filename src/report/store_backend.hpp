// What a session store keeps sessions in: an embedded SQLite file (sqlite_store.cpp) or a
// PostgreSQL server (postgres_store.cpp). Both build their tables from store_schema.hpp.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dentsph/report/class_report.hpp"

namespace dentsph::report {

class StoreBackend {
 public:
  virtual ~StoreBackend() = default;
  // The new session's id.
  virtual std::int64_t add(const SessionEntry& session) = 0;
  // `student` and `exercise` empty: any; oldest first.
  virtual std::vector<SessionEntry> find(const std::string& student, const std::string& exercise) const = 0;
  virtual int schema_version() const = 0;
  virtual std::size_t pending() const { return 0; }
};

// Both throw StoreError (session_store.hpp) naming `location` when it cannot be opened or
// migrated.
std::unique_ptr<StoreBackend> open_sqlite_store(const std::string& location);

// Sessions as the stores hold them: the row's columns into an entry (the label made from them).
SessionEntry entry_from_row(std::string student, std::string exercise, std::string finished_at, std::string folder,
                            std::string report, const std::string& summary, const std::string& procedure,
                            const std::string& location);
// The recording folder of a session's run folder ("" when it has none).
std::string recording_of(const SessionEntry& e);

}  // namespace dentsph::report
