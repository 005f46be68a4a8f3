// The session store's front (session_store.hpp): which backend, and what they share.
#include "dentsph/report/session_store.hpp"

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <string_view>

#include "dentsph/report/session_folder.hpp"
#include "report/postgres_store.hpp"
#include "report/session_fields.hpp"
#include "report/store_backend.hpp"

namespace dentsph::report {

namespace {

// libpq's connection keywords (a key-value address begins with one: "host=db dbname=dentsph").
constexpr std::string_view kLibpqKeywords[] = {
    "host", "hostaddr", "port", "dbname", "user", "password", "passfile", "connect_timeout", "options",
    "application_name", "sslmode", "sslcert", "sslkey", "sslrootcert", "service", "target_session_attrs"};

bool is_key_value_address(const std::string& l) {
  const std::size_t start = l.find_first_not_of(" \t");
  if (start == std::string::npos) return false;
  const std::size_t eq = l.find('=', start);
  if (eq == std::string::npos) return false;
  std::string key = l.substr(start, eq - start);
  while (!key.empty() && (key.back() == ' ' || key.back() == '\t')) key.pop_back();
  return std::find(std::begin(kLibpqKeywords), std::end(kLibpqKeywords), key) != std::end(kLibpqKeywords);
}

// Each "password=VALUE" (a key-value pair or a URI's query parameter) with VALUE replaced by ***:
// VALUE runs to the next space, tab or '&' (a URI's next parameter), past a part quoted in '...'
// with \' inside.
std::string mask_password_parameters(const std::string& l) {
  std::string out;
  std::size_t k = 0;
  while (true) {
    const std::size_t p = l.find("password", k);
    if (p == std::string::npos) break;
    std::size_t v = p + 8;
    while (v < l.size() && l[v] == ' ') ++v;
    const bool starts_key = p == 0 || l[p - 1] == ' ' || l[p - 1] == '\t' || l[p - 1] == '?' || l[p - 1] == '&';
    if (!starts_key || v >= l.size() || l[v] != '=') {
      out += l.substr(k, p + 8 - k);
      k = p + 8;
      continue;
    }
    ++v;
    while (v < l.size() && l[v] == ' ') ++v;
    std::size_t end = v;
    if (end < l.size() && l[end] == '\'') {
      for (++end; end < l.size() && l[end] != '\''; ++end)
        if (l[end] == '\\') ++end;
      end = std::min(end + 1, l.size());
    }
    // To the next space, tab or '&' (past a closing quote too: what follows it belongs to the value
    // as a second pass would read it, so that the mask masks to itself).
    while (end < l.size() && l[end] != ' ' && l[end] != '\t' && l[end] != '&') ++end;
    out += l.substr(k, v - k) + "***";
    k = end;
  }
  return out + l.substr(k);
}

}  // namespace

bool is_postgres_location(const std::string& l) {
  return l.rfind("postgresql://", 0) == 0 || l.rfind("postgres://", 0) == 0 || is_key_value_address(l);
}

std::string masked_location(const std::string& location) {
  const std::string l = mask_password_parameters(location);
  const std::size_t scheme = l.find("://"), at = l.find('@');
  if (scheme == std::string::npos || at == std::string::npos || at < scheme) return l;
  const std::size_t colon = l.find(':', scheme + 3);
  if (colon == std::string::npos || colon > at) return l;
  return l.substr(0, colon + 1) + "***" + l.substr(at);
}

std::string recording_of(const SessionEntry& e) {
  if (e.folder.empty()) return "";
  const std::filesystem::path r = std::filesystem::path(e.folder) / "recording";
  return std::filesystem::is_directory(r) ? r.string() : "";
}

SessionEntry entry_from_row(std::string student, std::string exercise, std::string finished_at, std::string folder,
                            std::string report, const std::string& summary, const std::string& procedure,
                            const std::string& location) {
  SessionEntry e;
  e.student = std::move(student);
  e.exercise = std::move(exercise);
  e.finished_at = std::move(finished_at);
  e.folder = std::move(folder);
  e.report = std::move(report);
  e.summary = nlohmann::json::parse(summary, nullptr, false);
  if (e.summary.is_discarded())
    throw StoreError(masked_location(location) + ": a session's summary is not JSON (folder '" + e.folder +
                     "'); add that session again");
  if (!procedure.empty()) e.procedure = nlohmann::json::parse(procedure, nullptr, false);
  if (e.procedure.is_discarded()) e.procedure = nullptr;
  // A stored summary is read as a folder's is (session_fields.hpp): a row changed by hand is refused.
  try {
    const std::filesystem::path dir = e.folder.empty() ? std::filesystem::path("session") : std::filesystem::path(e.folder);
    check_summary_fields(dir / "summary.json", e.summary);
    if (!e.procedure.is_null()) check_procedure_fields(dir / "procedure.json", e.procedure);
  } catch (const SessionError& err) {
    throw StoreError(masked_location(location) + ": a stored session: " + err.what() + " and add it again");
  }
  const std::string base = e.folder.empty() ? "session" : std::filesystem::path(e.folder).filename().string();
  // "A. Student, 2026-11-22 23:37" (the finished_at's date and minute).
  std::string when = e.finished_at.substr(0, std::min<std::size_t>(16, e.finished_at.size()));
  std::replace(when.begin(), when.end(), 'T', ' ');
  e.label = !e.student.empty() ? (when.empty() ? e.student : e.student + ", " + when) : base;
  return e;
}

SessionStore::SessionStore(const std::string& location, const std::filesystem::path& spool_dir) : location_(location) {
  if (is_postgres_location(location)) {
    std::filesystem::path spool = spool_dir;
    if (spool.empty()) {
      if (const char* env = std::getenv("DENTSPH_STORE_SPOOL"))
        spool = env;
      else if (const char* home = std::getenv("HOME"))
        spool = std::filesystem::path(home) / ".local" / "state" / "dentsph";
      else
        spool = std::filesystem::temp_directory_path() / "dentsph-spool";
    }
    backend_ = open_postgres_store(location, spool);
  } else {
    backend_ = open_sqlite_store(location);
  }
}

SessionStore::~SessionStore() = default;
SessionStore::SessionStore(SessionStore&&) noexcept = default;
SessionStore& SessionStore::operator=(SessionStore&&) noexcept = default;

std::int64_t SessionStore::add(const SessionEntry& e) { return backend_->add(e); }

std::int64_t SessionStore::add_folder(const std::filesystem::path& dir) {
  SessionEntry e = session_entry(dir);
  e.folder = std::filesystem::absolute(dir).lexically_normal().string();
  if (!e.report.empty()) e.report = std::filesystem::absolute(e.report).lexically_normal().string();
  return add(e);
}

std::vector<SessionEntry> SessionStore::find(const std::string& student, const std::string& exercise) const {
  return backend_->find(student, exercise);
}

int SessionStore::schema_version() const { return backend_->schema_version(); }
std::size_t SessionStore::pending() const { return backend_->pending(); }
const std::string& SessionStore::location() const { return location_; }

}  // namespace dentsph::report
