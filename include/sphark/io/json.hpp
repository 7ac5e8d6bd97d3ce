#pragma once
// A small JSON value, writer and reader for run records (io/run_record.hpp) and the
// configuration files of --config (cli/options.hpp). No JSON library is among the dependencies.
//
//   Json r = Json::Object{};
//   r["program"] = "water_drop";
//   r["options"]["t-end"] = 0.1;        // objects keep their insertion order
//   write_file_atomically(path, to_json_text(r));
//   const Json back = parse_json(text);  // JsonError (line, column, reason) on bad input
//
// Numbers keep the text they were read from (number_text()), so a configuration value reaches
// the option parser exactly as written; a Real is written as the shortest text that reads back
// to the same double (std::to_chars), so every real survives a write and a read bit for bit.
// Non-finite reals have no JSON form and are written as null.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace sphark {

class Json {
 public:
  using Array = std::vector<Json>;
  using Object = std::vector<std::pair<std::string, Json>>;
  enum class Kind { null, boolean, number, string, array, object };

  Json() = default;  // null
  Json(std::nullptr_t) {}
  Json(bool b) : value_(b) {}
  Json(double x);
  Json(int i) : Json(static_cast<long long>(i)) {}
  Json(long i) : Json(static_cast<long long>(i)) {}
  Json(long long i);
  Json(unsigned long i);
  Json(const char* s) : value_(std::string(s)) {}
  Json(std::string s) : value_(std::move(s)) {}
  Json(std::string_view s) : value_(std::string(s)) {}
  Json(Array a) : value_(std::move(a)) {}
  Json(Object o) : value_(std::move(o)) {}
  // A number given by its JSON text (as the reader found it); std::invalid_argument if `text`
  // is not a JSON number.
  static Json number_from_text(std::string text);

  Kind kind() const { return static_cast<Kind>(value_.index()); }
  bool is_null() const { return kind() == Kind::null; }
  bool is_bool() const { return kind() == Kind::boolean; }
  bool is_number() const { return kind() == Kind::number; }
  bool is_string() const { return kind() == Kind::string; }
  bool is_array() const { return kind() == Kind::array; }
  bool is_object() const { return kind() == Kind::object; }

  // Accessors throw std::logic_error for the wrong kind.
  bool as_bool() const;
  double as_number() const;
  const std::string& number_text() const;
  const std::string& as_string() const;
  const Array& as_array() const;
  const Object& as_object() const;
  Array& as_array();
  Object& as_object();

  // Objects: the member `key` or nullptr.
  const Json* find(std::string_view key) const;
  // Objects (a null becomes an empty object): the member `key`, appended as null if absent.
  Json& operator[](std::string_view key);
  // Arrays (a null becomes an empty array).
  void push_back(Json v);

  // Same kind and value: numbers compare by value, objects member by member in order.
  friend bool operator==(const Json& a, const Json& b);

 private:
  struct Number {
    double value = 0;
    std::string text;
  };
  std::variant<std::monostate, bool, Number, std::string, Array, Object> value_;
};

// "name of the kind": "null", "a boolean", "a number", "a string", "an array", "an object".
const char* describe(Json::Kind k);

// JSON text, indented by two spaces per level; arrays of scalars that fit stay on one line.
// Strings are escaped (quote, backslash and control characters; other bytes pass unchanged).
std::string to_json_text(const Json& v);
// The same on one line ("[1, 2]", "\"abc\""): for error messages.
std::string to_json_line(const Json& v);

struct JsonError : std::runtime_error {
  JsonError(int line, int column, const std::string& reason);
  int line, column;
};

// Parses a complete JSON text (RFC 8259; nesting depth at most 256; duplicate object keys are
// an error). Throws JsonError naming the line and column of the first problem.
Json parse_json(std::string_view text);

}  // namespace sphark
