// What the report reads of a run's summary.json and procedure.json, checked before it is read: every
// field it shows has the type a run writes (a text, a number, a count, an object or a list) and every
// figure it judges lies within what a run can write. A file changed by hand (a void's "against" of
// 99999999999, a fill of 1e308, a step count of 1e300) is refused with a SessionError naming the
// file, the field and its value, instead of a library's type error or a count cast out of range.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace dentsph::report {

// Throws SessionError naming `file` and the field.
void check_summary_fields(const std::filesystem::path& file, const nlohmann::json& summary);
void check_procedure_fields(const std::filesystem::path& file, const nlohmann::json& procedure);

}  // namespace dentsph::report
