// The SQLite session store (session_store.hpp).
#include "report/session_store.hpp"

#include <sqlite3.h>

#include <algorithm>

#include <fmt/format.h>

#include "report/store_schema.hpp"

namespace dentsph::report {

struct SessionStore::Impl {
  std::string location;
  sqlite3* db = nullptr;

  [[noreturn]] void fail(const std::string& what) const {
    throw StoreError(fmt::format("{}: {}: {}", location, what, db ? sqlite3_errmsg(db) : "cannot open"));
  }
  void exec(const char* sql, const std::string& what) {
    char* err = nullptr;
    if (sqlite3_exec(db, sql, nullptr, nullptr, &err) != SQLITE_OK) {
      const std::string msg = err ? err : "";
      sqlite3_free(err);
      throw StoreError(fmt::format("{}: {}: {}", location, what, msg));
    }
  }
  int version() const {
    sqlite3_stmt* st = nullptr;
    if (sqlite3_prepare_v2(db, "SELECT version FROM schema_version", -1, &st, nullptr) != SQLITE_OK)
      fail("reading the schema's version");
    int v = 0;
    if (sqlite3_step(st) == SQLITE_ROW) v = sqlite3_column_int(st, 0);
    sqlite3_finalize(st);
    return v;
  }
};

namespace {

// A prepared statement, finalised on every path.
struct Statement {
  sqlite3_stmt* st = nullptr;
  Statement(const SessionStore::Impl& s, const char* sql) {
    if (sqlite3_prepare_v2(s.db, sql, -1, &st, nullptr) != SQLITE_OK) s.fail("preparing a query");
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

SessionStore::SessionStore(const std::string& location) : impl_(std::make_unique<Impl>()) {
  impl_->location = location;
  if (location.rfind("postgresql://", 0) == 0 || location.rfind("postgres://", 0) == 0)
    throw StoreError(fmt::format("{}: this build's session store is SQLite only (a PostgreSQL store is not built yet); "
                                 "give a database file, e.g. --db sessions.sqlite",
                                 location));
  if (sqlite3_open_v2(location.c_str(), &impl_->db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
    const std::string msg = impl_->db ? sqlite3_errmsg(impl_->db) : "out of memory";
    sqlite3_close(impl_->db);
    impl_->db = nullptr;
    throw StoreError(fmt::format("{}: cannot open the session store ({}); give a writable file", location, msg));
  }
  sqlite3_busy_timeout(impl_->db, 5000);  // another workstation's write: wait for it
  impl_->exec("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)", "not a session store (is it "
              "another program's database?)");
  if (impl_->version() == 0) {
    Statement has(*impl_, "SELECT COUNT(*) FROM schema_version");
    if (sqlite3_step(has.st) == SQLITE_ROW && sqlite3_column_int(has.st, 0) == 0)
      impl_->exec("INSERT INTO schema_version (version) VALUES (0)", "starting the schema");
  }
  const int have = impl_->version();
  if (have > current_store_version())
    throw StoreError(fmt::format("{}: the store's schema is version {}, newer than this program's {}: use a newer "
                                 "dentsph", location, have, current_store_version()));
  for (const Migration& m : store_migrations()) {
    if (m.version <= have) continue;
    impl_->exec("BEGIN IMMEDIATE", "starting a migration");
    try {
      impl_->exec(m.sql, fmt::format("migration {} ({})", m.version, m.what));
      impl_->exec(fmt::format("UPDATE schema_version SET version = {}", m.version).c_str(), "recording the migration");
      impl_->exec("COMMIT", "committing a migration");
    } catch (...) {
      sqlite3_exec(impl_->db, "ROLLBACK", nullptr, nullptr, nullptr);
      throw;
    }
  }
}

SessionStore::~SessionStore() {
  if (impl_ && impl_->db) sqlite3_close(impl_->db);
}
SessionStore::SessionStore(SessionStore&&) noexcept = default;
SessionStore& SessionStore::operator=(SessionStore&&) noexcept = default;

std::int64_t SessionStore::add(const SessionEntry& e) {
  Statement st(*impl_,
               "INSERT INTO sessions (student, exercise, finished_at, folder, recording, report, summary, procedure) "
               "VALUES (?, ?, ?, ?, ?, ?, ?, ?)");
  const std::string recording =
      !e.folder.empty() && std::filesystem::is_directory(std::filesystem::path(e.folder) / "recording")
          ? (std::filesystem::path(e.folder) / "recording").string()
          : std::string();
  st.text(1, e.student);
  st.text(2, e.exercise);
  st.text(3, e.finished_at);
  st.text(4, e.folder);
  st.text(5, recording);
  st.text(6, e.report);
  st.text(7, e.summary.dump());
  st.text(8, e.procedure.is_null() ? std::string() : e.procedure.dump());
  if (sqlite3_step(st.st) != SQLITE_DONE) impl_->fail("adding a session");
  return sqlite3_last_insert_rowid(impl_->db);
}

std::int64_t SessionStore::add_folder(const std::filesystem::path& dir) {
  SessionEntry e = session_entry(dir);
  e.folder = std::filesystem::absolute(dir).lexically_normal().string();
  if (!e.report.empty()) e.report = std::filesystem::absolute(e.report).lexically_normal().string();
  return add(e);
}

std::vector<SessionEntry> SessionStore::find(const std::string& student, const std::string& exercise) const {
  Statement st(*impl_,
               "SELECT student, exercise, finished_at, folder, report, summary, procedure FROM sessions "
               "WHERE (?1 = '' OR student = ?1) AND (?2 = '' OR exercise = ?2) ORDER BY finished_at, id");
  st.text(1, student);
  st.text(2, exercise);
  std::vector<SessionEntry> out;
  int rc;
  while ((rc = sqlite3_step(st.st)) == SQLITE_ROW) {
    SessionEntry e;
    e.student = column(st.st, 0);
    e.exercise = column(st.st, 1);
    e.finished_at = column(st.st, 2);
    e.folder = column(st.st, 3);
    e.report = column(st.st, 4);
    e.summary = nlohmann::json::parse(column(st.st, 5), nullptr, false);
    if (e.summary.is_discarded())
      throw StoreError(fmt::format("{}: a session's summary is not JSON (folder '{}'); add that session again",
                                   impl_->location, e.folder));
    const std::string proc = column(st.st, 6);
    if (!proc.empty()) e.procedure = nlohmann::json::parse(proc, nullptr, false);
    if (e.procedure.is_discarded()) e.procedure = nullptr;
    const std::string base = e.folder.empty() ? "session" : std::filesystem::path(e.folder).filename().string();
    // "A. Student, 2026-11-22 23:37" (the finished_at's date and minute).
    std::string when = e.finished_at.substr(0, std::min<std::size_t>(16, e.finished_at.size()));
    std::replace(when.begin(), when.end(), 'T', ' ');
    e.label = !e.student.empty() ? (when.empty() ? e.student : e.student + ", " + when) : base;
    out.push_back(std::move(e));
  }
  if (rc != SQLITE_DONE) impl_->fail("reading the sessions");
  return out;
}

int SessionStore::schema_version() const { return impl_->version(); }
const std::string& SessionStore::location() const { return impl_->location; }

}  // namespace dentsph::report
