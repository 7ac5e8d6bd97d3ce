#include "sphark/run/checkpoint.hpp"

#include <algorithm>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "sphark/io/csv_writer.hpp"  // write_file_atomically

namespace sphark {
namespace {

constexpr char kMagic[8] = {'S', 'P', 'H', 'A', 'R', 'K', 'C', 'K'};
constexpr std::uint32_t kByteOrder = 0x01020304u;

std::uint64_t fnv1a(const char* p, std::size_t n) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(p[i]);
    h *= 1099511628211ull;
  }
  return h;
}

class Writer {
 public:
  template <class T>
  void pod(T v) {
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void str(const std::string& s) {
    pod<std::uint64_t>(s.size());
    out_ += s;
  }
  std::string& bytes() { return out_; }

 private:
  std::string out_;
};

class Reader {
 public:
  Reader(const std::string& b, std::size_t end) : b_(b), end_(end) {}
  template <class T>
  T pod(const char* what) {
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, b_.data() + pos_, sizeof v);
    pos_ += sizeof v;
    return v;
  }
  std::string str(const char* what) {
    const auto n = pod<std::uint64_t>(what);
    need(n, what);
    std::string s = b_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  // A count of items of at least `item_bytes` each: must fit in what is left.
  std::size_t count(const char* what, std::size_t item_bytes) {
    const auto n = pod<std::uint64_t>(what);
    if (n > (end_ - pos_) / item_bytes) throw std::runtime_error(std::string("corrupt ") + what + " count");
    return n;
  }
  std::size_t pos() const { return pos_; }

 private:
  void need(std::size_t n, const char* what) const {
    if (n > end_ - pos_) throw std::runtime_error(std::string("truncated file (reading ") + what + ")");
  }
  const std::string& b_;
  std::size_t end_, pos_ = 0;

 public:
  void skip(std::size_t n) { pos_ += n; }
};

}  // namespace

Real Checkpoint::scalar(const std::string& name) const {
  for (const auto& [k, v] : scalars)
    if (k == name) return v;
  throw std::runtime_error("checkpoint has no scalar '" + name + "'");
}

const std::string& Checkpoint::text(const std::string& name) const {
  for (const auto& [k, v] : texts)
    if (k == name) return v;
  throw std::runtime_error("checkpoint has no text '" + name + "'");
}

bool Checkpoint::has_scalar(const std::string& name) const {
  return std::any_of(scalars.begin(), scalars.end(), [&](const auto& e) { return e.first == name; });
}

bool Checkpoint::has_text(const std::string& name) const {
  return std::any_of(texts.begin(), texts.end(), [&](const auto& e) { return e.first == name; });
}

void Checkpoint::set_scalar(const std::string& name, Real value) {
  for (auto& [k, v] : scalars)
    if (k == name) {
      v = value;
      return;
    }
  scalars.emplace_back(name, value);
}

void Checkpoint::set_text(const std::string& name, std::string value) {
  for (auto& [k, v] : texts)
    if (k == name) {
      v = std::move(value);
      return;
    }
  texts.emplace_back(name, std::move(value));
}

std::vector<CheckpointSpecies> describe_layout(const StateLayout& layout) {
  std::vector<CheckpointSpecies> out;
  for (const auto& b : layout.species()) {
    CheckpointSpecies s{std::string(b.species.name()), b.count, {}};
    for (const auto& f : b.fields) s.fields.push_back({std::string(f.field.name()), f.components});
    out.push_back(std::move(s));
  }
  return out;
}

std::string encode_checkpoint(const Checkpoint& c) {
  Writer w;
  w.bytes().append(kMagic, sizeof kMagic);
  w.pod<std::uint32_t>(kCheckpointVersion);
  w.pod<std::uint32_t>(kByteOrder);
  w.str(c.program);
  w.pod<std::uint64_t>(c.argv.size());
  for (const auto& a : c.argv) w.str(a);
  w.pod<std::uint64_t>(c.species.size());
  for (const auto& sp : c.species) {
    w.str(sp.name);
    w.pod<std::uint64_t>(sp.particles);
    w.pod<std::uint64_t>(sp.fields.size());
    for (const auto& f : sp.fields) {
      w.str(f.name);
      w.pod<std::uint32_t>(static_cast<std::uint32_t>(f.components));
    }
  }
  w.pod<double>(c.t);
  w.pod<double>(c.last_dt);
  w.pod<std::uint64_t>(c.scalars.size());
  for (const auto& [k, v] : c.scalars) {
    w.str(k);
    w.pod<double>(v);
  }
  w.pod<std::uint64_t>(c.texts.size());
  for (const auto& [k, v] : c.texts) {
    w.str(k);
    w.str(v);
  }
  w.pod<std::uint64_t>(c.y.size());
  w.bytes().append(reinterpret_cast<const char*>(c.y.data()), c.y.size() * sizeof(Real));
  w.pod<std::uint64_t>(c.stepper_data.size());
  w.bytes().append(reinterpret_cast<const char*>(c.stepper_data.data()), c.stepper_data.size() * sizeof(Real));
  w.pod<std::uint64_t>(c.system_data.size());
  w.bytes().append(reinterpret_cast<const char*>(c.system_data.data()), c.system_data.size() * sizeof(Real));
  w.pod<std::uint64_t>(fnv1a(w.bytes().data(), w.bytes().size()));
  return std::move(w.bytes());
}

Checkpoint decode_checkpoint(const std::string& b) {
  if (b.size() < sizeof kMagic || std::memcmp(b.data(), kMagic, sizeof kMagic) != 0)
    throw std::runtime_error("not a sphark checkpoint (bad magic)");
  if (b.size() < sizeof kMagic + 16) throw std::runtime_error("truncated file (header)");
  Reader head(b, b.size());
  head.skip(sizeof kMagic);
  const auto version = head.pod<std::uint32_t>("version");
  if (version != kCheckpointVersion && version != 1 && version != 2)
    throw std::runtime_error("unsupported checkpoint version " + std::to_string(version) + " (this build reads " +
                             std::to_string(kCheckpointVersion) + ")");
  if (head.pod<std::uint32_t>("byte order") != kByteOrder)
    throw std::runtime_error("written on a machine with another byte order");
  const std::size_t end = b.size() - sizeof(std::uint64_t);
  std::uint64_t stored;
  std::memcpy(&stored, b.data() + end, sizeof stored);
  if (stored != fnv1a(b.data(), end)) throw std::runtime_error("checksum mismatch (truncated or corrupt file)");

  Reader r(b, end);
  r.skip(head.pos());
  Checkpoint c;
  c.program = r.str("program");
  for (std::size_t i = 0, n = r.count("argv", 8); i < n; ++i) c.argv.push_back(r.str("argv"));
  const auto read_fields = [&r](CheckpointSpecies& sp) {
    for (std::size_t i = 0, n = r.count("fields", 12); i < n; ++i) {
      CheckpointField f;
      f.name = r.str("field name");
      f.components = static_cast<int>(r.pod<std::uint32_t>("components"));
      sp.fields.push_back(std::move(f));
    }
  };
  if (version == 1) {  // one species, the gas
    CheckpointSpecies sp{"gas", r.pod<std::uint64_t>("particles"), {}};
    read_fields(sp);
    c.species.push_back(std::move(sp));
  } else {
    for (std::size_t i = 0, n = r.count("species", 24); i < n; ++i) {
      CheckpointSpecies sp;
      sp.name = r.str("species name");
      sp.particles = r.pod<std::uint64_t>("particles");
      read_fields(sp);
      c.species.push_back(std::move(sp));
    }
  }
  c.t = r.pod<double>("t");
  c.last_dt = r.pod<double>("last dt");
  for (std::size_t i = 0, n = r.count("scalars", 16); i < n; ++i) {
    std::string k = r.str("scalar name");
    c.scalars.emplace_back(std::move(k), r.pod<double>("scalar"));
  }
  for (std::size_t i = 0, n = r.count("texts", 16); i < n; ++i) {
    std::string k = r.str("text name");
    c.texts.emplace_back(std::move(k), r.str("text"));
  }
  c.y.resize(r.count("state", sizeof(Real)));
  for (Real& v : c.y) v = r.pod<double>("state");
  c.stepper_data.resize(r.count("stepper data", sizeof(Real)));
  for (Real& v : c.stepper_data) v = r.pod<double>("stepper data");
  if (version >= 3) {
    c.system_data.resize(r.count("system data", sizeof(Real)));
    for (Real& v : c.system_data) v = r.pod<double>("system data");
  }
  if (r.pos() != end) throw std::runtime_error("trailing bytes after the state");
  std::size_t expected = 0;
  for (const auto& sp : c.species)
    for (const auto& f : sp.fields) {
      if (f.components <= 0 || sp.particles > c.y.size() / static_cast<std::size_t>(f.components))
        throw std::runtime_error("corrupt layout (field " + f.name + ")");
      expected += sp.particles * static_cast<std::size_t>(f.components);
    }
  if (expected != c.y.size())
    throw std::runtime_error("state has " + std::to_string(c.y.size()) + " values, layout describes " +
                             std::to_string(expected));
  return c;
}

void save_checkpoint(const std::filesystem::path& path, const Checkpoint& c) {
  write_file_atomically(path, encode_checkpoint(c));
}

Checkpoint load_checkpoint(const std::filesystem::path& path) {
  const std::string where = "checkpoint '" + path.string() + "': ";
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw std::runtime_error(where + "no such file");
  if (!std::filesystem::is_regular_file(path, ec)) throw std::runtime_error(where + "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(where + "cannot open: " + std::strerror(errno));
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  try {
    return decode_checkpoint(bytes);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(where + e.what());
  }
}

std::optional<std::string> layout_mismatch(const Checkpoint& c, const StateLayout& layout) {
  const auto species = describe_layout(layout);
  const auto text = [](const std::vector<CheckpointSpecies>& all) {
    std::ostringstream s;
    for (std::size_t i = 0; i < all.size(); ++i) {
      s << (i ? "; " : "") << all[i].particles << ' ' << all[i].name << " particles, fields";
      for (const auto& f : all[i].fields) s << ' ' << f.name << '(' << f.components << ')';
    }
    return s.str();
  };
  if (c.species != species || c.y.size() != layout.size())
    return "checkpoint has " + text(c.species) + "; this run has " + text(species);
  return std::nullopt;
}

}  // namespace sphark
