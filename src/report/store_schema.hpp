// The session store's schema, as the ordered list of migrations that build it: the one place the
// tables are defined. A store at version N runs migrations N+1... in one transaction each.
#pragma once

#include <vector>

namespace dentsph::report {

struct Migration {
  int version;       // 1, 2, ... the schema's version once applied
  const char* what;  // for a person
  const char* sql;   // statements separated by ';'
};

// Every migration, in order; the last one's version is the current schema.
const std::vector<Migration>& store_migrations();
int current_store_version();

}  // namespace dentsph::report
