// The fields the report reads, checked (session_fields.hpp).
#include "report/session_fields.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "dentsph/report/session_folder.hpp"

namespace dentsph::report {

namespace {

namespace fs = std::filesystem;

enum class Kind { text, number, count, step, object, list, flag };

// A field by its path: keys parted by '.', a key ending in "[]" a list whose every element the
// rest of the path continues ("assessment.voids[].against"). Every object or list on the way, where
// present, must be one; a field that is absent is the report's to leave out.
struct Field {
  const char* path;
  Kind kind;
};

// Everything session_report.cpp, criteria.cpp, class_report.cpp and session_folder.cpp read of
// summary.json with a type of its own (number_at reads a figure of any type and treats another as
// absent; the figures a report judges are checked for their range below).
constexpr Field kSummaryFields[] = {
    {"scene", Kind::text},
    {"status", Kind::text},
    {"message", Kind::text},
    {"steps", Kind::count},
    {"threads", Kind::count},
    {"sim_time_s", Kind::number},
    {"wall_time_s", Kind::number},
    {"steps_per_second", Kind::number},
    {"session", Kind::object},
    {"session.student", Kind::text},
    {"session.exercise", Kind::text},
    {"session.finished_at", Kind::text},
    {"cavity", Kind::object},
    {"cavity.class", Kind::text},
    {"cavity.side", Kind::text},
    {"cavity.width_mm", Kind::number},
    {"cavity.length_mm", Kind::number},
    {"cavity.depth_mm", Kind::number},
    {"cavity.volume_mm3", Kind::number},
    {"particles", Kind::object},
    {"particles.material", Kind::count},
    {"particles.boundary", Kind::count},
    {"particles.tool", Kind::count},
    {"tool", Kind::object},
    {"tool.force_scale", Kind::number},
    {"device", Kind::object},
    {"device.name", Kind::text},
    {"haptic", Kind::object},
    {"haptic.profile", Kind::object},
    {"haptic.profile.name", Kind::text},
    {"assessment", Kind::object},
    {"assessment.voids", Kind::list},
    {"assessment.voids[]", Kind::object},
    {"assessment.voids[].against", Kind::text},
    {"assessment.voids[].centre_mm", Kind::list},
    {"assessment.voids[].volume_mm3", Kind::number},
    {"assessment.voids[].wall_distance_mm", Kind::number},
    {"cure", Kind::object},
    {"cure.message", Kind::text},
    {"cure.light_on_s", Kind::number},
    {"cure.criterion_bottom_top", Kind::number},
    {"cure.increments", Kind::list},
    {"cure.increments[]", Kind::object},
    {"cure.increments[].increment", Kind::count},
    {"cure.increments[].message", Kind::text},
    {"cure.increments[].thickness_mm", Kind::number},
    {"cure.increments[].bottom_top_ratio", Kind::number},
    {"cure.increments[].top_dose_J_per_cm2", Kind::number},
    {"cure.increments[].base_dose_J_per_cm2", Kind::number},
    {"cure.increments[].top_conversion", Kind::number},
    {"cure.increments[].base_conversion", Kind::number},
    {"grading", Kind::object},
    {"grading.anatomic_form", Kind::object},
    {"grading.anatomic_form.measured", Kind::flag},
    {"grading.anatomic_form.why_not", Kind::text},
    {"grading.anatomic_form.band", Kind::text},
    {"grading.marginal_adaptation", Kind::object},
    {"grading.marginal_adaptation.measured", Kind::flag},
    {"grading.marginal_adaptation.why_not", Kind::text},
    {"grading.marginal_adaptation.defects", Kind::list},
    {"grading.marginal_adaptation.defects[]", Kind::object},
    {"grading.marginal_adaptation.defects[].kind", Kind::text},
    {"grading.marginal_adaptation.defects[].centre_mm", Kind::list},
    {"grading.marginal_adaptation.defects[].length_mm", Kind::number},
    {"grading.marginal_adaptation.defects[].largest_step_mm", Kind::number},
    {"grading.proximal", Kind::object},
    {"grading.proximal.measured", Kind::flag},
    {"grading.proximal.why_not", Kind::text},
    {"grading.proximal.side", Kind::text},
    {"grading.proximal.contact", Kind::text},
    {"grading.surface_voids", Kind::object},
    {"grading.surface_voids.measured", Kind::flag},
    {"grading.surface_voids.why_not", Kind::text},
    {"grading.surface_voids.pits", Kind::list},
    {"grading.surface_voids.pits[]", Kind::object},
    {"grading.surface_voids.pits[].centre_mm", Kind::list},
    {"grading.surface_voids.pits[].volume_mm3", Kind::number},
    {"grading.surface_voids.pits[].depth_mm", Kind::number},
};

// Everything session_folder.cpp and criteria.cpp read of procedure.json.
constexpr Field kProcedureFields[] = {
    {"events", Kind::list},
    {"events[]", Kind::object},
    {"events[].kind", Kind::text},
    {"events[].source", Kind::text},
    {"events[].tool", Kind::text},
    {"events[].step", Kind::step},
    {"events[].t_s", Kind::number},
    {"increments", Kind::list},
    {"increments[]", Kind::object},
    {"increments[].index", Kind::count},
    {"increments[].particles", Kind::count},
    {"increments[].thickness_median_mm", Kind::number},
    {"increments[].thickness_p90_mm", Kind::number},
};

const char* kind_name(Kind k) {
  switch (k) {
    case Kind::text: return "a text";
    case Kind::number: return "a number";
    case Kind::count: return "a whole number from 0 to 2147483647";
    case Kind::step: return "a step number from 0 to 2^53";
    case Kind::object: return "an object";
    case Kind::list: return "a list";
    case Kind::flag: return "true or false";
  }
  return "?";
}

bool whole_within(const nlohmann::json& v, double hi) {
  if (!v.is_number()) return false;
  const double x = v.get<double>();
  return x >= 0 && x <= hi && std::floor(x) == x;
}

bool is_kind(const nlohmann::json& v, Kind k) {
  switch (k) {
    case Kind::text: return v.is_string();
    case Kind::number: return v.is_number();
    case Kind::count: return whole_within(v, 2147483647.0);
    case Kind::step: return whole_within(v, 9007199254740992.0);
    case Kind::object: return v.is_object();
    case Kind::list: return v.is_array();
    case Kind::flag: return v.is_boolean();
  }
  return false;
}

[[noreturn]] void refuse(const fs::path& file, const std::string& where, const nlohmann::json& v, const char* want) {
  std::string shown = v.dump();
  if (shown.size() > 60) shown = shown.substr(0, 57) + "...";
  throw SessionError(fmt::format("{}: {} is {}, not {}: the file was changed after the run (or is not dentsph's); run "
                                 "the session again",
                                 file.string(), where, shown, want));
}

// Checks the field `rest` (the rest of its path) below `at`, reached by `where`.
void check_at(const fs::path& file, const nlohmann::json& at, std::string_view rest, const std::string& where, Kind kind) {
  const std::size_t dot = rest.find('.');
  std::string_view key = rest.substr(0, dot);
  const bool each = key.size() > 2 && key.substr(key.size() - 2) == "[]";
  if (each) key.remove_suffix(2);
  const auto it = at.find(std::string(key));
  if (it == at.end()) return;
  const std::string here = where.empty() ? std::string(key) : where + "." + std::string(key);
  const bool last = dot == std::string_view::npos;
  if (!each) {
    if (last) {
      if (!is_kind(*it, kind)) refuse(file, here, *it, kind_name(kind));
    } else {
      if (!it->is_object()) refuse(file, here, *it, kind_name(Kind::object));
      check_at(file, *it, rest.substr(dot + 1), here, kind);
    }
    return;
  }
  if (!it->is_array()) refuse(file, here, *it, kind_name(Kind::list));
  for (std::size_t k = 0; k < it->size(); ++k) {
    const nlohmann::json& e = (*it)[k];
    const std::string element = fmt::format("{}[{}]", here, k);
    if (last) {
      if (!is_kind(e, kind)) refuse(file, element, e, kind_name(kind));
    } else {
      if (!e.is_object()) refuse(file, element, e, kind_name(Kind::object));
      check_at(file, e, rest.substr(dot + 1), element, kind);
    }
  }
}

template <std::size_t N>
void check_fields(const fs::path& file, const nlohmann::json& j, const Field (&fields)[N]) {
  if (!j.is_object()) refuse(file, "the file", j, kind_name(Kind::object));
  for (const Field& f : fields) check_at(file, j, f.path, "", f.kind);
}

// The figures a report judges, each within what a run can write: a summary changed by hand (a fill
// of 1e308 showed as "inf % good", -5 as "-500.0 %") is refused, naming the file and the field.
void check_figures(const fs::path& file, const nlohmann::json& summary) {
  struct Range {
    const char* path;
    double lo, hi;
  };
  constexpr double kMax = 1e12;
  static const Range kRanges[] = {
      {"assessment.fill_fraction", 0, 1},           {"assessment.void_count", 0, kMax},
      {"assessment.void_volume_mm3", 0, kMax},      {"assessment.overfill_mm3", 0, kMax},
      {"assessment.cavity_volume_mm3", 0, kMax},    {"assessment.leaked_particles", 0, kMax},
      {"assessment.lost_particles", 0, kMax},       {"assessment.peak_device_force_N", 0, kMax},
      {"assessment.mean_device_force_N", 0, kMax},  {"tool.peak_device_force_N", 0, kMax},
      {"tool.force_scale", 0, kMax},                {"assessment.pore_count", 0, kMax},
      {"assessment.pore_volume_mm3", 0, kMax},      {"assessment.min_void_mm3", 0, kMax},
      {"grading.anatomic_form.p95_abs_mm", 0, kMax}, {"grading.anatomic_form.rms_mm", 0, kMax},
      {"grading.marginal_adaptation.sites", 0, kMax}, {"grading.marginal_adaptation.largest_site_mm", 0, kMax},
      {"grading.marginal_adaptation.length_mm", 0, kMax}, {"grading.marginal_adaptation.max_sites", 0, kMax},
      {"grading.marginal_adaptation.max_site_mm", 0, kMax}, {"grading.proximal.gap_mm", -kMax, kMax},
      {"grading.proximal.overhang_mm", -kMax, kMax}, {"grading.proximal.overhang_area_mm2", 0, kMax},
      {"grading.surface_voids.count", 0, kMax}, {"grading.surface_voids.volume_mm3", 0, kMax},
  };
  for (const Range& r : kRanges) {
    // Present but not a number, or a number out of range (JSON has no NaN; an overflowed literal
    // such as 1e999 reads as infinity).
    std::string pointer = std::string("/") + r.path;
    std::replace(pointer.begin(), pointer.end(), '.', '/');
    const nlohmann::json::json_pointer at(pointer);
    if (!summary.contains(at)) continue;
    const nlohmann::json& v = summary.at(at);
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < r.lo || v.get<double>() > r.hi)
      refuse(file, r.path, v, fmt::format("a number in [{:g}, {:g}]", r.lo, r.hi).c_str());
  }
}

}  // namespace

void check_summary_fields(const fs::path& file, const nlohmann::json& summary) {
  check_fields(file, summary, kSummaryFields);
  check_figures(file, summary);
}

void check_procedure_fields(const fs::path& file, const nlohmann::json& procedure) {
  check_fields(file, procedure, kProcedureFields);
}

}  // namespace dentsph::report
