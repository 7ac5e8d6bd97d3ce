// The JSON reader: recursive descent over RFC 8259, with the line and column of every error.
#include <string>

#include "sphark/io/json.hpp"

namespace sphark {

JsonError::JsonError(int l, int c, const std::string& reason)
    : std::runtime_error("line " + std::to_string(l) + ", column " + std::to_string(c) + ": " + reason),
      line(l), column(c) {}

namespace {

constexpr int kMaxDepth = 256;

class Reader {
 public:
  explicit Reader(std::string_view text) : s_(text) {}

  Json document() {
    Json v = value(0);
    skip_space();
    if (i_ < s_.size()) fail("unexpected text after the JSON value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& reason) const {
    int line = 1, column = 1;
    for (std::size_t k = 0; k < i_ && k < s_.size(); ++k) {
      if (s_[k] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    throw JsonError(line, column, reason);
  }

  void skip_space() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
  }

  void expect(char c, const char* what) {
    skip_space();
    if (i_ >= s_.size() || s_[i_] != c) fail(std::string("expected ") + what);
    ++i_;
  }

  void literal(std::string_view word) {
    if (s_.substr(i_, word.size()) != word) fail("expected a JSON value");
    i_ += word.size();
  }

  Json value(int depth) {
    if (depth > kMaxDepth) fail("nested deeper than 256 levels");
    skip_space();
    if (i_ >= s_.size()) fail("unexpected end of the text (expected a JSON value)");
    switch (s_[i_]) {
      case '{': return object(depth);
      case '[': return array(depth);
      case '"': return Json(string());
      case 't': literal("true"); return Json(true);
      case 'f': literal("false"); return Json(false);
      case 'n': literal("null"); return Json();
      default: return number();
    }
  }

  Json number() {
    const std::size_t start = i_;
    while (i_ < s_.size() && std::string_view("+-0123456789.eE").find(s_[i_]) != std::string_view::npos) ++i_;
    if (i_ == start) fail("expected a JSON value");
    const std::string text(s_.substr(start, i_ - start));
    try {
      return Json::number_from_text(text);
    } catch (const std::invalid_argument&) {
      i_ = start;
      fail("malformed number '" + text + "'");
    }
  }

  unsigned hex4() {
    if (i_ + 4 > s_.size()) fail("truncated \\u escape");
    unsigned v = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s_[i_++];
      v <<= 4;
      if (c >= '0' && c <= '9') v |= static_cast<unsigned>(c - '0');
      else if (c >= 'a' && c <= 'f') v |= static_cast<unsigned>(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') v |= static_cast<unsigned>(c - 'A' + 10);
      else fail("bad \\u escape");
    }
    return v;
  }

  static void append_utf8(std::string& out, unsigned cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }

  void escape(std::string& out) {
    if (i_ >= s_.size()) fail("unterminated string");
    const char c = s_[i_++];
    switch (c) {
      case '"': case '\\': case '/': out += c; return;
      case 'b': out += '\b'; return;
      case 'f': out += '\f'; return;
      case 'n': out += '\n'; return;
      case 'r': out += '\r'; return;
      case 't': out += '\t'; return;
      case 'u': break;
      default: --i_; fail(std::string("bad escape '\\") + c + "'");
    }
    unsigned cp = hex4();
    if (cp >= 0xD800 && cp < 0xDC00) {  // a surrogate pair
      if (s_.substr(i_, 2) != "\\u") fail("lone surrogate in \\u escape");
      i_ += 2;
      const unsigned low = hex4();
      if (low < 0xDC00 || low >= 0xE000) fail("bad surrogate pair in \\u escape");
      cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
    } else if (cp >= 0xDC00 && cp < 0xE000) {
      fail("lone surrogate in \\u escape");
    }
    append_utf8(out, cp);
  }

  std::string string() {
    ++i_;  // the opening quote
    std::string out;
    while (true) {
      if (i_ >= s_.size()) fail("unterminated string");
      const char c = s_[i_++];
      if (c == '"') return out;
      if (c == '\\') {
        escape(out);
      } else if (static_cast<unsigned char>(c) < 0x20) {
        --i_;
        fail("control character in a string (write it as an escape)");
      } else {
        out += c;
      }
    }
  }

  Json array(int depth) {
    ++i_;
    Json::Array a;
    skip_space();
    if (i_ < s_.size() && s_[i_] == ']') return ++i_, Json(std::move(a));
    while (true) {
      a.push_back(value(depth + 1));
      skip_space();
      if (i_ < s_.size() && s_[i_] == ']') return ++i_, Json(std::move(a));
      expect(',', "',' or ']'");
    }
  }

  Json object(int depth) {
    ++i_;
    Json::Object o;
    skip_space();
    if (i_ < s_.size() && s_[i_] == '}') return ++i_, Json(std::move(o));
    while (true) {
      skip_space();
      if (i_ >= s_.size() || s_[i_] != '"') fail("expected a key (a string in double quotes)");
      const std::size_t key_at = i_;
      std::string key = string();
      for (const auto& [k, v] : o) {
        if (k == key) {
          i_ = key_at;
          fail("duplicate key \"" + key + "\"");
        }
      }
      expect(':', "':'");
      o.emplace_back(std::move(key), value(depth + 1));
      skip_space();
      if (i_ < s_.size() && s_[i_] == '}') return ++i_, Json(std::move(o));
      expect(',', "',' or '}'");
    }
  }

  std::string_view s_;
  std::size_t i_ = 0;
};

}  // namespace

Json parse_json(std::string_view text) { return Reader(text).document(); }

}  // namespace sphark
