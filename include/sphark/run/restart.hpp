#pragma once
// Command-line plumbing of --restart FILE: a restarted run re-reads the options stored in the
// checkpoint and applies the ones given now on top (the parser's "last occurrence wins"), so
// `prog --restart out/checkpoint.bin --t-end 0.2` continues the same run further.
#include <optional>
#include <string>
#include <vector>

namespace sphark {

// The value of `name` in argv[1..argc) ("--name value" or "--name=value"; the last occurrence),
// or nullopt. A trailing "--name" without a value yields "" (the parser then reports it).
std::optional<std::string> find_option_value(int argc, const char* const* argv, const std::string& name);

// `args` without every occurrence of `name` and its value.
std::vector<std::string> without_option(const std::vector<std::string>& args, const std::string& name);

// argv[1..argc) as strings.
std::vector<std::string> arguments(int argc, const char* const* argv);

// [program] + stored + current: the argument list of a restarted run.
std::vector<std::string> restart_arguments(const std::string& program, const std::vector<std::string>& stored,
                                           const std::vector<std::string>& current);

// Pointers into `args` for an argc/argv-style parser (valid while `args` lives).
std::vector<const char*> as_argv(const std::vector<std::string>& args);

}  // namespace sphark
