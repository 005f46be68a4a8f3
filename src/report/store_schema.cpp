// The session store's migrations (store_schema.hpp). Plain SQL that SQLite and PostgreSQL both
// read (TEXT columns), but for the key column's type.
#include "report/store_schema.hpp"

namespace dentsph::report {

const std::vector<Migration>& store_migrations() {
  static const std::vector<Migration> m = {
      {1, "sessions: who, which exercise, when, where its files are, its summary and procedure",
       "CREATE TABLE sessions ("
       "  id {id},"
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

std::string migration_sql(const Migration& m, SqlDialect d) {
  std::string sql = m.sql;
  const std::string key = d == SqlDialect::sqlite ? "INTEGER PRIMARY KEY" : "BIGSERIAL PRIMARY KEY";
  for (std::size_t at; (at = sql.find("{id}")) != std::string::npos;) sql.replace(at, 4, key);
  return sql;
}

}  // namespace dentsph::report
