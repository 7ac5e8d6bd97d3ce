// OptionParser::help(): the --help text.
#include <algorithm>

#include "sphark/cli/options.hpp"

namespace sphark {

namespace {
// Appends `text` to `out` wrapped at kHelpWidth columns, continuation lines indented by
// `indent` spaces; the first line starts at column `column`.
void append_wrapped(std::string& out, const std::string& text, std::size_t indent,
                    std::size_t column) {
  constexpr std::size_t kHelpWidth = 100;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t room = kHelpWidth > column ? kHelpWidth - column : 20;
    std::size_t end = text.size();
    if (end - start > room) {
      end = text.rfind(' ', start + room);
      if (end == std::string::npos || end <= start) end = text.find(' ', start + room);
      if (end == std::string::npos) end = text.size();
    }
    out.append(text, start, end - start);
    start = end < text.size() ? end + 1 : end;
    if (start < text.size()) {
      out += '\n';
      out.append(indent, ' ');
      column = indent;
    }
  }
  out += '\n';
}
}  // namespace

std::string OptionParser::help() const {
  std::vector<std::string> heads;
  std::size_t width = std::string_view("--config FILE").size();
  for (const auto& o : options_) {
    heads.push_back(o.metavar.empty() ? o.name : o.name + " " + o.metavar);
    width = std::max(width, heads.back().size());
  }
  std::string s = program_;
  s += ": ";
  s += description_;
  s += "\n\nusage: ";
  s += program_;
  s += " [options]\n\noptions:\n";
  const std::size_t indent = 2 + width + 2;
  for (std::size_t k = 0; k < options_.size(); ++k) {
    const Option& o = options_[k];
    s += "  ";
    s += heads[k];
    s.append(width - heads[k].size() + 2, ' ');
    std::string text = o.help;
    if (!o.metavar.empty()) text += " (" + o.expected + "; default " + o.default_text + ")";
    append_wrapped(s, text, indent, indent);
  }
  const auto builtin = [&](const std::string& head, const std::string& text) {
    s += "  " + head;
    s.append(width > head.size() ? width - head.size() + 2 : 2, ' ');
    append_wrapped(s, text, indent, indent);
  };
  builtin("--config FILE",
          "read option values from a JSON FILE: a run.json (its \"options\") or {\"option\": value, ...}; options "
          "given here override them");
  builtin("--help", "print this help and exit");
  return s;
}

}  // namespace sphark
