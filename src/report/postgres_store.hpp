// The session store on a PostgreSQL server (Debian's libpq), shared by many workstations. What
// the server cannot take, because it is unreachable or the connection is lost mid-write, is kept
// in a local SQLite spool (one file per server address under the spool folder) and sent, oldest
// first, the next time the store reaches the server (opening it, or adding another session).
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "report/store_backend.hpp"

namespace dentsph::report {

std::unique_ptr<StoreBackend> open_postgres_store(const std::string& location, const std::filesystem::path& spool_dir);

// The spool file a server address keeps its unsent sessions in.
std::filesystem::path postgres_spool_file(const std::string& location, const std::filesystem::path& spool_dir);

}  // namespace dentsph::report
