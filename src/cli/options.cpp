#include "sphark/cli/options.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <utility>

namespace sphark {
namespace {

std::string real_text(Real v) {  // shortest text that reads back to v
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// from_chars takes no leading '+'; accept one ("+1e-3"), but not "+-1".
std::string_view without_plus(std::string_view s) {
  return s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+' ? s.substr(1) : s;
}

std::optional<Real> parse_real(std::string_view s) {
  s = without_plus(s);
  Real v = 0;
  auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v)) {
    return std::nullopt;
  }
  return v;
}

std::optional<long> parse_long(std::string_view s) {
  s = without_plus(s);
  long v = 0;
  auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

bool satisfies(Real v, const NumberConstraint& c) {
  if (std::holds_alternative<Positive>(c)) return v > 0;
  if (std::holds_alternative<NonNegative>(c)) return v >= 0;
  if (const Range* r = std::get_if<Range>(&c)) return r->lo <= v && v <= r->hi;
  return true;
}

// "a positive real number", "an integer in [1, 64]", ...
std::string expected_number(const NumberConstraint& c, bool integer) {
  const std::string noun = integer ? "integer" : "real number";
  if (std::holds_alternative<Positive>(c)) return "a positive " + noun;
  if (std::holds_alternative<NonNegative>(c)) return "a non-negative " + noun;
  if (const Range* r = std::get_if<Range>(&c)) {
    return std::string(integer ? "an " : "a ") + noun + " in [" + real_text(r->lo) + ", " +
           real_text(r->hi) + "]";
  }
  return std::string(integer ? "an " : "a ") + noun;
}

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + v[i];
  return s;
}

template <class Int>
std::function<bool(std::string_view)> integer_assign(Int* target, NumberConstraint c) {
  return [target, c](std::string_view s) {
    const auto v = parse_long(s);
    if (!v || *v < std::numeric_limits<Int>::min() || *v > std::numeric_limits<Int>::max() ||
        !satisfies(static_cast<Real>(*v), c)) {
      return false;
    }
    *target = static_cast<Int>(*v);
    return true;
  };
}

// Splits "a,b,c" and parses every element with `one`; nullopt if any element fails or s is empty.
template <class T, class ParseOne>
std::optional<std::vector<T>> parse_list(std::string_view s, ParseOne one) {
  std::vector<T> out;
  if (s.empty()) return std::nullopt;
  for (std::size_t start = 0;;) {
    const std::size_t end = std::min(s.find(',', start), s.size());
    const auto v = one(s.substr(start, end - start));
    if (!v) return std::nullopt;
    out.push_back(*v);
    if (end == s.size()) return out;
    start = end + 1;
  }
}

std::string plural_expected(const NumberConstraint& c, bool integer) {
  std::string text = "a comma-separated list of ";
  if (std::holds_alternative<Positive>(c)) text += "positive ";
  if (std::holds_alternative<NonNegative>(c)) text += "non-negative ";
  text += integer ? "integers" : "real numbers";
  if (const Range* r = std::get_if<Range>(&c)) {
    text += " in [";
    text += real_text(r->lo);
    text += ", ";
    text += real_text(r->hi);
    text += ']';
  }
  return text;
}

}  // namespace

void exit_usage_error(std::string_view program, std::string_view option,
                      std::string_view reason) {
  std::string line(program);
  line += ": ";
  if (!option.empty()) line += std::string(option) + ": ";
  line += reason;
  std::fprintf(stderr, "%s\n", line.c_str());
  std::exit(2);
}

OptionParser::OptionParser(std::string program, std::string description)
    : program_(std::move(program)), description_(std::move(description)) {}

void OptionParser::add_option(Option o) {
  if (o.name.size() < 3 || o.name.compare(0, 2, "--") != 0 || o.name == "--help" ||
      o.name == "--config") {
    throw std::logic_error("OptionParser: bad option name '" + o.name + "'");
  }
  if (find(o.name)) throw std::logic_error("OptionParser: duplicate option " + o.name);
  options_.push_back(std::move(o));
}

const OptionParser::Option* OptionParser::find(std::string_view name) const {
  for (const auto& o : options_) {
    if (o.name == name) return &o;
  }
  return nullptr;
}

OptionParser::Option* OptionParser::find(std::string_view name) {
  return const_cast<Option*>(std::as_const(*this).find(name));
}

void OptionParser::add(std::string name, Real* target, std::string help, NumberConstraint c) {
  if (!std::isfinite(*target) || !satisfies(*target, c)) {
    throw std::logic_error("OptionParser: default of " + name + " violates its constraint");
  }
  auto assign = [target, c](std::string_view s) {
    const auto v = parse_real(s);
    if (!v || !satisfies(*v, c)) return false;
    *target = *v;
    return true;
  };
  Option o{std::move(name), "REAL", std::move(help), real_text(*target), expected_number(c, false), assign,
           Kind::real, [target] { return Json(*target); }, false};
  add_option(std::move(o));
}

void OptionParser::add(std::string name, int* target, std::string help, NumberConstraint c) {
  if (!satisfies(*target, c)) {
    throw std::logic_error("OptionParser: default of " + name + " violates its constraint");
  }
  Option o{std::move(name), "INT", std::move(help), std::to_string(*target), expected_number(c, true),
           integer_assign(target, c),
           Kind::integer, [target] { return Json(*target); }, false};
  add_option(std::move(o));
}

void OptionParser::add(std::string name, long* target, std::string help, NumberConstraint c) {
  if (!satisfies(static_cast<Real>(*target), c)) {
    throw std::logic_error("OptionParser: default of " + name + " violates its constraint");
  }
  Option o{std::move(name), "INT", std::move(help), std::to_string(*target), expected_number(c, true),
           integer_assign(target, c),
           Kind::integer, [target] { return Json(*target); }, false};
  add_option(std::move(o));
}

void OptionParser::add(std::string name, std::string* target, std::string help, OneOf allowed) {
  const auto& vals = allowed.values;
  const bool listed = !vals.empty();
  auto in_list = [vals](std::string_view s) {
    for (const auto& v : vals) {
      if (v == s) return true;
    }
    return false;
  };
  if (listed && !in_list(*target)) {
    throw std::logic_error("OptionParser: default of " + name + " is not one of its values");
  }
  auto assign = [target, listed, in_list](std::string_view s) {
    if (s.empty() || (listed && !in_list(s))) return false;
    *target = std::string(s);
    return true;
  };
  Option o{std::move(name), "NAME", std::move(help), target->empty() ? "none" : *target,
           listed ? "one of: " + join(vals, ", ") : "a non-empty string", assign,
           Kind::string, [target] { return Json(*target); }, false};
  add_option(std::move(o));
}

void OptionParser::add(std::string name, std::filesystem::path* target, std::string help,
                       std::string metavar) {
  auto assign = [target](std::string_view s) {
    if (s.empty()) return false;
    *target = std::filesystem::path(std::string(s));
    return true;
  };
  if (metavar.empty()) metavar = "PATH";  // an empty metavar would mark a flag
  Option o{std::move(name), std::move(metavar), std::move(help), target->string(), "a path", assign,
           Kind::path, [target] { return Json(target->string()); }, false};
  add_option(std::move(o));
}

void OptionParser::add(std::string name, std::vector<Real>* target, std::string help,
                       NumberConstraint c) {
  std::string def;
  for (Real v : *target) {
    if (!std::isfinite(v) || !satisfies(v, c)) {
      throw std::logic_error("OptionParser: default of " + name + " violates its constraint");
    }
    if (!def.empty()) def += ',';
    def += real_text(v);
  }
  auto assign = [target, c](std::string_view s) {
    auto v = parse_list<Real>(s, [&c](std::string_view e) -> std::optional<Real> {
      const auto x = parse_real(e);
      return x && satisfies(*x, c) ? x : std::nullopt;
    });
    if (v) *target = std::move(*v);
    return v.has_value();
  };
  Option o{std::move(name), "LIST", std::move(help), def.empty() ? "none" : def, plural_expected(c, false), assign,
           Kind::real_list, [target] { return Json(Json::Array(target->begin(), target->end())); }, false};
  add_option(std::move(o));
}

void OptionParser::add(std::string name, std::vector<int>* target, std::string help,
                       NumberConstraint c) {
  std::string def;
  for (int v : *target) {
    if (!satisfies(v, c)) {
      throw std::logic_error("OptionParser: default of " + name + " violates its constraint");
    }
    if (!def.empty()) def += ',';
    def += std::to_string(v);
  }
  auto assign = [target, c](std::string_view s) {
    auto v = parse_list<int>(s, [&c](std::string_view e) -> std::optional<int> {
      int x = 0;
      return integer_assign(&x, c)(e) ? std::optional<int>(x) : std::nullopt;
    });
    if (v) *target = std::move(*v);
    return v.has_value();
  };
  Option o{std::move(name), "LIST", std::move(help), def.empty() ? "none" : def, plural_expected(c, true), assign,
           Kind::integer_list, [target] { return Json(Json::Array(target->begin(), target->end())); }, false};
  add_option(std::move(o));
}

void OptionParser::add_flag(std::string name, bool* target, std::string help,
                            bool value_when_given) {
  auto assign = [target, value_when_given](std::string_view s) {
    if (!s.empty() && s != "off") return false;
    *target = s.empty() ? value_when_given : !value_when_given;
    return true;
  };
  Option o{std::move(name), "", std::move(help), "", "no value", assign,
           Kind::flag, [target, value_when_given] { return Json(*target == value_when_given); }, false};
  add_option(std::move(o));
}

void OptionParser::add_switch(std::string name, bool* target, std::string help) {
  auto assign = [target](std::string_view s) {
    if (s != "on" && s != "off") return false;
    *target = s == "on";
    return true;
  };
  Option o{std::move(name), "on|off", std::move(help), *target ? "on" : "off", "on or off", assign,
           Kind::on_off, [target] { return Json(*target); }, false};
  add_option(std::move(o));
}

ParseStatus OptionParser::report(std::string_view option, const std::string& reason) const {
  std::fprintf(stderr, "%s: %.*s: %s\n", program_.c_str(), static_cast<int>(option.size()), option.data(),
               reason.c_str());
  return ParseStatus::usage_error;
}

ParseStatus OptionParser::parse(int argc, const char* const* argv) {
  arguments_.assign(argv + (argc > 0 ? 1 : 0), argv + std::max(argc, 0));
  config_files_.clear();
  for (int i = 1; i < argc; ++i) {  // --help wins wherever it is
    const std::string_view arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::fputs(help().c_str(), stdout);
      std::fflush(stdout);
      return ParseStatus::help;
    }
  }
  for (int i = 1; i < argc; ++i) {  // --config files first, in order: the command line overrides them
    const std::string_view arg = argv[i];
    if (arg != "--config" && arg.rfind("--config=", 0) != 0) continue;
    std::string_view file;
    if (arg.size() > 8) {
      file = arg.substr(9);
    } else if (i + 1 < argc && std::string_view(argv[i + 1]).compare(0, 2, "--") != 0) {
      file = argv[++i];
    }
    if (file.empty()) return report("--config", "missing value (expected a JSON FILE, e.g. a run.json)");
    if (apply_config_file(std::string(file)) != ParseStatus::ok) return ParseStatus::usage_error;
  }
  return parse_arguments(argc, argv);
}

ParseStatus OptionParser::parse_arguments(int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) {
      std::string quoted = "'";  // (built stepwise: GCC 12 -Wrestrict false positive)
      quoted.append(arg).append("'");
      return report(quoted, "unexpected argument (try --help)");
    }
    const auto eq = arg.find('=');
    const std::string_view name = arg.substr(0, eq);
    if (name == "--config") {  // applied already
      if (eq == std::string_view::npos) ++i;
      continue;
    }
    Option* o = find(name);
    if (!o) return report(name, "unknown option (try --help)");
    if (o->metavar.empty()) {  // flag
      if (eq != std::string_view::npos) {
        return report(name, "takes no value (got '" + std::string(arg.substr(eq + 1)) + "')");
      }
      o->assign({});
      o->given = true;
      continue;
    }
    std::string_view value;
    if (eq != std::string_view::npos) {
      value = arg.substr(eq + 1);
    } else if (i + 1 < argc && std::string_view(argv[i + 1]).compare(0, 2, "--") != 0) {
      value = argv[++i];
    } else {
      return report(name, "missing value (expected " + o->expected + ")");
    }
    if (!o->assign(value)) {
      return report(name, "bad value '" + std::string(value) + "' (expected " + o->expected + ")");
    }
    o->given = true;
  }
  return ParseStatus::ok;
}

void OptionParser::parse_or_exit(int argc, const char* const* argv) {
  switch (parse(argc, argv)) {
    case ParseStatus::ok: return;
    case ParseStatus::help: std::exit(0);
    case ParseStatus::usage_error: std::exit(2);
  }
}

void OptionParser::fail(std::string_view option, std::string_view reason) const {
  exit_usage_error(program_, option, reason);
}

}  // namespace sphark
