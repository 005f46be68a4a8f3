// The PostgreSQL session store (postgres_store.hpp).
#include "report/postgres_store.hpp"

#include <libpq-fe.h>

#include <functional>

#include <fmt/format.h>

#include "dentsph/report/session_store.hpp"
#include "report/sqlite_store.hpp"
#include "report/store_schema.hpp"

namespace dentsph::report {

namespace {

// A query's result, cleared on every path.
struct Result {
  PGresult* r = nullptr;
  explicit Result(PGresult* res) : r(res) {}
  ~Result() { PQclear(r); }
  Result(const Result&) = delete;
  Result& operator=(const Result&) = delete;
  bool ok() const {
    const ExecStatusType s = PQresultStatus(r);
    return s == PGRES_COMMAND_OK || s == PGRES_TUPLES_OK;
  }
};

class PostgresStore final : public StoreBackend {
 public:
  PostgresStore(std::string location, std::filesystem::path spool)
      : location_(std::move(location)), spool_file_(std::move(spool)) {
    // Unreachable now: a session added later is kept in the spool, whose folder must be there (said
    // now, before a run, rather than after it).
    if (!reach()) make_spool_folder();
  }
  ~PostgresStore() override {
    if (conn_) PQfinish(conn_);
  }

  std::int64_t add(const SessionEntry& e) override {
    if (reach()) {
      if (const std::int64_t id = insert(e)) return id;
    }
    spool().add(e);  // unreachable, or lost mid-write: kept, sent later
    return 0;
  }

  std::vector<SessionEntry> find(const std::string& student, const std::string& exercise) const override {
    if (!reach())
      throw StoreError(fmt::format("{}: the server cannot be reached ({}); start it or check the address",
                                   masked_location(location_), last_error_));
    const char* params[] = {student.c_str(), exercise.c_str()};
    Result r(PQexecParams(conn_,
                          "SELECT student, exercise, finished_at, folder, report, summary, procedure FROM sessions "
                          "WHERE ($1 = '' OR student = $1) AND ($2 = '' OR exercise = $2) ORDER BY finished_at, id",
                          2, nullptr, params, nullptr, nullptr, 0));
    if (!r.ok()) fail("reading the sessions");
    std::vector<SessionEntry> out;
    for (int i = 0; i < PQntuples(r.r); ++i)
      out.push_back(entry_from_row(PQgetvalue(r.r, i, 0), PQgetvalue(r.r, i, 1), PQgetvalue(r.r, i, 2),
                                   PQgetvalue(r.r, i, 3), PQgetvalue(r.r, i, 4), PQgetvalue(r.r, i, 5),
                                   PQgetvalue(r.r, i, 6), location_));
    return out;
  }

  int schema_version() const override {
    if (!reach())
      throw StoreError(fmt::format("{}: the server cannot be reached ({})", masked_location(location_), last_error_));
    Result r(PQexec(conn_, "SELECT version FROM schema_version"));
    return r.ok() && PQntuples(r.r) > 0 ? std::atoi(PQgetvalue(r.r, 0, 0)) : 0;
  }

  std::size_t pending() const override {
    return std::filesystem::exists(spool_file_) ? spool().all().size() : 0;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw StoreError(fmt::format("{}: {}: {}", masked_location(location_), what, conn_ ? PQerrorMessage(conn_) : ""));
  }

  void make_spool_folder() const {
    std::error_code ec;
    std::filesystem::create_directories(spool_file_.parent_path(), ec);
    if (ec)
      throw StoreError(fmt::format("{}: the server cannot be reached ({}), and a session could not be kept locally "
                                   "until it is: the spool folder {} cannot be made ({}); set DENTSPH_STORE_SPOOL to "
                                   "a folder you can write",
                                   masked_location(location_), last_error_, spool_file_.parent_path().string(),
                                   ec.message()));
  }

  SqliteStore& spool() const {
    if (!spool_) {
      make_spool_folder();
      spool_ = std::make_unique<SqliteStore>(spool_file_.string());
    }
    return *spool_;
  }

  // Connected (connecting, migrating and sending the spool when not yet): false when the server
  // cannot be reached.
  bool reach() const {
    if (conn_ && PQstatus(conn_) == CONNECTION_OK) return true;
    if (conn_) PQfinish(conn_);
    const char* keys[] = {"dbname", "connect_timeout", nullptr};
    const char* values[] = {location_.c_str(), "5", nullptr};
    conn_ = PQconnectdbParams(keys, values, 1);
    if (!conn_ || PQstatus(conn_) != CONNECTION_OK) {
      last_error_ = conn_ ? PQerrorMessage(conn_) : "out of memory";
      while (!last_error_.empty() && (last_error_.back() == '\n' || last_error_.back() == ' ')) last_error_.pop_back();
      if (conn_) PQfinish(conn_);
      conn_ = nullptr;
      return false;
    }
    PQsetNoticeProcessor(conn_, [](void*, const char*) {}, nullptr);  // CREATE ... IF NOT EXISTS notices
    migrate();
    send_spool();
    return true;
  }

  void exec(const std::string& sql, const std::string& what) const {
    Result r(PQexec(conn_, sql.c_str()));
    if (!r.ok()) {
      const std::string msg = PQerrorMessage(conn_);
      Result rollback(PQexec(conn_, "ROLLBACK"));
      throw StoreError(fmt::format("{}: {}: {}", masked_location(location_), what, msg));
    }
  }

  // The schema brought to the current version in one transaction, under an advisory lock so that
  // workstations opening the store at once migrate it once.
  void migrate() const {
    exec("BEGIN", "starting the schema");
    exec("SELECT pg_advisory_xact_lock(730317)", "locking the schema");
    exec("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)", "creating the schema's version");
    exec("INSERT INTO schema_version (version) SELECT 0 WHERE NOT EXISTS (SELECT 1 FROM schema_version)",
         "starting the schema");
    Result v(PQexec(conn_, "SELECT version FROM schema_version"));
    const int have = v.ok() && PQntuples(v.r) > 0 ? std::atoi(PQgetvalue(v.r, 0, 0)) : 0;
    if (have > current_store_version()) {
      exec("ROLLBACK", "leaving the schema");
      throw StoreError(fmt::format("{}: the store's schema is version {}, newer than this program's {}: use a newer "
                                   "dentsph", masked_location(location_), have, current_store_version()));
    }
    for (const Migration& m : store_migrations()) {
      if (m.version <= have) continue;
      exec(migration_sql(m, SqlDialect::postgresql), fmt::format("migration {} ({})", m.version, m.what));
      exec(fmt::format("UPDATE schema_version SET version = {}", m.version), "recording the migration");
    }
    exec("COMMIT", "committing the schema");
  }

  // The new row's id, or 0 when the connection was lost (the caller spools the session).
  std::int64_t insert(const SessionEntry& e) const {
    const std::string summary = e.summary.dump(), procedure = e.procedure.is_null() ? "" : e.procedure.dump();
    const std::string recording = recording_of(e);
    const char* params[] = {e.student.c_str(),   e.exercise.c_str(), e.finished_at.c_str(), e.folder.c_str(),
                            recording.c_str(),   e.report.c_str(),   summary.c_str(),       procedure.c_str()};
    Result r(PQexecParams(conn_,
                          "INSERT INTO sessions (student, exercise, finished_at, folder, recording, report, summary, "
                          "procedure) VALUES ($1, $2, $3, $4, $5, $6, $7, $8) RETURNING id",
                          8, nullptr, params, nullptr, nullptr, 0));
    if (r.ok() && PQntuples(r.r) == 1) return std::atoll(PQgetvalue(r.r, 0, 0));
    // The connection lost (no SQLSTATE: the client saw it go; class 08: connection exception;
    // 57P: the server shutting down), as opposed to a query the server refused.
    const char* state = PQresultErrorField(r.r, PG_DIAG_SQLSTATE);
    const std::string code = state ? state : "";
    if (PQstatus(conn_) != CONNECTION_OK || code.empty() || code.rfind("08", 0) == 0 || code.rfind("57P", 0) == 0) {
      last_error_ = PQerrorMessage(conn_);
      PQfinish(conn_);
      conn_ = nullptr;
      return 0;
    }
    fail("adding a session");
  }

  // What the spool holds, oldest first, each removed once the server has it.
  void send_spool() const {
    if (!std::filesystem::exists(spool_file_)) return;
    for (const auto& [id, e] : spool().all()) {
      if (!insert(e)) return;  // lost again: the rest waits
      spool().remove(id);
    }
  }

  std::string location_;
  std::filesystem::path spool_file_;
  // The connection, made (again) when a query needs it: a const query may connect.
  mutable PGconn* conn_ = nullptr;
  mutable std::string last_error_;
  mutable std::unique_ptr<SqliteStore> spool_;
};

}  // namespace

std::filesystem::path postgres_spool_file(const std::string& location, const std::filesystem::path& spool_dir) {
  return spool_dir / fmt::format("pending-{:016x}.sqlite", std::hash<std::string>{}(location));
}

std::unique_ptr<StoreBackend> open_postgres_store(const std::string& location, const std::filesystem::path& spool_dir) {
  return std::make_unique<PostgresStore>(location, postgres_spool_file(location, spool_dir));
}

}  // namespace dentsph::report
