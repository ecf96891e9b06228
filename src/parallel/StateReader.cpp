// The reading side of the checkpoint and snapshot layout (FORMAT.md): the header with its checks, the whole-file
// verification that --resume relies on, and each rank's block of discs, contact rows and the walls. The writer
// and the routing of rows to their owners are in StateFile.cpp.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string_view>
#include <type_traits>

#include "core/ConfigRead.hpp"
#include "core/Errors.hpp"
#include "core/Format.hpp"
#include "core/MemoryLimit.hpp"
#include "core/WallKinds.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/CanonicalOrder.hpp"
#include "parallel/Hdf5File.hpp"
#include "parallel/RecordPacking.hpp"
#include "parallel/StateFile.hpp"

namespace rondel {

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string x;
  while (std::getline(in, x, ','))
    if (!x.empty()) out.push_back(x);
  return out;
}

}  // namespace

namespace {

StateHeader read_header(const Hdf5File& f, const std::string& path) {
  if (!f.has_attribute("/", "format") || f.read_string_attribute("/", "format") != "rondel")  // FORMAT.md
    throw InputError("'" + path + "' is not a Rondel checkpoint or snapshot (no format = rondel attribute)");
  const std::int64_t version = f.read_int_attribute("/", "format_version");
  if (version < kOldestReadableFormatVersion || version > kStateFormatVersion)
    throw InputError("'" + path + "' has format version " + std::to_string(version) + "; this Rondel reads versions " +
                     std::to_string(kOldestReadableFormatVersion) + " to " + std::to_string(kStateFormatVersion));
  if (!f.has_attribute("/", "complete")) throw InputError("'" + path + "' is incomplete (its writer was interrupted)");
  if (const std::int64_t complete = f.read_int_attribute("/", "complete"); complete != 1)
    throw InputError("'" + path + "' has complete = " + std::to_string(complete) +
                     " (1 expected): the file is damaged");
  if (version >= 4) {
    if (!f.has_attribute("/integrity", "attributes_checksum"))
      throw InputError("'" + path + "' has no /integrity attributes_checksum (format version " +
                       std::to_string(version) + " has one): the file is damaged");
    const auto stored = static_cast<std::uint64_t>(f.read_int_attribute("/integrity", "attributes_checksum"));
    if (stored != f.attribute_digest())
      throw InputError("'" + path +
                       "': its attributes (the header, the configuration, the ledger, the walls' references or a "
                       "dataset's checksum) fail their checksum: the file is corrupted");
  }
  StateHeader h;
  h.kind = f.read_string_attribute("/", "kind");
  h.step = f.read_int_attribute("/", "step");
  h.time = f.read_double_attribute("/", "time");
  h.dt = f.read_double_attribute("/", "dt");
  h.normal_law = f.read_string_attribute("/", "normal_law");
  h.tangential_law = f.read_string_attribute("/", "tangential_law");
  h.rolling_law = f.read_string_attribute("/", "rolling_law");
  h.slots = split(f.read_string_attribute("/", "history_slots"));
  h.config = f.read_string_attribute("/", "config");
  if (f.has_attribute("/run_metadata", "run_id")) h.run_id = f.read_string_attribute("/run_metadata", "run_id");
  if (f.has_attribute("/materials", "table")) h.materials = f.read_string_attribute("/materials", "table");
  h.box_width0 = f.read_double_attribute("/walls", "box_width0");
  h.box_height0 = f.read_double_attribute("/walls", "box_height0");
  if (version >= 5) {
    h.has_cell = true;
    Domain& c = h.cell;
    for (const auto& [name, value] : cell_attributes(c)) {
      *value = f.read_double_attribute("/cell", name);
      if (!std::isfinite(*value))
        throw InputError("'" + path + "': /cell " + name + " = " + std::to_string(*value) + " is not finite");
    }
    if (!(c.xhi > c.xlo && c.yhi > c.ylo && std::fabs(c.tilt) <= 0.5 * c.length_x() * (1.0 + 1e-12)))
      throw InputError("'" + path +
                       "': /cell is not a cell (xhi > xlo, yhi > ylo and |tilt| <= (xhi - xlo) / 2 "
                       "expected)");
    h.flips = f.read_int_attribute("/cell", "flips");
  }
  h.ledger.for_each_term([&f](const LedgerTermInfo& t, double& value) {
    const std::string name(t.name);
    if (f.has_attribute("/ledger", name)) value = f.read_double_attribute("/ledger", name);
  });
  return h;
}

}  // namespace

StateHeader read_state_header(const std::string& path, const Communicator& comm) {
  Hdf5File f(path, Hdf5File::Mode::read, comm);
  StateHeader h;
  f.run([&] { h = read_header(f, path); });
  return h;
}

void verify_state_file(const std::string& path, const Communicator& comm) {
  Hdf5File f(path, Hdf5File::Mode::read, comm);
  f.run([&] {
    read_header(f, path);
    // A group's datasets have the rows of its first one (/discs/force as many as /discs/flags, ...);
    // a history group those of its table.
    std::vector<std::pair<std::string, std::uint64_t>> tables;
    for (const auto& [object, dataset] : f.objects()) {
      if (!dataset) continue;
      const std::string table = object.substr(0, object.find('/', 1));
      auto it = std::find_if(tables.begin(), tables.end(), [&](const auto& t) { return t.first == table; });
      if (it == tables.end()) it = tables.insert(tables.end(), {table, f.rows(object)});
      f.verify_dataset(object, it->second);
    }
  });
}

std::uint64_t state_file_discs(const std::string& path, const Communicator& comm) {
  return Hdf5File(path, Hdf5File::Mode::read, comm).rows("/discs/position");
}

std::int64_t state_file_rows(const std::string& path, const std::string& dataset, const Communicator& comm) {
  return static_cast<std::int64_t>(Hdf5File(path, Hdf5File::Mode::read, comm).rows(dataset));
}

std::vector<std::string> state_file_disc_datasets(const std::string& path, const Communicator& comm) {
  Hdf5File f(path, Hdf5File::Mode::read, comm);
  std::vector<std::string> found;
  DiscStore fields;
  fields.for_each_field([&](const char* name, unsigned uses, auto&) {
    if ((uses & kCheckpoint) && f.exists(std::string("/discs/") + name)) found.emplace_back(name);
  });
  for (const char* extra : {kRankField, kIndexField})
    if (f.exists(std::string("/discs/") + extra)) found.emplace_back(extra);
  f.close();
  return found;
}

namespace {

// The discs of a file are checked as the rows of a CSV scene are (core/SceneCsv.cpp), each rank its block
// (rows from `first`): the first bad row in the file is named on any rank count (the lowest failing rank's).
void check_disc_rows(const std::string& path, const DiscStore& d, std::uint64_t first) {
  for (std::size_t i = 0; i < d.n_owned(); ++i) {
    const auto refuse = [&](const char* set, const std::string& value, const char* allowed) {
      throw InputError("'" + path + "': /discs/" + set + " row " + std::to_string(first + i) + " (disc " +
                       std::to_string(d.gid[i]) + ") is " + value + ": " + allowed);
    };
    const auto vec = [](Vec2 v) {
      std::string s = fmt(v.x);  // built up in steps: GCC 12 warns (-Wrestrict, a false positive) on "(" + s
      s.insert(0, 1, '(');
      return s + ", " + fmt(v.y) + ")";
    };
    const auto finite = [](Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); };
    if (d.gid[i] < 0 || d.gid[i] >= kMaxGid)
      refuse("gid", std::to_string(d.gid[i]), "a disc id is an integer from 0 to 2^53 - 1");
    if (!(d.radius[i] > 0.0 && std::isfinite(d.radius[i])))
      refuse("radius", fmt(d.radius[i]), "a radius is finite and > 0");
    if (!(d.mass[i] > 0.0 && std::isfinite(d.mass[i]))) refuse("mass", fmt(d.mass[i]), "a mass is finite and > 0");
    if (!(d.inertia[i] > 0.0 && std::isfinite(d.inertia[i])))
      refuse("inertia", fmt(d.inertia[i]), "a moment of inertia is finite and > 0");
    if (!finite(d.position[i])) refuse("position", vec(d.position[i]), "a position is finite");
    if (!finite(d.velocity[i]) || std::hypot(d.velocity[i].x, d.velocity[i].y) > config::kLightSpeed)
      refuse("velocity", vec(d.velocity[i]), "a velocity is finite and below the speed of light");
    if (!finite(d.force[i])) refuse("force", vec(d.force[i]), "a force is finite");
    for (const auto& [set, v] : {std::pair{"omega", d.omega[i]}, {"theta", d.theta[i]}, {"torque", d.torque[i]}})
      if (!std::isfinite(v)) refuse(set, fmt(v), "a finite number");
  }
}

}  // namespace

void read_state_discs(const std::string& path, DiscStore& discs, const Communicator& comm) {
  Hdf5File f(path, Hdf5File::Mode::read, comm);
  const std::uint64_t total = f.rows("/discs/gid");
  const std::uint64_t begin = block_begin(total, comm.rank(), comm.size());
  const std::uint64_t count = block_begin(total, comm.rank() + 1, comm.size()) - begin;
  // This rank's block against the memory this process may use, before it is read (a restart's share; all of a
  // scene file's discs where every rank reads them).
  agree(comm, [&] {
    check_memory(static_cast<double>(count), 0.0, 0.0,
                 "the discs of '" + path + "' over " + std::to_string(comm.size()) + " rank(s), per rank");
  });
  discs.clear();
  f.run([&] {
    discs.for_each_field([&](const char* name, unsigned uses, auto& field) {
      using T = typename std::decay_t<decltype(field)>::value_type;
      if (!(uses & kCheckpoint)) return;
      const std::string set = std::string("/discs/") + name;
      if (!f.exists(set))
        throw InputError("'" + path + "' has no dataset " + set + " (a snapshot without every field?)");
      field = f.read<T>(set, begin, count);
    });
  });
  discs.set_owned_count(count);
  agree(comm, [&] { check_disc_rows(path, discs, begin); });
  check_unique_gids(discs, path, comm);
}

namespace {

void read_rows(const Hdf5File& f, const std::string& path, ContactTable& pairs, ContactTable& wall_rows,
               ContactTable* bonds, const Communicator& comm) {
  const bool has_bonds = f.exists("/bonds");
  if (has_bonds && !bonds)
    throw InputError("'" + path + "' holds parallel bonds (/bonds, " + std::to_string(f.rows("/bonds/key")) +
                     " of them): its run is resumed with its configuration's [bonds]");
  if (bonds && !has_bonds)
    throw InputError("'" + path +
                     "' holds no parallel bonds (/bonds), but the configuration has [bonds]: a run "
                     "resumes with the bonds it had; to bond the discs of a file, start a new run from it (scene.type "
                     "= file)");
  for (auto [group, table] :
       {std::pair{std::string("/contacts"), &pairs}, std::pair{std::string("/wall_contacts"), &wall_rows},
        std::pair{std::string("/bonds"), bonds}}) {
    if (!table) continue;
    table->clear();
    const std::uint64_t total = f.rows(group + "/key");
    const std::uint64_t begin = block_begin(total, comm.rank(), comm.size());
    const std::uint64_t count = block_begin(total, comm.rank() + 1, comm.size()) - begin;
    table->for_each_column([&](std::string_view name, unsigned uses, auto& column) {
      using T = typename std::decay_t<decltype(column)>::value_type;
      if (uses & kColumnRecord)
        column = f.read<T>(group + "/" + std::string(name), begin, count);
      else
        column.assign(count, unset_column_value<T>(uses));
    });
  }
}

// Every rank reads the whole (small) wall table and checks its own copy. A kind code that no kind of
// core/WallKinds.hpp has is refused, naming the file's kinds.
WallSet read_walls(const Hdf5File& f, const std::string& path) {
  const std::uint64_t n = f.rows("/walls/kind");
  const auto kind = f.read<std::int32_t>("/walls/kind", 0, n, 1, false);
  const auto p0 = f.read<Vec2>("/walls/p0", 0, n, 1, false), p1 = f.read<Vec2>("/walls/p1", 0, n, 1, false);
  const auto normal = f.read<Vec2>("/walls/normal", 0, n, 1, false);
  const auto velocity = f.read<Vec2>("/walls/velocity", 0, n, 1, false);
  const auto force = f.read<Vec2>("/walls/force", 0, n, 1, false);
  const auto normal_force = f.read<double>("/walls/normal_force", 0, n, 1, false);
  const auto contacts = f.read<std::int64_t>("/walls/contacts", 0, n, 1, false);
  // Files written before the materials have no /walls/material: every wall is of material 0.
  const auto material = f.rows("/walls/material") == n ? f.read<std::int32_t>("/walls/material", 0, n, 1, false)
                                                       : std::vector<std::int32_t>(n, 0);
  // Files before version 3 have no rotating walls and no circles: centre, radius, omega and angle read as 0.
  const bool turning = f.rows("/walls/centre") == n;
  const auto centre = turning ? f.read<Vec2>("/walls/centre", 0, n, 1, false) : std::vector<Vec2>(n);
  const auto radius = turning ? f.read<double>("/walls/radius", 0, n, 1, false) : std::vector<double>(n, 0.0);
  const auto omega = turning ? f.read<double>("/walls/omega", 0, n, 1, false) : std::vector<double>(n, 0.0);
  const auto angle = turning ? f.read<double>("/walls/angle", 0, n, 1, false) : std::vector<double>(n, 0.0);
  WallSet walls(n);
  for (std::uint64_t w = 0; w < n; ++w) {
    walls[w].material = material[w];
    const std::optional<Wall::Kind> k = WallKinds::from_code(kind[w]);
    if (!k) {
      const auto names = WallKinds::names_by_code();
      std::string known;
      for (std::size_t code = 0; code < names.size(); ++code)
        known += (code ? ", " : "") + std::to_string(code) + " " + names[code];
      throw InputError("'" + path + "': wall " + std::to_string(w) + " has the kind " + std::to_string(kind[w]) +
                       " (/walls/kind), which no wall kind has (" + known + ")");
    }
    walls[w].kind = *k;
    walls[w].centre = centre[w], walls[w].radius = radius[w], walls[w].omega = omega[w], walls[w].angle = angle[w];
    walls[w].p0 = p0[w], walls[w].p1 = p1[w], walls[w].normal = normal[w], walls[w].velocity = velocity[w];
    walls[w].force = force[w], walls[w].normal_force = normal_force[w], walls[w].contacts = contacts[w];
  }
  return walls;
}

}  // namespace

void read_state_rows(const std::string& path, ContactTable& pairs, ContactTable& wall_rows, const Communicator& comm,
                     ContactTable* bonds) {
  Hdf5File f(path, Hdf5File::Mode::read, comm);
  f.run([&] { read_rows(f, path, pairs, wall_rows, bonds, comm); });
}

WallSet read_state_walls(const std::string& path, const Communicator& comm) {
  Hdf5File f(path, Hdf5File::Mode::read, comm);
  WallSet walls;
  f.run([&] { walls = read_walls(f, path); });
  return walls;
}

}  // namespace rondel
