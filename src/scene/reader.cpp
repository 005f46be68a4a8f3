// Typed, path-tracking access to scene JSON; see reader.hpp.
#include "dentsph/scene_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "dentsph/scene.hpp"

namespace dentsph::scene {

namespace {

// Levenshtein distance, for "did you mean" suggestions on short field names.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string range_problem(real x, Range range) {
  if (range == Range::positive && !(x > 0)) return fmt::format("must be > 0, got {}", x);
  if (range == Range::non_negative && !(x >= 0)) return fmt::format("must be >= 0, got {}", x);
  return {};
}

}  // namespace

std::string_view closest(std::string_view name, const std::vector<std::string_view>& known) {
  std::string_view best;
  std::size_t best_d = std::max<std::size_t>(2, name.size() / 3) + 1;
  for (std::string_view k : known) {
    const std::size_t d = edit_distance(name, k);
    if (d < best_d) best = k, best_d = d;
  }
  return best;
}

void fail(std::string_view source, std::string_view path, std::string_view problem,
          std::string_view fix) {
  throw SceneError(
      fmt::format("{}: {}: {}; {}", source, path.empty() ? "(top level)" : path, problem, fix));
}

std::string describe(const Json& v) {
  switch (v.type()) {
    case Json::value_t::string: {
      std::string s = v.get<std::string>();
      if (s.size() > 40) s = s.substr(0, 37) + "...";
      return fmt::format("a string \"{}\"", s);
    }
    case Json::value_t::array:
      return fmt::format("an array of {}", v.size());
    case Json::value_t::object:
      return "an object";
    case Json::value_t::null:
      return "null";
    default:
      return v.dump();  // numbers and booleans as written
  }
}

Reader::Reader(const Json& object, std::string path, std::string source, std::string_view what)
    : object_(object), path_(std::move(path)), source_(std::move(source)) {
  if (!object_.is_object())
    scene::fail(source_, path_,
                fmt::format("expected {} (a JSON object), got {}", what, describe(object_)),
                "write it as {\"field\": value, ...}");
}

std::string Reader::path_of(std::string_view key) const {
  return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
}

Reader Reader::element(const Json& array, std::string_view key, std::size_t index,
                       std::string_view what) const {
  return Reader(array.at(index), fmt::format("{}[{}]", path_of(key), index), source_, what);
}

void Reader::only(const std::vector<std::string_view>& known) const {
  for (const auto& item : object_.items()) {
    const std::string& key = item.key();
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    const std::string_view guess = closest(key, known);
    const std::string known_list = fmt::format("{}", fmt::join(known, ", "));
    fail(key, "unknown field",
         guess.empty() ? fmt::format("the fields known here are: {}", known_list)
                       : fmt::format("did you mean \"{}\"? The fields known here are: {}", guess,
                                     known_list));
  }
}

const Json* Reader::find(std::string_view key) const {
  const auto it = object_.find(key);
  return it == object_.end() ? nullptr : &*it;
}

void Reader::fail(std::string_view key, std::string_view problem, std::string_view fix) const {
  scene::fail(source_, path_of(key), problem, fix);
}

void Reader::fail_here(std::string_view problem, std::string_view fix) const {
  scene::fail(source_, path_, problem, fix);
}

const Json& Reader::require(std::string_view key, std::string_view hint) const {
  const Json* v = find(key);
  if (v == nullptr) fail(key, "missing", fmt::format("give {}", hint));
  return *v;
}

real Reader::as_number(const Json& v, std::string_view key, std::string_view hint,
                       Range range) const {
  if (!v.is_number())
    fail(key, fmt::format("expected a number, got {}", describe(v)), fmt::format("give {}", hint));
  const real x = v.get<real>();
  if (!std::isfinite(x)) fail(key, "not a finite number", fmt::format("give {}", hint));
  if (const std::string p = range_problem(x, range); !p.empty())
    fail(key, p, fmt::format("give {}", hint));
  return x;
}

real Reader::number(std::string_view key, std::string_view hint, Range range) const {
  return as_number(require(key, hint), key, hint, range);
}

std::optional<real> Reader::optional_number(std::string_view key, std::string_view hint,
                                            Range range) const {
  if (!has(key)) return std::nullopt;
  return number(key, hint, range);
}

real Reader::number_or(std::string_view key, real fallback, std::string_view hint,
                       Range range) const {
  return optional_number(key, hint, range).value_or(fallback);
}

real Reader::number_in(std::string_view key, std::string_view hint, real lo, real hi) const {
  const real x = number(key, hint);
  if (x < lo || x > hi) fail(key, fmt::format("must be in [{:g}, {:g}], got {:g}", lo, hi, x), fmt::format("give {}", hint));
  return x;
}

Vec3 Reader::vec3(std::string_view key, std::string_view hint) const {
  const Json& v = require(key, hint);
  if (!v.is_array() || v.size() != 3)
    fail(key, fmt::format("expected an array of 3 numbers [x, y, z], got {}", describe(v)),
         fmt::format("give {}", hint));
  real c[3];
  for (std::size_t i = 0; i < 3; ++i)
    c[i] = as_number(v[i], fmt::format("{}[{}]", key, i), hint, Range::any);
  return {c[0], c[1], c[2]};
}

std::optional<Vec3> Reader::optional_vec3(std::string_view key, std::string_view hint) const {
  if (!has(key)) return std::nullopt;
  return vec3(key, hint);
}

Vec3 Reader::vec3_or(std::string_view key, Vec3 fallback, std::string_view hint) const {
  return optional_vec3(key, hint).value_or(fallback);
}

std::int64_t Reader::integer(std::string_view key, std::string_view hint, std::int64_t lo,
                             std::int64_t hi) const {
  const real x = number(key, hint);
  // JSON does not distinguish 32 from 32.0; accept either, refuse 32.5.
  if (x != std::floor(x))
    fail(key, fmt::format("expected a whole number, got {}", x), fmt::format("give {}", hint));
  if (x < real(lo) || x > real(hi))
    fail(key, fmt::format("must be in [{}, {}], got {}", lo, hi, x), fmt::format("give {}", hint));
  return std::int64_t(x);
}

std::int64_t Reader::integer_or(std::string_view key, std::int64_t fallback, std::string_view hint,
                                std::int64_t lo, std::int64_t hi) const {
  return has(key) ? integer(key, hint, lo, hi) : fallback;
}

bool Reader::boolean_or(std::string_view key, bool fallback, std::string_view hint) const {
  const Json* v = find(key);
  if (v == nullptr) return fallback;
  if (!v->is_boolean())
    fail(key, fmt::format("expected true or false, got {}", describe(*v)),
         fmt::format("give {}", hint));
  return v->get<bool>();
}

std::string Reader::string(std::string_view key, std::string_view hint) const {
  const Json& v = require(key, hint);
  if (!v.is_string())
    fail(key, fmt::format("expected a string, got {}", describe(v)), fmt::format("give {}", hint));
  return v.get<std::string>();
}

std::optional<std::string> Reader::optional_string(std::string_view key,
                                                   std::string_view hint) const {
  if (!has(key)) return std::nullopt;
  return string(key, hint);
}

Reader Reader::object(std::string_view key, std::string_view hint) const {
  return Reader(require(key, hint), path_of(key), source_, hint);
}

std::optional<Reader> Reader::optional_object(std::string_view key, std::string_view hint) const {
  if (!has(key)) return std::nullopt;
  return object(key, hint);
}

const Json& Reader::array(std::string_view key, std::string_view hint) const {
  const Json& v = require(key, hint);
  if (!v.is_array())
    fail(key, fmt::format("expected an array, got {}", describe(v)), fmt::format("give {}", hint));
  if (v.empty()) fail(key, "empty", fmt::format("give {}", hint));
  return v;
}

}  // namespace dentsph::scene
