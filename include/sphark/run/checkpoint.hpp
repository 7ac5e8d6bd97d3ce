#pragma once
// Checkpoint files: the full state of a run, bit-exact, for --restart.
//
// Binary format (little-endian host order, checked by a byte-order mark):
//   "SPHARKCK"  8-byte magic
//   u32 version (kCheckpointVersion), u32 byte-order mark 0x01020304
//   payload:  str program; u64 n, n x str argv (the options, as given)
//             u64 n, n x (str species, u64 particles,                      -- the layout
//                         u64 k, k x (str field name, u32 components))
//             (version 1, still read: u64 particles; u64 k, k x (str field name, u32 components)
//              of the one species "gas")
//             f64 t; f64 last_dt
//             u64 n, n x (str name, f64 value)    -- named scalars of the run loop
//             u64 n, n x (str name, str text)     -- named texts (e.g. the diagnostics so far)
//             u64 n, n x f64 state values (N_Vector contents)
//             u64 n, n x f64 stepper resume data (Stepper::resume_data(); may be empty)
//             (version 3:) u64 n, n x f64 system resume data (OdeSystem::resume_data(); may be empty)
//   u64 FNV-1a 64 checksum of every byte before it
// str = u64 length + bytes. Reals are stored as their IEEE-754 bits: a load returns exactly
// the values saved. The file is written atomically (temporary file + rename), so a killed run
// leaves either the previous checkpoint or the new one, never a partial file.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sphark/core/types.hpp"
#include "sphark/state/state_layout.hpp"

namespace sphark {

inline constexpr std::uint32_t kCheckpointVersion = 3;  // 1 and 2 are still read

struct CheckpointField {
  std::string name;
  int components = 0;
  bool operator==(const CheckpointField&) const = default;
};

struct CheckpointSpecies {
  std::string name;
  std::size_t particles = 0;
  std::vector<CheckpointField> fields;  // in state order
  bool operator==(const CheckpointSpecies&) const = default;
};

struct Checkpoint {
  std::string program;
  std::vector<std::string> argv;          // options of the run that wrote it (argv[1..])
  std::vector<CheckpointSpecies> species; // the layout, in state order
  Real t = 0;
  Real last_dt = 0;                     // last step taken (initial step of a restart)
  std::vector<std::pair<std::string, Real>> scalars;
  std::vector<std::pair<std::string, std::string>> texts;
  std::vector<Real> y;
  std::vector<Real> stepper_data;       // Stepper::resume_data() (leapfrog: bit-exact restart)
  std::vector<Real> system_data;        // OdeSystem::resume_data() (SPMHD: the h solve's starts)

  // Particles of the first species (0 without species).
  std::size_t particles() const { return species.empty() ? 0 : species.front().particles; }
  // Named lookups; throw std::runtime_error naming the missing entry.
  Real scalar(const std::string& name) const;
  const std::string& text(const std::string& name) const;
  bool has_scalar(const std::string& name) const;  // entries newer than some checkpoints
  bool has_text(const std::string& name) const;
  void set_scalar(const std::string& name, Real value);
  void set_text(const std::string& name, std::string value);
};

// Species, particle counts, field names and component counts of a layout, in state order.
std::vector<CheckpointSpecies> describe_layout(const StateLayout& layout);

// The file image / its parse. decode throws std::runtime_error with one line saying what is
// wrong (not a checkpoint, unsupported version, truncated, checksum mismatch, ...).
std::string encode_checkpoint(const Checkpoint& c);
Checkpoint decode_checkpoint(const std::string& bytes);

// Atomic write; std::runtime_error naming the path on failure.
void save_checkpoint(const std::filesystem::path& path, const Checkpoint& c);
// std::runtime_error "checkpoint '<path>': <reason>" for a missing, unreadable or corrupt file.
Checkpoint load_checkpoint(const std::filesystem::path& path);

// Why the checkpoint does not fit a run with this layout (species, particle counts, fields,
// components, state size), or nullopt if it fits.
std::optional<std::string> layout_mismatch(const Checkpoint& c, const StateLayout& layout);

}  // namespace sphark
