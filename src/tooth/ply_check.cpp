// check_ply(): a PLY file's header, and its body (ASCII or binary) against it, read before assimp
// sees the file. Assimp 5.2 loops for ever on a header without its end_header line, allocates what the
// header declares whatever the file holds, and asked for gigabytes on an ASCII body that ended
// inside its first vertex with a number of 63 digits (each found by fuzz_mesh: docs/fuzzing.md).
#include "ply_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <vector>

#include "dentsph/tooth.hpp"

namespace dentsph {

namespace {

struct Property {
  bool list = false;
  std::string count_type;  // a list's length's type
  std::string type;        // the value's type (a list's items')
  std::string name;
};

struct Element {
  std::string name;
  double count = 0;
  std::vector<Property> properties;
};

// The largest magnitude a PLY type holds, and whether it holds only whole numbers.
struct Range {
  double max;
  double min;
  bool whole;
};

Range range_of(const std::string& t) {
  if (t == "char" || t == "int8") return {127, -128, true};
  if (t == "uchar" || t == "uint8") return {255, 0, true};
  if (t == "short" || t == "int16") return {32767, -32768, true};
  if (t == "ushort" || t == "uint16") return {65535, 0, true};
  if (t == "int" || t == "int32") return {2147483647.0, -2147483648.0, true};
  if (t == "uint" || t == "uint32") return {4294967295.0, 0, true};
  if (t == "float" || t == "float32") return {FLT_MAX, -FLT_MAX, false};
  return {DBL_MAX, -DBL_MAX, false};  // double, float64
}

// The numbers of an ASCII body, one at a time, with the line each is on.
class BodyNumbers {
 public:
  BodyNumbers(std::istream& in, std::size_t first_line, const std::string& name)
      : buf_(*in.rdbuf()), line_(first_line), name_(name) {}

  std::size_t line() const { return line_; }

  // The next number as text; empty at the end of the file.
  std::string next() {
    std::string token;
    for (int got; (got = buf_.sbumpc()) != std::char_traits<char>::eof();) {
      const char c = char(got);
      if (c == '\n') ++line_;
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
        if (!token.empty()) {
          if (c == '\n') --line_, buf_.sungetc();  // the number ends on the line it began on
          return token;
        }
        continue;
      }
      if (!std::strchr("0123456789+-.eE", c) || c == '\0')
        throw MeshError(fmt::format("{}: line {} of its ASCII PLY body holds a byte that is not part of a number; "
                                    "the file is damaged: export it again",
                                    name_, line_));
      // A number in a PLY file has at most 17 significant digits and an exponent: 32 characters
      // are more than any writer uses.
      if (token.size() == 32)
        throw MeshError(fmt::format("{}: line {} of its ASCII PLY body holds a number of more than 32 characters; "
                                    "the file is damaged: export it again",
                                    name_, line_));
      token += c;
    }
    return token;
  }

 private:
  std::streambuf& buf_;
  std::size_t line_;
  const std::string& name_;
};

// Walks a body as the header declares it: every element's every property, each list as long as
// its length says. `value(e, index, p, type)` reads the next value of `type` (std::nullopt at the
// end of the file); `where()` says where the last one was, for a length that is not a count.
template <class Value, class Where>
void walk_body(const std::vector<Element>& elements, const char* kind, const std::string& name, Value value,
               Where where) {
  for (const Element& e : elements)
    for (double i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        auto next = [&](const std::string& type) {
          const std::optional<double> v = value(e, i, p, type);
          if (!v)
            throw MeshError(fmt::format("{}: its {} PLY body ends before the {} of {} {:.0f} of the {:.0f} its header "
                                        "declares; the file is truncated: export it again",
                                        name, kind, p.name, e.name, i + 1, e.count));
          return *v;
        };
        if (!p.list) {
          next(p.type);
          continue;
        }
        const double length = next(p.count_type);
        if (!(length >= 0) || length != std::floor(length))
          throw MeshError(fmt::format("{}: {} gives the {} of {} {:.0f} a length of {}; the file is damaged: export "
                                      "it again",
                                      name, where(), p.name, e.name, i + 1, length));
        for (double k = 0; k < length; ++k) next(p.type);
      }
}

// An ASCII body: each value a number its type holds; nothing after the last element.
void check_ascii_body(std::istream& in, std::size_t first_line, const std::vector<Element>& elements,
                      const std::string& name) {
  BodyNumbers numbers(in, first_line, name);
  auto read = [&](const Element& e, double index, const Property& p, const std::string& type) -> std::optional<double> {
    const std::string token = numbers.next();
    if (token.empty()) return std::nullopt;
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    const Range r = range_of(type);
    if (end != token.c_str() + token.size() || !std::isfinite(v) || v > r.max || v < r.min ||
        (r.whole && v != std::floor(v)))
      throw MeshError(fmt::format("{}: line {} of its ASCII PLY body holds \"{}\" for the {} of {} {:.0f}, which is "
                                  "not a {} number; the file is damaged: export it again",
                                  name, numbers.line(), token, p.name, e.name, index + 1, type));
    return v;
  };
  walk_body(elements, "ASCII", name, read,
            [&] { return fmt::format("line {} of its ASCII PLY body", numbers.line()); });
  if (const std::string more = numbers.next(); !more.empty())
    throw MeshError(fmt::format("{}: line {} of its ASCII PLY body holds more numbers than its header declares "
                                "(\"{}\" after the last {}); the file is damaged: export it again",
                                name, numbers.line(), more, elements.empty() ? "element" : elements.back().name));
}

// The bytes of a value of a PLY type.
std::size_t size_of(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "double" || t == "float64") return 8;
  return 4;  // int, uint, float and their sized names
}

// The value of a PLY type held in `bytes`, in the file's byte order.
double decode(const unsigned char* bytes, const std::string& t, bool big_endian) {
  unsigned char b[8] = {};
  const std::size_t n = size_of(t);
  for (std::size_t k = 0; k < n; ++k) b[k] = bytes[big_endian ? n - 1 - k : k];
  if (t == "float" || t == "float32") {
    float f;
    std::memcpy(&f, b, 4);
    return f;
  }
  if (t == "double" || t == "float64") {
    double d;
    std::memcpy(&d, b, 8);
    return d;
  }
  std::uint64_t u = 0;
  std::memcpy(&u, b, n);  // little-endian host: the value's low bytes first
  const bool is_signed = t == "char" || t == "int8" || t == "short" || t == "int16" || t == "int" || t == "int32";
  if (is_signed && n < 8 && (u >> (8 * n - 1)) & 1) return double(std::int64_t(u | (~std::uint64_t(0) << (8 * n))));
  return double(u);
}

// A binary body, read once in order: the file long enough for every value.
void check_binary_body(std::istream& in, const std::vector<Element>& elements, bool big_endian,
                       const std::string& name) {
  std::streambuf& buf = *in.rdbuf();
  unsigned char bytes[8];
  auto read = [&](const Element&, double, const Property&, const std::string& type) -> std::optional<double> {
    const std::streamsize n = std::streamsize(size_of(type));
    if (buf.sgetn(reinterpret_cast<char*>(bytes), n) != n) return std::nullopt;
    return decode(bytes, type, big_endian);
  };
  walk_body(elements, "binary", name, read, [] { return std::string("its binary PLY body"); });
}

}  // namespace

std::uint64_t check_ply(const std::filesystem::path& file, const std::string& name, std::uintmax_t size) {
  std::ifstream in(file, std::ios::binary);
  std::string first;
  std::getline(in, first);
  // Assimp takes a .ply file as PLY whatever its first line, and a "ply" of any case as PLY: a file
  // named .ply must begin with the magic line, and any that begins with it is checked.
  std::string magic = first.substr(0, 3);
  for (char& c : magic) c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool ply_name = file.extension() == ".ply";
  if (magic != "ply") {
    if (ply_name)
      throw MeshError(fmt::format("{}: is not a PLY file (its first line is not \"ply\"); export it again as PLY", name));
    return 0;  // not a PLY file: assimp decides
  }
  constexpr std::size_t kMaxHeaderLines = 10000;
  std::vector<Element> elements;
  bool ascii = false, big_endian = false;
  std::string line;
  // Assimp 5.2 looped for ever on headers it half understood ("ehement%vertex 4", "end_header"
  // followed by a vertical tab, found by fuzz_mesh): every header line is printable and one of
  // PLY's, its names plain words, and end_header stands alone on its line.
  auto refuse_line = [&](std::size_t n, const std::string& why) {
    throw MeshError(fmt::format("{}: line {} of its PLY header {}; the file is damaged: export it again", name, n + 2, why));
  };
  // A name begins with a letter or an underscore: assimp 5.2 read "element 9999...9vertex 4" (the
  // digits run into the name) as that many vertices and allocated 100 GB for them (found by
  // fuzz_mesh).
  auto plain = [](const std::string& w) {
    return !w.empty() && !std::isdigit(static_cast<unsigned char>(w[0])) &&
           std::all_of(w.begin(), w.end(), [](unsigned char c) { return std::isalnum(c) || c == '_'; });
  };
  static const char* const types[] = {"char",  "uchar",  "short", "ushort",  "int",     "uint",    "float",  "double",
                                      "int8",  "uint8",  "int16", "uint16",  "int32",   "uint32",  "float32", "float64"};
  auto type = [&](const std::string& w) { return std::find(std::begin(types), std::end(types), w) != std::end(types); };
  for (std::size_t n = 0; n < kMaxHeaderLines && std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string word;
    words >> word;
    const bool text = std::all_of(line.begin(), line.end(), [](unsigned char c) { return c >= 0x20 || c == '\t'; });
    if (!text && !word.empty() && !std::isdigit(static_cast<unsigned char>(word[0])))
      refuse_line(n, "holds a byte that is not text");
    if (word == "end_header" && line != "end_header") refuse_line(n, "has more than end_header on it");
    if (word == "format") {
      std::string f;
      words >> f;
      ascii = f == "ascii";
      big_endian = f == "binary_big_endian";
    } else if (word == "end_header") {
      // Bytes the elements need at the least: one per property of each.
      double declared = 0;
      for (const Element& e : elements) declared += e.count * std::max<double>(1.0, double(e.properties.size()));
      if (declared > double(size))
        throw MeshError(fmt::format("{}: its PLY header declares elements of at least {:.3g} bytes, but the file holds "
                                    "{}; the file is truncated or damaged: export it again",
                                    name, declared, size));
      if (ascii)
        check_ascii_body(in, n + 3, elements, name);
      else
        check_binary_body(in, elements, big_endian, name);
      std::uint64_t faces = 0;
      for (const Element& e : elements)
        if (e.name == "face") faces += std::uint64_t(e.count);
      return faces;
    } else if (word == "element") {
      Element e;
      words >> e.name >> e.count;
      if (!plain(e.name)) refuse_line(n, "names an element that is not a plain word");
      if (!words || !(e.count >= 0)) e.count = 0;
      elements.push_back(std::move(e));
    } else if (word == "property") {
      std::vector<std::string> w;
      for (std::string t; words >> t;) w.push_back(t);
      const bool scalar = w.size() == 2 && type(w[0]) && plain(w[1]);
      const bool list = w.size() == 4 && w[0] == "list" && type(w[1]) && type(w[2]) && plain(w[3]);
      if (!scalar && !list) refuse_line(n, "is not \"property TYPE NAME\" nor \"property list TYPE TYPE NAME\"");
      if (elements.empty()) refuse_line(n, "declares a property before any element");
      elements.back().properties.push_back(
          scalar ? Property{false, "", w[0], w[1]} : Property{true, w[1], w[2], w[3]});
    } else if (!word.empty() && (std::isdigit(static_cast<unsigned char>(word[0])) || word[0] == '-' || word[0] == '.')) {
      break;  // data before end_header
    } else if (word != "comment" && word != "obj_info" && !word.empty()) {
      refuse_line(n, fmt::format("begins with \"{}\", not format, comment, obj_info, element, property or end_header",
                                 word.size() > 40 ? word.substr(0, 40) + "..." : word));
    }
  }
  throw MeshError(fmt::format("{}: is not a complete PLY file (its header has no end_header line); export it again",
                              name));
}

}  // namespace dentsph
