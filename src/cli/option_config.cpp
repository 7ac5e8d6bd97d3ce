// OptionParser and JSON: the option values a run record stores (records, to_json) and the
// config files of --config, applied through the same checks as the command line.
#include <fstream>
#include <sstream>

#include "sphark/cli/options.hpp"

namespace sphark {

const char* OptionParser::kind_name(Kind k) {
  switch (k) {
    case Kind::real: return "real";
    case Kind::integer: return "integer";
    case Kind::string: return "string";
    case Kind::path: return "path";
    case Kind::real_list: return "real list";
    case Kind::integer_list: return "integer list";
    case Kind::flag: return "flag";
    case Kind::on_off: return "switch";
  }
  return "?";
}

bool OptionParser::was_given(std::string_view name) const {
  const Option* o = find(name);
  if (!o) throw std::logic_error("OptionParser::was_given: no option " + std::string(name));
  return o->given;
}

std::vector<OptionRecord> OptionParser::records() const {
  std::vector<OptionRecord> out;
  for (const Option& o : options_) out.push_back({o.name.substr(2), kind_name(o.kind), o.value(), o.given});
  return out;
}

Json OptionParser::to_json() const {
  Json j = Json::Object{};
  for (const Option& o : options_) j[o.name.substr(2)] = o.value();
  return j;
}

std::optional<std::string> OptionParser::config_text(const Option& o, const Json& v) {
  switch (o.kind) {
    case Kind::real:
    case Kind::integer:
      if (v.is_number()) return v.number_text();  // exactly as written: bit-exact reals
      return std::nullopt;
    case Kind::string:
    case Kind::path:
      if (v.is_string()) return v.as_string();
      return std::nullopt;
    case Kind::real_list:
    case Kind::integer_list: {
      if (!v.is_array()) return std::nullopt;
      std::string text;
      for (const Json& e : v.as_array()) {
        if (!e.is_number()) return std::nullopt;
        if (!text.empty()) text += ',';
        text += e.number_text();
      }
      return text;
    }
    case Kind::flag:
      if (v.is_bool()) return std::string(v.as_bool() ? "" : "off");
      return std::nullopt;
    case Kind::on_off:
      if (v.is_bool()) return std::string(v.as_bool() ? "on" : "off");
      if (v.is_string() && (v.as_string() == "on" || v.as_string() == "off")) return v.as_string();
      return std::nullopt;
  }
  return std::nullopt;
}

ParseStatus OptionParser::apply_json(const Json& options, std::string_view source) {
  std::string where = "config '";
  where += source;
  where += '\'';
  if (!options.is_object()) return report("--config", where + " is not a JSON object of option values");
  for (const auto& [key, value] : options.as_object()) {
    const std::string name = key.rfind("--", 0) == 0 ? key : "--" + key;
    Option* o = find(name);
    if (!o) return report(name, "unknown option in " + where + " (try --help)");
    // A value equal to the current one (a record's defaults: "restart": "", "resolutions": [])
    // is accepted as it stands, even where the command line needs a non-empty text.
    if (value == o->value()) {
      o->given = true;
      continue;
    }
    const std::optional<std::string> text = config_text(*o, value);
    if (!text || !o->assign(*text)) {
      return report(name, "bad value '" + to_json_line(value) + "' in " + where + " (expected " +
                              (o->kind == Kind::flag || o->kind == Kind::on_off ? std::string("true or false") : o->expected) + ")");
    }
    o->given = true;
  }
  return ParseStatus::ok;
}

ParseStatus OptionParser::apply_config_file(const std::filesystem::path& file) {
  std::string quoted = "'";  // (built stepwise: GCC 12 -Wrestrict false positive on "'" + std::string)
  quoted += file.string();
  quoted += '\'';
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  if (!in || in.bad() || std::filesystem::is_directory(file)) {
    return report("--config", "cannot read " + quoted + (std::filesystem::exists(file) ? "" : ": no such file"));
  }
  Json doc;
  try {
    doc = parse_json(text.str());
  } catch (const JsonError& e) {
    return report("--config", quoted + ": " + e.what());
  }
  if (!doc.is_object()) return report("--config", quoted + " is not a JSON object");
  const Json* options = doc.find("options");  // a run record; else a flat object of options
  if (options) {
    const Json* program = doc.find("program");
    if (program && program->is_string() && program->as_string() != program_) {
      return report("--config", quoted + " records a run of " + program->as_string() + ", not " + program_);
    }
  }
  config_files_.push_back(file);
  return apply_json(options ? *options : doc, file.string());
}

}  // namespace sphark
