// The session store's schema, as the ordered list of migrations that build it: the one place the
// tables are defined. A store at version N runs migrations N+1... in one transaction each.
#pragma once

#include <string>
#include <vector>

namespace dentsph::report {

struct Migration {
  int version;       // 1, 2, ... the schema's version once applied
  const char* what;  // for a person
  const char* sql;   // statements separated by ';'; {id} stands for the dialect's key column
};

enum class SqlDialect { sqlite, postgresql };
// A migration's SQL for a database: {id} becomes "INTEGER PRIMARY KEY" (SQLite's row id) or
// "BIGSERIAL PRIMARY KEY" (PostgreSQL). Everything else is plain SQL both read.
std::string migration_sql(const Migration& m, SqlDialect d);

// Every migration, in order; the last one's version is the current schema.
const std::vector<Migration>& store_migrations();
int current_store_version();

}  // namespace dentsph::report
