// The SQLite session store (sqlite_store.hpp).
#include "report/sqlite_store.hpp"

#include <sqlite3.h>

#include <fmt/format.h>

#include "dentsph/report/session_store.hpp"
#include "report/store_schema.hpp"

namespace dentsph::report {

namespace {

constexpr int kBusyTimeoutMs = 5000;

// A prepared statement, finalised on every path.
struct Statement {
  sqlite3_stmt* st = nullptr;
  Statement(const SqliteStore& s, const char* sql) {
    if (sqlite3_prepare_v2(s.db(), sql, -1, &st, nullptr) != SQLITE_OK) s.fail("preparing a query");
  }
  ~Statement() { sqlite3_finalize(st); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  void text(int i, const std::string& v) { sqlite3_bind_text(st, i, v.c_str(), int(v.size()), SQLITE_TRANSIENT); }
};

std::string column(sqlite3_stmt* st, int i) {
  const auto* t = reinterpret_cast<const char*>(sqlite3_column_text(st, i));
  return t ? t : "";
}

}  // namespace

void SqliteStore::fail(const std::string& what) const {
  throw StoreError(fmt::format("{}: {}: {}", location_, what, db_ ? sqlite3_errmsg(db_) : "cannot open"));
}

void SqliteStore::exec(const std::string& sql, const std::string& what) {
  char* err = nullptr;
  if (const int rc = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err); rc != SQLITE_OK) {
    const std::string msg = err ? err : "";
    sqlite3_free(err);
    // Another program holding its lock past the busy timeout: not a question of what the file is.
    if ((rc & 0xff) == SQLITE_BUSY || (rc & 0xff) == SQLITE_LOCKED)
      throw StoreError(fmt::format("{}: the session store is locked by another program (waited {} s); close it, or "
                                   "run again when it is done ({})",
                                   location_, kBusyTimeoutMs / 1000, msg));
    throw StoreError(fmt::format("{}: {}: {}", location_, what, msg));
  }
}

int SqliteStore::schema_version() const {
  Statement st(*this, "SELECT version FROM schema_version");
  return sqlite3_step(st.st) == SQLITE_ROW ? sqlite3_column_int(st.st, 0) : 0;
}

SqliteStore::SqliteStore(std::string location) : location_(std::move(location)) {
  if (sqlite3_open_v2(location_.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
    const std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw StoreError(fmt::format("{}: cannot open the session store ({}); give a writable file", location_, msg));
  }
  sqlite3_busy_timeout(db_, kBusyTimeoutMs);  // another workstation's write: wait for it
  try {
    exec("BEGIN IMMEDIATE", "not a session store (is it another program's database?)");
    exec("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)",
         "not a session store (is it another program's database?)");
    {
      Statement has(*this, "SELECT COUNT(*) FROM schema_version");
      const bool empty = sqlite3_step(has.st) == SQLITE_ROW && sqlite3_column_int(has.st, 0) == 0;
      if (empty) exec("INSERT INTO schema_version (version) VALUES (0)", "starting the schema");
    }
    const int have = schema_version();
    if (have > current_store_version())
      throw StoreError(fmt::format("{}: the store's schema is version {}, newer than this program's {}: use a newer "
                                   "dentsph", location_, have, current_store_version()));
    // Every migration the store lacks, in the one transaction that holds the write lock.
    for (const Migration& m : store_migrations()) {
      if (m.version <= have) continue;
      exec(migration_sql(m, SqlDialect::sqlite), fmt::format("migration {} ({})", m.version, m.what));
      exec(fmt::format("UPDATE schema_version SET version = {}", m.version), "recording the migration");
    }
    exec("COMMIT", "committing the schema");
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    sqlite3_close(db_);
    db_ = nullptr;
    throw;
  }
}

SqliteStore::~SqliteStore() {
  if (db_) sqlite3_close(db_);
}

std::int64_t SqliteStore::add(const SessionEntry& e) {
  Statement st(*this,
               "INSERT INTO sessions (student, exercise, finished_at, folder, recording, report, summary, procedure) "
               "VALUES (?, ?, ?, ?, ?, ?, ?, ?)");
  st.text(1, e.student);
  st.text(2, e.exercise);
  st.text(3, e.finished_at);
  st.text(4, e.folder);
  st.text(5, recording_of(e));
  st.text(6, e.report);
  st.text(7, e.summary.dump());
  st.text(8, e.procedure.is_null() ? std::string() : e.procedure.dump());
  if (sqlite3_step(st.st) != SQLITE_DONE) fail("adding a session");
  return sqlite3_last_insert_rowid(db_);
}

void SqliteStore::remove(std::int64_t id) {
  Statement st(*this, "DELETE FROM sessions WHERE id = ?");
  sqlite3_bind_int64(st.st, 1, id);
  if (sqlite3_step(st.st) != SQLITE_DONE) fail("removing a session");
}

std::vector<std::pair<std::int64_t, SessionEntry>> SqliteStore::all() const {
  Statement st(*this,
               "SELECT id, student, exercise, finished_at, folder, report, summary, procedure FROM sessions ORDER BY id");
  std::vector<std::pair<std::int64_t, SessionEntry>> out;
  int rc;
  while ((rc = sqlite3_step(st.st)) == SQLITE_ROW)
    out.emplace_back(sqlite3_column_int64(st.st, 0),
                     entry_from_row(column(st.st, 1), column(st.st, 2), column(st.st, 3), column(st.st, 4),
                                    column(st.st, 5), column(st.st, 6), column(st.st, 7), location_));
  if (rc != SQLITE_DONE) fail("reading the sessions");
  return out;
}

std::vector<SessionEntry> SqliteStore::find(const std::string& student, const std::string& exercise) const {
  Statement st(*this,
               "SELECT student, exercise, finished_at, folder, report, summary, procedure FROM sessions "
               "WHERE (?1 = '' OR student = ?1) AND (?2 = '' OR exercise = ?2) ORDER BY finished_at, id");
  st.text(1, student);
  st.text(2, exercise);
  std::vector<SessionEntry> out;
  int rc;
  while ((rc = sqlite3_step(st.st)) == SQLITE_ROW)
    out.push_back(entry_from_row(column(st.st, 0), column(st.st, 1), column(st.st, 2), column(st.st, 3),
                                 column(st.st, 4), column(st.st, 5), column(st.st, 6), location_));
  if (rc != SQLITE_DONE) fail("reading the sessions");
  return out;
}

std::unique_ptr<StoreBackend> open_sqlite_store(const std::string& location) {
  return std::make_unique<SqliteStore>(location);
}

}  // namespace dentsph::report
