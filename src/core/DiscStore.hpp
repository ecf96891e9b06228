#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/Material.hpp"
#include "core/Vec2.hpp"

namespace rondel {

// What each disc field is used for. Ghost packing, migration and checkpoints loop over this table
// (docs/design.md section 2) instead of naming fields one by one.
// Disc ids are integers from 0 to kMaxGid - 1: final.csv and CSV scenes carry them as numbers that a double
// holds exactly, and every reader of a file refuses others.
inline constexpr std::int64_t kMaxGid = std::int64_t{1} << 53;

enum DiscFieldUse : unsigned {
  kGhostCreate = 1u,  // copied when a ghost is created
  kGhostStep = 2u,    // refreshed on ghosts every step between rebuilds
  kMigrate = 4u,      // travels with a disc to its new owner
  kCheckpoint = 8u,   // written to checkpoints
};

enum DiscFlag : std::uint32_t {
  kFlagFixed = 1u,     // not integrated (a prescribed disc: immobile, or moved by its wall)
  kFlagAttached = 2u,  // glued to a wall (walls.rough): translates with it; bits 8-23 hold the wall index
};
constexpr bool is_attached(std::uint32_t f) { return (f & kFlagAttached) != 0u; }
constexpr std::size_t attached_wall(std::uint32_t f) { return (f >> 8) & 0xffffu; }
constexpr std::uint32_t attached_flags(std::size_t wall) {
  return kFlagFixed | kFlagAttached | (static_cast<std::uint32_t>(wall) << 8);
}
// True when two discs form one rigid body (both fixed and glued to the same wall, or both plain fixed):
// their contact exerts no work and is not searched.
constexpr bool same_rigid_body(std::uint32_t a, std::uint32_t b) {
  return (a & kFlagFixed) && (b & kFlagFixed) && (a & ~kFlagFixed) == (b & ~kFlagFixed);
}

// Structure of arrays: owned discs first (indices [0, n_owned)), then ghosts.
class DiscStore {
 public:
  std::vector<std::int64_t> gid;
  std::vector<std::int32_t> material;
  std::vector<double> radius, mass, inertia;
  std::vector<Vec2> position, velocity;
  std::vector<double> theta, omega;
  std::vector<Vec2> force;
  std::vector<double> torque;
  std::vector<std::uint32_t> flags;

  std::size_t size() const { return gid.size(); }
  std::size_t n_owned() const { return n_owned_; }
  std::size_t n_ghost() const { return size() - n_owned_; }

  // Appends an owned disc (only while there are no ghosts). Mass and inertia follow docs/physics.md section 1.
  std::size_t add(std::int64_t id, std::int32_t mat, double R, double density, double thickness, Vec2 x, Vec2 v = {},
                  double w = 0.0);
  // The same with the mass and inertia of the material's body (core/Material.hpp).
  std::size_t add(std::int64_t id, std::int32_t mat, double R, const Material& m, Vec2 x, Vec2 v = {}, double w = 0.0);
  // Gives owned disc i the material `mat` (index) with the mass and inertia of its body.
  void set_material(std::size_t i, std::int32_t mat, const Material& m);
  void reserve(std::size_t n);
  void clear();
  // Drops ghosts (everything past n_owned).
  void truncate_to_owned();
  // Declares the first n discs owned and the rest ghosts (after appending records field by field).
  void set_owned_count(std::size_t n) { n_owned_ = n; }
  // Removes the owned discs whose flag in `drop` is set (ghosts are dropped too), keeping the order.
  void remove_owned(const std::vector<bool>& drop);
  // Puts the owned discs in ascending gid (ghosts are dropped), when they are not already: the contact
  // kernel walks the rows in ascending key order, so discs stored in that order are read as a stream.
  // Returns whether anything moved.
  bool sort_owned_by_gid();
  std::size_t memory_bytes() const;

  // Visits every field with its name, its uses and its vector.
  template <class Visitor>
  void for_each_field(Visitor&& visit) {
    visit("gid", kGhostCreate | kMigrate | kCheckpoint, gid);
    visit("material", kGhostCreate | kMigrate | kCheckpoint, material);
    visit("radius", kGhostCreate | kMigrate | kCheckpoint, radius);
    visit("mass", kGhostCreate | kMigrate | kCheckpoint, mass);
    visit("inertia", kGhostCreate | kMigrate | kCheckpoint, inertia);
    visit("position", kGhostCreate | kGhostStep | kMigrate | kCheckpoint, position);
    visit("velocity", kGhostCreate | kGhostStep | kMigrate | kCheckpoint, velocity);
    visit("theta", kMigrate | kCheckpoint, theta);
    visit("omega", kGhostCreate | kGhostStep | kMigrate | kCheckpoint, omega);
    visit("force", kMigrate | kCheckpoint, force);
    visit("torque", kMigrate | kCheckpoint, torque);
    visit("flags", kGhostCreate | kMigrate | kCheckpoint, flags);
  }

 private:
  std::size_t n_owned_ = 0;
};

// The datasets of /discs a snapshot may hold (output.snapshot_fields), one row each: the fields of for_each_field
// in its order, then the snapshot-only ones (kRankField, the owner rank: run metadata, never in a checkpoint), with
// how a file stores them (FORMAT.md; the XDMF side-car's attributes come from these rows).
struct DiscFieldInfo {
  std::string name;
  const char* number;  // "Float", "Int" or "UInt" (XDMF's NumberType)
  int bytes;           // per component
  int components;      // 2 for a vector
};
inline constexpr const char* kRankField = "rank";
inline constexpr const char* kPositionField = "position";  // the geometry of the XDMF side-car: always written
inline constexpr const char* kIndexField = "index";        // a snapshot's row numbers (its XDMF vertex cells)
std::vector<DiscFieldInfo> snapshot_fields();
// Their names ("position velocity ... rank"): the words output.snapshot_fields allows.
std::vector<std::string> snapshot_field_names();

}  // namespace rondel
