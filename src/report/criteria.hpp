// The criteria a tutor judges a filling by, each with the number behind it (as summary.json or
// procedure.json hold it), a plain verdict and the rule that gives it; and the haptic loop's
// health for realtime sessions. The thresholds are documented in docs/report.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dentsph::report {

enum class Verdict { good, needs_work, not_measured };
const char* verdict_name(Verdict v);  // "good", "needs work", "not measured"

struct Criterion {
  std::string id;                // "fill", "voids", ... (a CSV column, a class report's row)
  std::string label;             // what a tutor reads: "Cavity filled"
  std::string key;               // where the number is: "assessment.fill_fraction" in summary.json,
                                 // "procedure:increments" in procedure.json
  std::optional<double> value;   // the number as the file holds it (none: not measured)
  std::string shown;             // the number as the page shows it: "98.1 %"
  Verdict verdict = Verdict::not_measured;
  std::string rule;              // when it is good: "95 % or more"
  std::string advice;            // what to tell the student when it needs work
  std::vector<std::string> details;  // e.g. each void's place
};

// The thresholds (docs/report.md gives the reasons).
struct Thresholds {
  double fill_min = 0.95;               // share of the cavity filled
  double overfill_max_share = 0.25;     // overfill against the cavity's volume
  double increment_max_mm = 2.0;        // thickest increment (90th percentile of its columns)
  double mean_force_max_share = 0.5;    // mean device force against the device's limit
  double default_device_limit_N = 9.0;  // without a realtime device: the Novint Falcon (falcon profile)
  // Haptic loop health.
  double rate_tolerance = 0.01;         // achieved rate within 1 % of the target
  double period_p99_max_share = 1.5;    // period p99 against the nominal period
  double deadline_miss_max_share = 1e-3;  // missed deadlines against ticks
  double force_age_p99_max_us = 10000;  // the force a hand feels answers a pose at most 10 ms old
};

// The filling's criteria from summary.json's "assessment" (and "tool", "haptic.profile") and
// procedure.json's "increments" (null: not measured).
std::vector<Criterion> filling_criteria(const nlohmann::json& summary, const nlohmann::json& procedure,
                                        const Thresholds& t = {});
// The light curing's criteria from summary.json's "cure" (cure_assessment_json): one per increment,
// good when it is adequately cured throughout (bottom/top conversion at least the criterion, 0.8),
// its message (thickness, the dose at its base, the share under-cured) as its detail. Empty when the
// run did not cure.
std::vector<Criterion> cure_criteria(const nlohmann::json& summary);
// The haptic loop's health from summary.json's "haptic" section (empty for an offline run).
std::vector<Criterion> haptic_criteria(const nlohmann::json& summary, const Thresholds& t = {});

// The device's force limit a session is judged against (N) and its name for a person.
double device_limit_N(const nlohmann::json& summary, const Thresholds& t = {});
std::string device_limit_name(const nlohmann::json& summary);

// A number of a JSON object by a dotted path ("assessment.fill_fraction"; an array's element by its
// index: "cure.increments.0.thickness_mm"); none when absent or not a number.
std::optional<double> number_at(const nlohmann::json& j, const std::string& path);

}  // namespace dentsph::report
