#include "parallel/StateFile.hpp"

#include <algorithm>
#include <sstream>
#include <string_view>
#include <type_traits>

#include "core/Errors.hpp"
#include "parallel/CanonicalOrder.hpp"
#include "parallel/Hdf5File.hpp"
#include "parallel/RecordPacking.hpp"
#include "rondel/Version.hpp"

namespace rondel {

namespace {

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
  return s;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string x;
  while (std::getline(in, x, ','))
    if (!x.empty()) out.push_back(x);
  return out;
}

void write_discs(Hdf5File& f, DiscStore& discs, const Communicator& comm, const std::vector<std::string>& fields) {
  ByteBuffer records;
  std::vector<std::int64_t> keys(discs.gid.begin(), discs.gid.begin() + discs.n_owned());
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    pack_disc(discs, i, kCheckpoint, records);
    records.put(static_cast<std::int32_t>(comm.rank()));
  }
  const std::size_t bytes = record_bytes(discs, kCheckpoint) + sizeof(std::int32_t);
  const OrderedBlock block = order_into_blocks(keys, records.bytes, bytes, comm);
  DiscStore ordered;
  std::vector<std::int32_t> rank;
  ByteReader r(block.records.data(), block.records.size());
  for (std::uint64_t k = 0; k < block.count; ++k) {
    append_disc(ordered, kCheckpoint, r);
    rank.push_back(r.get<std::int32_t>());
  }
  f.create_group("/discs");
  ordered.for_each_field([&](const char* name, unsigned uses, auto& field) {
    const bool wanted = fields.empty() || std::find(fields.begin(), fields.end(), name) != fields.end();
    if ((uses & kCheckpoint) && wanted) f.write(std::string("/discs/") + name, field, block.total, block.offset);
  });
  // The owner rank is run metadata: in snapshots on request (for pictures), never in checkpoints.
  if (!fields.empty() && std::find(fields.begin(), fields.end(), "rank") != fields.end())
    f.write("/discs/rank", rank, block.total, block.offset);
  // A snapshot's row numbers, the connectivity of its XDMF vertex cells (without cells ParaView shows
  // nothing on Apply).
  if (!fields.empty()) {
    std::vector<std::int64_t> index(block.count);
    for (std::uint64_t k = 0; k < block.count; ++k) index[k] = static_cast<std::int64_t>(block.offset + k);
    f.write("/discs/index", index, block.total, block.offset);
  }
}

// Rows this rank books (disc 1 owned), with state, in ascending key order over all ranks.
void write_rows(Hdf5File& f, const std::string& group, const ContactTable& rows, std::size_t n_owned,
                const Communicator& comm) {
  std::vector<ContactKey> keys;
  ByteBuffer records;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (static_cast<std::size_t>(rows.i1[r]) >= n_owned || !rows.has_state(r)) continue;
    keys.push_back(rows.key[r]);
    pack_row(rows, r, records);
  }
  const OrderedBlock block = order_into_blocks(keys, records.bytes, row_bytes(rows), comm);
  ContactTable ordered(rows.slot_names(), rows.has_moment());
  ByteReader reader(block.records.data(), block.records.size());
  for (std::uint64_t k = 0; k < block.count; ++k) unpack_row(ordered, reader);
  f.create_group(group);
  f.create_group(group + "/history");
  ordered.for_each_column([&](std::string_view name, unsigned uses, const auto& column) {
    if (uses & kColumnRecord) f.write(group + "/" + std::string(name), column, block.total, block.offset);
  });
}

void write_walls(Hdf5File& f, const WallSet& walls, const Communicator& comm) {
  f.create_group("/walls");
  const std::uint64_t n = walls.size();
  std::vector<std::int32_t> kind, material;
  std::vector<std::int64_t> contacts;
  std::vector<double> normal_force;
  std::vector<Vec2> p0, p1, normal, velocity, force;
  if (comm.root())
    for (const Wall& w : walls) {
      kind.push_back(w.kind == Wall::Kind::line ? 0 : 1);
      material.push_back(w.material);
      p0.push_back(w.p0), p1.push_back(w.p1), normal.push_back(w.normal), velocity.push_back(w.velocity);
      force.push_back(w.force), normal_force.push_back(w.normal_force), contacts.push_back(w.contacts);
    }
  f.write("/walls/kind", kind, n, 0);
  f.write("/walls/p0", p0, n, 0);
  f.write("/walls/p1", p1, n, 0);
  f.write("/walls/normal", normal, n, 0);
  f.write("/walls/velocity", velocity, n, 0);
  f.write("/walls/force", force, n, 0);
  f.write("/walls/normal_force", normal_force, n, 0);
  f.write("/walls/contacts", contacts, n, 0);
  f.write("/walls/material", material, n, 0);
}

}  // namespace

void write_state_file(const std::string& path, const StateHeader& h, DiscStore& discs, const ContactTable& pairs,
                      const ContactTable& wall_rows, const WallSet& walls, const Communicator& comm,
                      const std::vector<std::string>& fields, double wall_seconds) {
  Hdf5File f(path, Hdf5File::Mode::create, comm);
  f.write_attribute("/", "format", std::string("rondel"));
  f.write_attribute("/", "format_version", kStateFormatVersion);
  f.write_attribute("/", "kind", h.kind);
  f.write_attribute("/", "step", h.step);
  f.write_attribute("/", "time", h.time);
  f.write_attribute("/", "dt", h.dt);
  f.write_attribute("/", "normal_law", h.normal_law);
  f.write_attribute("/", "tangential_law", h.tangential_law);
  f.write_attribute("/", "rolling_law", h.rolling_law);
  f.write_attribute("/", "history_slots", join(h.slots));
  f.write_attribute("/", "config", h.config);
  f.create_group("/materials");
  f.write_attribute("/materials", "table", h.materials);
  write_discs(f, discs, comm, fields);
  if (fields.empty()) {
    write_rows(f, "/contacts", pairs, discs.n_owned(), comm);
    write_rows(f, "/wall_contacts", wall_rows, discs.n_owned(), comm);
  }
  write_walls(f, walls, comm);
  f.write_attribute("/walls", "box_width0", h.box_width0);
  f.write_attribute("/walls", "box_height0", h.box_height0);
  f.create_group("/ledger");
  h.ledger.for_each_term(
      [&f](const LedgerTermInfo& t, double value) { f.write_attribute("/ledger", std::string(t.name), value); });
  f.create_group("/run_metadata");
  f.write_attribute("/run_metadata", "ranks", static_cast<std::int64_t>(comm.size()));
  f.write_attribute("/run_metadata", "wall_seconds", wall_seconds);
  f.write_attribute("/run_metadata", "rondel_version", std::string(kRondelVersion));
  f.write_attribute("/run_metadata", "rondel_commit", std::string(kRondelCommit));
  f.write_attribute("/", "complete", std::int64_t{1});  // last: a file without it was cut short
}

StateHeader read_state_header(const std::string& path, const Communicator& comm) {
  Hdf5File f(path, Hdf5File::Mode::read, comm);
  if (!f.has_attribute("/", "format") || f.read_string_attribute("/", "format") != "rondel")
    throw InputError("'" + path + "' is not a Rondel checkpoint or snapshot (no format = rondel attribute)");
  const std::int64_t version = f.read_int_attribute("/", "format_version");
  if (version != kStateFormatVersion)
    throw InputError("'" + path + "' has format version " + std::to_string(version) + "; this Rondel reads version " +
                     std::to_string(kStateFormatVersion));
  if (!f.has_attribute("/", "complete")) throw InputError("'" + path + "' is incomplete (its writer was interrupted)");
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
  if (f.has_attribute("/materials", "table")) h.materials = f.read_string_attribute("/materials", "table");
  h.box_width0 = f.read_double_attribute("/walls", "box_width0");
  h.box_height0 = f.read_double_attribute("/walls", "box_height0");
  h.ledger.for_each_term([&f](const LedgerTermInfo& t, double& value) {
    const std::string name(t.name);
    if (f.has_attribute("/ledger", name)) value = f.read_double_attribute("/ledger", name);
  });
  return h;
}

std::uint64_t state_file_discs(const std::string& path, const Communicator& comm) {
  return Hdf5File(path, Hdf5File::Mode::read, comm).rows("/discs/position");
}

std::vector<std::string> state_file_disc_datasets(const std::string& path, const Communicator& comm) {
  Hdf5File f(path, Hdf5File::Mode::read, comm);
  std::vector<std::string> found;
  DiscStore fields;
  fields.for_each_field([&](const char* name, unsigned uses, auto&) {
    if ((uses & kCheckpoint) && f.exists(std::string("/discs/") + name)) found.emplace_back(name);
  });
  for (const char* extra : {"rank", "index"})
    if (f.exists(std::string("/discs/") + extra)) found.emplace_back(extra);
  return found;
}

void read_state_discs(const std::string& path, DiscStore& discs, const Communicator& comm) {
  Hdf5File f(path, Hdf5File::Mode::read, comm);
  const std::uint64_t total = f.rows("/discs/gid");
  const std::uint64_t begin = block_begin(total, comm.rank(), comm.size());
  const std::uint64_t count = block_begin(total, comm.rank() + 1, comm.size()) - begin;
  discs.clear();
  discs.for_each_field([&](const char* name, unsigned uses, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    if (!(uses & kCheckpoint)) return;
    const std::string set = std::string("/discs/") + name;
    if (!f.exists(set)) throw InputError("'" + path + "' has no dataset " + set + " (a snapshot without every field?)");
    field = f.read<T>(set, begin, count);
  });
  discs.set_owned_count(count);
}

void read_state_rows(const std::string& path, ContactTable& pairs, ContactTable& wall_rows, const Communicator& comm) {
  Hdf5File f(path, Hdf5File::Mode::read, comm);
  for (auto [group, table] :
       {std::pair{std::string("/contacts"), &pairs}, std::pair{std::string("/wall_contacts"), &wall_rows}}) {
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

WallSet read_state_walls(const std::string& path, const Communicator& comm) {
  Hdf5File f(path, Hdf5File::Mode::read, comm);
  const std::uint64_t n = f.rows("/walls/kind");
  // Every rank reads the whole (small) wall table and checks its own copy.
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
  WallSet walls(n);
  for (std::uint64_t w = 0; w < n; ++w) {
    walls[w].material = material[w];
    walls[w].kind = kind[w] == 0 ? Wall::Kind::line : Wall::Kind::segment;
    walls[w].p0 = p0[w], walls[w].p1 = p1[w], walls[w].normal = normal[w], walls[w].velocity = velocity[w];
    walls[w].force = force[w], walls[w].normal_force = normal_force[w], walls[w].contacts = contacts[w];
  }
  return walls;
}

void route_rows_to_owners(ContactTable& rows, bool both_ends, const DiscStore& discs, const Communicator& comm) {
  // A directory of (gid, owner rank) from every rank's owned discs.
  ByteBuffer mine;
  for (std::size_t i = 0; i < discs.n_owned(); ++i) mine.put(discs.gid[i]);
  std::vector<std::pair<std::int64_t, int>> owner;
  const auto all = comm.all_gather(mine);
  for (int r = 0; r < comm.size(); ++r) {
    ByteReader reader(all[r].bytes.data(), all[r].bytes.size());
    while (!reader.done()) owner.emplace_back(reader.get<std::int64_t>(), r);
  }
  std::sort(owner.begin(), owner.end());
  auto rank_of = [&owner](std::int64_t gid) {
    const auto it = std::lower_bound(owner.begin(), owner.end(), std::make_pair(gid, -1));
    return (it != owner.end() && it->first == gid) ? it->second : -1;
  };
  std::vector<ByteBuffer> out(static_cast<std::size_t>(comm.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const int a = rank_of(rows.key[r].lo), b = both_ends ? rank_of(rows.key[r].hi) : -1;
    if (a >= 0) pack_row(rows, r, out[a]);
    if (b >= 0 && b != a) pack_row(rows, r, out[b]);
  }
  rows.clear();
  for (const ByteBuffer& b : comm.all_to_all(out)) {
    ByteReader reader(b.bytes.data(), b.bytes.size());
    while (!reader.done()) unpack_row(rows, reader);
  }
  rows.sort_unique_by_key();
}

}  // namespace rondel
