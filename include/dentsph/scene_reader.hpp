// Typed access to the JSON objects of a scene file, with the path of every field kept for error
// messages. Every problem becomes a SceneError reading "<source>: <path>: <problem>; <fix>". The
// scene files, procedure files and the viewer's input scripts are read with it.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "dentsph/vec3.hpp"

namespace dentsph::scene {

using Json = nlohmann::json;

// Throws SceneError "<source>: <path>: <problem>; <fix>".
[[noreturn]] void fail(std::string_view source, std::string_view path, std::string_view problem,
                       std::string_view fix);

// Which numbers a field accepts (beyond being finite).
enum class Range { any, positive, non_negative };

// One JSON object of the scene at `path` ("" for the top level, "blocks[2]", "materials.paste").
// Each accessor takes the field's key and a `hint` that completes "give <hint>" in the fix, so
// it should say what the field is, its unit and a typical value.
class Reader {
 public:
  // Refuses anything but a JSON object; `what` names it in that message ("a block").
  Reader(const Json& object, std::string path, std::string source, std::string_view what);

  const std::string& path() const { return path_; }
  const std::string& source() const { return source_; }
  // "blocks[2]" + "spacing" -> "blocks[2].spacing".
  std::string path_of(std::string_view key) const;
  // A reader for element `index` of the array field `key` ("blocks" -> "blocks[3]").
  Reader element(const Json& array, std::string_view key, std::size_t index,
                 std::string_view what) const;

  // Refuses every key of the object not in `known`, naming the closest known one (catches
  // typos: an unknown field is an error, never silently ignored).
  void only(const std::vector<std::string_view>& known) const;

  bool has(std::string_view key) const { return object_.contains(key); }
  // The raw value, or nullptr when absent.
  const Json* find(std::string_view key) const;

  [[noreturn]] void fail(std::string_view key, std::string_view problem,
                         std::string_view fix) const;
  [[noreturn]] void fail_here(std::string_view problem, std::string_view fix) const;

  // Required fields: missing, wrong type, non-finite or out of range is an error.
  real number(std::string_view key, std::string_view hint, Range range = Range::any) const;
  // A number within [lo, hi] (the physical bounds of a field whose value past them is finite but
  // overflows or vanishes in a step).
  real number_in(std::string_view key, std::string_view hint, real lo, real hi) const;
  Vec3 vec3(std::string_view key, std::string_view hint) const;
  std::int64_t integer(std::string_view key, std::string_view hint, std::int64_t lo,
                       std::int64_t hi) const;
  std::string string(std::string_view key, std::string_view hint) const;
  Reader object(std::string_view key, std::string_view hint) const;
  // A required array with at least one element.
  const Json& array(std::string_view key, std::string_view hint) const;

  // Optional fields: absent gives the fallback (or nullopt); present must be valid.
  real number_or(std::string_view key, real fallback, std::string_view hint,
                 Range range = Range::any) const;
  std::optional<real> optional_number(std::string_view key, std::string_view hint,
                                      Range range = Range::any) const;
  Vec3 vec3_or(std::string_view key, Vec3 fallback, std::string_view hint) const;
  std::optional<Vec3> optional_vec3(std::string_view key, std::string_view hint) const;
  std::int64_t integer_or(std::string_view key, std::int64_t fallback, std::string_view hint,
                          std::int64_t lo, std::int64_t hi) const;
  bool boolean_or(std::string_view key, bool fallback, std::string_view hint) const;
  std::optional<std::string> optional_string(std::string_view key, std::string_view hint) const;
  std::optional<Reader> optional_object(std::string_view key, std::string_view hint) const;

  // Checks a value already taken from the object (used for array elements and the accessors).
  real as_number(const Json& v, std::string_view key, std::string_view hint, Range range) const;

 private:
  const Json& require(std::string_view key, std::string_view hint) const;

  const Json& object_;
  std::string path_;
  std::string source_;
};

// The JSON of `text`; a syntax error is a SceneError naming `source` and the line and column
// (scene_json.cpp).
Json parse_json(const std::string& text, const std::string& source);

// The known name closest to `name` when close enough to be a likely typo, else "".
std::string_view closest(std::string_view name, const std::vector<std::string_view>& known);

// A short rendering of a JSON value for messages ("a string \"abc\"", "an array of 2").
std::string describe(const Json& v);

}  // namespace dentsph::scene
