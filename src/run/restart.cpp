#include "sphark/run/restart.hpp"

namespace sphark {

std::optional<std::string> find_option_value(int argc, const char* const* argv, const std::string& name) {
  std::optional<std::string> value;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == name) {
      value = i + 1 < argc ? std::string(argv[i + 1]) : std::string();
      ++i;
    } else if (a.rfind(name + "=", 0) == 0) {
      value = a.substr(name.size() + 1);
    }
  }
  return value;
}

std::vector<std::string> without_option(const std::vector<std::string>& args, const std::string& name) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == name) {
      ++i;  // and its value
      continue;
    }
    if (args[i].rfind(name + "=", 0) == 0) continue;
    out.push_back(args[i]);
  }
  return out;
}

std::vector<std::string> arguments(int argc, const char* const* argv) {
  return std::vector<std::string>(argv + (argc > 0 ? 1 : 0), argv + argc);
}

std::vector<std::string> restart_arguments(const std::string& program, const std::vector<std::string>& stored,
                                           const std::vector<std::string>& current) {
  std::vector<std::string> out{program};
  out.insert(out.end(), stored.begin(), stored.end());
  out.insert(out.end(), current.begin(), current.end());
  return out;
}

std::vector<const char*> as_argv(const std::vector<std::string>& args) {
  std::vector<const char*> p;
  for (const auto& a : args) p.push_back(a.c_str());
  return p;
}

}  // namespace sphark
