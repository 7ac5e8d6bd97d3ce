#pragma once
// A file's bytes (binary), for tests that compare outputs byte for byte; "" if it cannot be read.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace sphark::test {

inline std::string file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace sphark::test
