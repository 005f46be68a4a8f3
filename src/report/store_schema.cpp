// The session store's migrations (store_schema.hpp). Plain SQL that SQLite and PostgreSQL both
// read: TEXT, BIGINT, no engine-specific types.
#include "report/store_schema.hpp"

namespace dentsph::report {

const std::vector<Migration>& store_migrations() {
  static const std::vector<Migration> m = {
      {1, "sessions: who, which exercise, when, where its files are, its summary and procedure",
       "CREATE TABLE sessions ("
       "  id INTEGER PRIMARY KEY,"
       "  student TEXT NOT NULL DEFAULT '',"
       "  exercise TEXT NOT NULL DEFAULT '',"
       "  finished_at TEXT NOT NULL DEFAULT '',"
       "  folder TEXT NOT NULL DEFAULT '',"
       "  recording TEXT NOT NULL DEFAULT '',"
       "  report TEXT NOT NULL DEFAULT '',"
       "  summary TEXT NOT NULL,"
       "  procedure TEXT NOT NULL DEFAULT ''"
       ");"
       "CREATE INDEX sessions_by_student ON sessions (student, finished_at);"
       "CREATE INDEX sessions_by_exercise ON sessions (exercise, finished_at)"},
  };
  return m;
}

int current_store_version() { return store_migrations().back().version; }

}  // namespace dentsph::report
