// The JSON value and its writer (the reader is json_parse.cpp).
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "sphark/io/json.hpp"

namespace sphark {

Json::Json(double x) {
  if (!std::isfinite(x)) return;  // null: JSON has no inf / nan
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);  // shortest text that reads back to x
  value_ = Number{x, std::string(buf, r.ptr)};
}

Json::Json(long long i) : value_(Number{static_cast<double>(i), std::to_string(i)}) {}

Json::Json(unsigned long i) : value_(Number{static_cast<double>(i), std::to_string(i)}) {}

Json Json::number_from_text(std::string text) {
  // RFC 8259: -? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t start = i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
    return i > start;
  };
  bool ok = true;
  if (i < text.size() && text[i] == '-') ++i;
  if (i < text.size() && text[i] == '0') {
    ++i;
  } else {
    ok = digits();
  }
  if (ok && i < text.size() && text[i] == '.') ++i, ok = digits();
  if (ok && i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    ok = digits();
  }
  if (!ok || i != text.size()) throw std::invalid_argument("not a JSON number: '" + text + "'");
  double v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec == std::errc::result_out_of_range) v = std::strtod(text.c_str(), nullptr);  // +-inf or 0
  Json j;
  j.value_ = Number{v, std::move(text)};
  return j;
}

namespace {
[[noreturn]] void wrong_kind(Json::Kind want, Json::Kind have) {
  throw std::logic_error(std::string("Json: expected ") + describe(want) + ", have " + describe(have));
}
}  // namespace

const char* describe(Json::Kind k) {
  switch (k) {
    case Json::Kind::null: return "null";
    case Json::Kind::boolean: return "a boolean";
    case Json::Kind::number: return "a number";
    case Json::Kind::string: return "a string";
    case Json::Kind::array: return "an array";
    case Json::Kind::object: return "an object";
  }
  return "?";
}

bool Json::as_bool() const {
  if (!is_bool()) wrong_kind(Kind::boolean, kind());
  return std::get<bool>(value_);
}
double Json::as_number() const {
  if (!is_number()) wrong_kind(Kind::number, kind());
  return std::get<Number>(value_).value;
}
const std::string& Json::number_text() const {
  if (!is_number()) wrong_kind(Kind::number, kind());
  return std::get<Number>(value_).text;
}
const std::string& Json::as_string() const {
  if (!is_string()) wrong_kind(Kind::string, kind());
  return std::get<std::string>(value_);
}
const Json::Array& Json::as_array() const {
  if (!is_array()) wrong_kind(Kind::array, kind());
  return std::get<Array>(value_);
}
const Json::Object& Json::as_object() const {
  if (!is_object()) wrong_kind(Kind::object, kind());
  return std::get<Object>(value_);
}
Json::Array& Json::as_array() {
  if (!is_array()) wrong_kind(Kind::array, kind());
  return std::get<Array>(value_);
}
Json::Object& Json::as_object() {
  if (!is_object()) wrong_kind(Kind::object, kind());
  return std::get<Object>(value_);
}

const Json* Json::find(std::string_view key) const {
  for (const auto& [k, v] : as_object())
    if (k == key) return &v;
  return nullptr;
}

Json& Json::operator[](std::string_view key) {
  if (is_null()) value_ = Object{};
  Object& o = as_object();
  for (auto& [k, v] : o)
    if (k == key) return v;
  o.emplace_back(std::string(key), Json());
  return o.back().second;
}

void Json::push_back(Json v) {
  if (is_null()) value_ = Array{};
  as_array().push_back(std::move(v));
}

bool operator==(const Json& a, const Json& b) {
  if (a.kind() != b.kind()) return false;
  switch (a.kind()) {
    case Json::Kind::null: return true;
    case Json::Kind::boolean: return a.as_bool() == b.as_bool();
    case Json::Kind::number: return a.as_number() == b.as_number();
    case Json::Kind::string: return a.as_string() == b.as_string();
    case Json::Kind::array: return a.as_array() == b.as_array();
    case Json::Kind::object: return a.as_object() == b.as_object();
  }
  return false;
}

// ---- writer ----------------------------------------------------------------------------------

namespace {

void append_string(std::string& out, const std::string& s) {
  out += '"';
  for (const char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

bool is_scalar(const Json& v) { return !v.is_array() && !v.is_object(); }

void append(std::string& out, const Json& v, int depth, bool pretty);

void append_array(std::string& out, const Json::Array& a, int depth, bool pretty) {
  bool one_line = !pretty || a.empty();
  if (!one_line) {  // scalars that fit in about 80 columns stay on one line
    std::size_t width = 2 * static_cast<std::size_t>(depth) + 2;
    one_line = true;
    for (const Json& e : a) {
      if (!is_scalar(e)) one_line = false;
      width += to_json_line(e).size() + 2;
    }
    one_line = one_line && width <= 100;
  }
  const std::string indent(2 * static_cast<std::size_t>(depth + 1), ' ');
  out += '[';
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (i) out += one_line ? ", " : ",";
    if (!one_line) (out += '\n') += indent;
    append(out, a[i], depth + 1, pretty);
  }
  if (!one_line) (out += '\n').append(2 * static_cast<std::size_t>(depth), ' ');
  out += ']';
}

void append_object(std::string& out, const Json::Object& o, int depth, bool pretty) {
  const std::string indent(2 * static_cast<std::size_t>(depth + 1), ' ');
  out += '{';
  for (std::size_t i = 0; i < o.size(); ++i) {
    if (i) out += pretty ? "," : ", ";
    if (pretty) (out += '\n') += indent;
    append_string(out, o[i].first);
    out += ": ";
    append(out, o[i].second, depth + 1, pretty);
  }
  if (pretty && !o.empty()) (out += '\n').append(2 * static_cast<std::size_t>(depth), ' ');
  out += '}';
}

void append(std::string& out, const Json& v, int depth, bool pretty) {
  switch (v.kind()) {
    case Json::Kind::null: out += "null"; break;
    case Json::Kind::boolean: out += v.as_bool() ? "true" : "false"; break;
    case Json::Kind::number: out += v.number_text(); break;
    case Json::Kind::string: append_string(out, v.as_string()); break;
    case Json::Kind::array: append_array(out, v.as_array(), depth, pretty); break;
    case Json::Kind::object: append_object(out, v.as_object(), depth, pretty); break;
  }
}

}  // namespace

std::string to_json_text(const Json& v) {
  std::string out;
  append(out, v, 0, true);
  out += '\n';
  return out;
}

std::string to_json_line(const Json& v) {
  std::string out;
  append(out, v, 0, false);
  return out;
}

}  // namespace sphark
