#include "parallel/StateFile.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <type_traits>

#include "core/Errors.hpp"
#include "core/WallKinds.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/CanonicalOrder.hpp"
#include "parallel/Hdf5File.hpp"
#include "parallel/RecordPacking.hpp"
#include "rondel/Version.hpp"

namespace rondel {

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
  return s;
}

void write_walls(Hdf5File& f, const WallSet& walls, const Communicator& comm) {
  f.create_group("/walls");
  const std::uint64_t n = walls.size();
  std::vector<std::int32_t> kind, material;
  std::vector<std::int64_t> contacts;
  std::vector<double> normal_force, radius, omega, angle;
  std::vector<Vec2> p0, p1, normal, velocity, force, centre;
  if (comm.root())
    for (const Wall& w : walls) {
      kind.push_back(static_cast<std::int32_t>(w.kind));  // the kind's code (core/WallKinds.hpp)
      material.push_back(w.material);
      p0.push_back(w.p0), p1.push_back(w.p1), normal.push_back(w.normal), velocity.push_back(w.velocity);
      force.push_back(w.force), normal_force.push_back(w.normal_force), contacts.push_back(w.contacts);
      centre.push_back(w.centre), radius.push_back(w.radius), omega.push_back(w.omega), angle.push_back(w.angle);
    }
  f.write("/walls/kind", kind, n, 0);
  // The names of the codes of /walls/kind, in code order: readers decode the kinds with them (FORMAT.md).
  std::string names;
  for (const std::string& name : WallKinds::names_by_code()) names += (names.empty() ? "" : " ") + name;
  f.write_attribute("/walls", "kind_names", names);
  f.write("/walls/p0", p0, n, 0);
  f.write("/walls/p1", p1, n, 0);
  f.write("/walls/normal", normal, n, 0);
  f.write("/walls/velocity", velocity, n, 0);
  f.write("/walls/force", force, n, 0);
  f.write("/walls/normal_force", normal_force, n, 0);
  f.write("/walls/contacts", contacts, n, 0);
  f.write("/walls/material", material, n, 0);
  f.write("/walls/centre", centre, n, 0);
  f.write("/walls/radius", radius, n, 0);
  f.write("/walls/omega", omega, n, 0);
  f.write("/walls/angle", angle, n, 0);
}

// The peak over the writers and routings of this process (peak_checkpoint_structure_bytes()).
std::size_t g_peak_bytes = 0;
void note_bytes(std::size_t bytes) { g_peak_bytes = std::max(g_peak_bytes, bytes); }

void write_header(Hdf5File& f, const StateHeader& h) {
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
}

// Rows of `t` that this rank writes (write_rows books them: disc 1 owned, with state).
std::int64_t booked_rows(const ContactTable& t, std::size_t n_owned) {
  std::int64_t n = 0;
  for (std::size_t r = 0; r < t.size(); ++r) n += static_cast<std::size_t>(t.i1[r]) < n_owned && t.has_state(r);
  return n;
}

// The file's size, estimated from above (collective): every record (a snapshot's index and owner columns
// too), the walls, the text attributes, and HDF5's metadata (about 6 kB for a checkpoint: 64 kB), plus 2 %.
// Bytes of one record of a RecordTable (its key and a value of each column).
std::size_t record_bytes(const RecordTable& t) {
  return sizeof(ContactKey) + 8 * (t.reals.size() + t.integers.size()) + sizeof(Vec2) * t.vectors.size();
}

std::uint64_t estimate_file_bytes(const StateHeader& h, DiscStore& discs, const ContactTable& pairs,
                                  const ContactTable& wall_rows, const StateExtras& extras, std::size_t walls,
                                  bool snapshot, const Communicator& comm) {
  const ContactTable* bonds = snapshot ? nullptr : extras.bonds;
  const std::size_t n = discs.n_owned();
  double local = static_cast<double>(n) * static_cast<double>(record_bytes(discs, kCheckpoint) + (snapshot ? 12 : 0)) +
                 static_cast<double>(booked_rows(pairs, n)) * static_cast<double>(row_bytes(pairs)) +
                 static_cast<double>(booked_rows(wall_rows, n)) * static_cast<double>(row_bytes(wall_rows));
  if (bonds) local += static_cast<double>(booked_rows(*bonds, n)) * static_cast<double>(row_bytes(*bonds));
  for (const RecordTable* t : {extras.bond_segments, extras.breaks})  // with points and index
    if (t) local += static_cast<double>(t->size()) * static_cast<double>(record_bytes(*t) + 48);
  const double fixed =
      static_cast<double>(walls) * 256.0 + static_cast<double>(h.config.size() + h.materials.size()) + 64.0 * 1024.0;
  return static_cast<std::uint64_t>(1.02 * (comm.sum(local) + fixed));
}

bool listed(const std::vector<std::string>& fields, const char* name) {
  return std::find(fields.begin(), fields.end(), name) != fields.end();
}

}  // namespace

template <class T, class Local>
void StateWriter::write_column(Hdf5File& f, const std::string& name, Local&& local, const Communicator& comm) {
  const double t0 = now();
  order_.exchange(
      sizeof(T), [&local](std::size_t i, char* out) { std::memcpy(out, local(i), sizeof(T)); }, comm);
  times_.order += now() - t0;
  write_arranged<T>(f, name, local, 0);
}

template <class T, class Local>
void StateWriter::write_arranged(Hdf5File& f, const std::string& name, Local&& local, std::size_t at) {
  // In pieces of at most 2^20 rows: the copy in file order is 16 MiB at most, whatever this rank's block.
  constexpr std::uint64_t kPiece = std::uint64_t{1} << 20;
  std::uint64_t n = order_.count();
  try {
    resize_buffer(column_, (std::min(n, kPiece) * sizeof(T) + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t));
  } catch (...) {
    f.defer_error(std::current_exception());  // thrown on every rank by the write below
    n = 0;
  }
  T* out = reinterpret_cast<T*>(column_.data());
  f.write_pieces<T>(name, n, order_.total(), order_.offset(), kPiece, [&](std::uint64_t first, std::uint64_t count) {
    const double t0 = now();
    for (std::uint64_t k = first; k < first + count; ++k) {
      const void* from = order_.is_local(k) ? static_cast<const void*>(local(order_.local_index(k)))
                                            : static_cast<const void*>(order_.received(k) + at);
      std::memcpy(out + (k - first), from, sizeof(T));
    }
    times_.columns += now() - t0;
    return static_cast<const T*>(out);
  });
}

void StateWriter::write_discs(Hdf5File& f, DiscStore& discs, const Communicator& comm,
                              const std::vector<std::string>& fields) {
  const double t0 = now();
  const std::int64_t* gid = discs.gid.data();
  order_.arrange_keys(
      discs.n_owned(),
      [gid](std::size_t i) {
        return OrderKey{gid[i], 0};
      },
      comm);
  times_.order += now() - t0;
  f.create_group("/discs");
  discs.for_each_field([&](const char* name, unsigned uses, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    if ((uses & kCheckpoint) && (fields.empty() || listed(fields, name)))
      write_column<T>(
          f, std::string("/discs/") + name, [&field](std::size_t i) { return &field[i]; }, comm);
  });
  // The owner rank is run metadata: in snapshots on request (for pictures), never in checkpoints.
  const std::int32_t me = comm.rank();
  if (!fields.empty() && listed(fields, kRankField))
    write_column<std::int32_t>(
        f, std::string("/discs/") + kRankField, [&me](std::size_t) { return &me; }, comm);
  // A snapshot's row numbers, the connectivity of its XDMF vertex cells (without cells ParaView shows
  // nothing on Apply).
  if (!fields.empty()) {
    std::vector<std::int64_t> index(order_.count());
    for (std::uint64_t k = 0; k < order_.count(); ++k) index[k] = static_cast<std::int64_t>(order_.offset() + k);
    f.write(std::string("/discs/") + kIndexField, index, order_.total(), order_.offset());
  }
  note(checkpoint_buffer_bytes());
}

// Rows this rank books (disc 1 owned), with state, in ascending key order over all ranks.
void StateWriter::write_rows(Hdf5File& f, const std::string& group, const ContactTable& rows, std::size_t n_owned,
                             const Communicator& comm) {
  resize_buffer(booked_, rows.size());  // room for every row: no doubling while booking
  booked_.clear();
  for (std::size_t r = 0; r < rows.size(); ++r)
    if (static_cast<std::size_t>(rows.i1[r]) < n_owned && rows.has_state(r))
      booked_.push_back(static_cast<std::uint32_t>(r));
  const auto key_of = [&](std::size_t i) {
    const ContactKey& k = rows.key[booked_[i]];
    return OrderKey{k.lo, k.hi};
  };
  const double t0 = now();
  order_.arrange_keys(booked_.size(), key_of, comm);
  times_.order += now() - t0;
  f.create_group(group);
  f.create_group(group + "/history");
  rows.for_each_column([&](std::string_view name, unsigned uses, const auto& column) {
    using T = typename std::decay_t<decltype(column)>::value_type;
    if (uses & kColumnRecord)
      write_column<T>(
          f, group + "/" + std::string(name), [&](std::size_t i) { return &column[booked_[i]]; }, comm);
  });
  note(checkpoint_buffer_bytes());
}

void StateWriter::write_records(Hdf5File& f, const std::string& group, const RecordTable& t, const Communicator& comm) {
  // A record: the key, then each column's value in the order reals, integers, vectors.
  const double t0 = now();
  order_.arrange(
      t.size(),
      [&](std::size_t i) {
        return OrderKey{t.key[i].lo, t.key[i].hi};
      },
      record_bytes(t),
      [&](std::size_t i, char* out) {
        std::memcpy(out, &t.key[i], sizeof(ContactKey));
        out += sizeof(ContactKey);
        const auto put = [&](const auto& columns) {
          for (const auto& [name, values] : columns) {
            std::memcpy(out, &values[i], sizeof values[i]);
            out += sizeof values[i];
          }
        };
        put(t.reals), put(t.integers), put(t.vectors);
      },
      comm);
  times_.order += now() - t0;
  f.create_group(group);
  write_arranged<ContactKey>(
      f, group + "/key", [&](std::size_t i) { return &t.key[i]; }, 0);
  std::size_t at = sizeof(ContactKey);
  std::array<std::size_t, 2> end_at{};             // the ends' byte offsets in a record
  std::array<const std::vector<Vec2>*, 2> ends{};  // and their local columns
  const auto columns = [&](const auto& list) {
    for (const auto& [name, values] : list) {
      using T = typename std::decay_t<decltype(values)>::value_type;
      bool end = false;  // a segment's ends are written as its points only
      if constexpr (std::is_same_v<T, Vec2>)
        for (std::size_t e = 0; e < 2; ++e)
          if (t.segments && name == (e == 0 ? "end1" : "end2")) end_at[e] = at, ends[e] = &values, end = true;
      if (!end)
        write_arranged<T>(
            f, group + "/" + name, [&values](std::size_t i) { return &values[i]; }, at);
      at += sizeof(T);
    }
  };
  columns(t.reals), columns(t.integers), columns(t.vectors);
  // The XDMF cells: each record's two ends as points 2k and 2k + 1 (segments), or the row numbers.
  const std::uint64_t per = t.segments ? 2 : 1, count = order_.count(), offset = order_.offset();
  std::vector<std::int64_t> index(per * count);
  for (std::uint64_t k = 0; k < index.size(); ++k) index[k] = static_cast<std::int64_t>(per * offset + k);
  f.write(group + "/index", index, per * order_.total(), per * offset);
  if (!t.segments) return;
  if (!ends[0] || !ends[1]) throw std::logic_error("a RecordTable of segments without the columns end1 and end2");
  std::vector<Vec2> points(2 * count);
  for (std::uint64_t k = 0; k < count; ++k)
    for (std::size_t e = 0; e < 2; ++e) {
      const void* from = order_.is_local(k) ? static_cast<const void*>(&(*ends[e])[order_.local_index(k)])
                                            : static_cast<const void*>(order_.received(k) + end_at[e]);
      std::memcpy(&points[2 * k + e], from, sizeof(Vec2));
    }
  f.write(group + "/points", points, 2 * order_.total(), 2 * offset);
}

std::size_t StateWriter::checkpoint_buffer_bytes() const {
  return order_.capacity_bytes() + booked_.capacity() * sizeof(booked_[0]) + column_.capacity() * sizeof(column_[0]);
}

void StateWriter::note(std::size_t bytes) {
  peak_bytes_ = std::max(peak_bytes_, bytes);
  note_bytes(bytes);
}

void StateWriter::release() {
  order_.release();
  rondel::release(booked_, column_);
}

void StateWriter::write(const std::string& path, const StateHeader& h, DiscStore& discs, const ContactTable& pairs,
                        const ContactTable& wall_rows, const WallSet& walls, const Communicator& comm,
                        const std::vector<std::string>& fields, double wall_seconds, const StateExtras& extras) {
  times_ = {};
  const double t0 = now();
  Hdf5File f(path, Hdf5File::Mode::create, comm,
             estimate_file_bytes(h, discs, pairs, wall_rows, extras, walls.size(), !fields.empty(), comm));
  f.run([&] {
    write_header(f, h);
    write_discs(f, discs, comm, fields);
    if (fields.empty()) {
      write_rows(f, "/contacts", pairs, discs.n_owned(), comm);
      write_rows(f, "/wall_contacts", wall_rows, discs.n_owned(), comm);
      if (extras.bonds) write_rows(f, "/bonds", *extras.bonds, discs.n_owned(), comm);
    } else if (extras.bond_segments) {
      write_records(f, "/bonds", *extras.bond_segments, comm);
    }
    if (extras.breaks) write_records(f, "/breaks", *extras.breaks, comm);
    write_walls(f, walls, comm);
    f.write_attribute("/walls", "box_width0", h.box_width0);
    f.write_attribute("/walls", "box_height0", h.box_height0);
    f.create_group("/cell");
    for (const auto& [name, value] : cell_attributes(h.cell)) f.write_attribute("/cell", name, *value);
    f.write_attribute("/cell", "flips", h.flips);
    f.create_group("/ledger");
    h.ledger.for_each_term(
        [&f](const LedgerTermInfo& t, double value) { f.write_attribute("/ledger", std::string(t.name), value); });
    f.create_group("/run_metadata");
    f.write_attribute("/run_metadata", "ranks", static_cast<std::int64_t>(comm.size()));
    // Rank 0's clock: every rank writes the same value (each keeps its own copy of the metadata).
    f.write_attribute("/run_metadata", "wall_seconds", comm.max(comm.root() ? wall_seconds : 0.0));
    f.write_attribute("/run_metadata", "rondel_version", std::string(kRondelVersion));
    f.write_attribute("/run_metadata", "rondel_commit", std::string(kRondelCommit));
    f.write_attribute("/run_metadata", "run_id", h.run_id);
    // Over every attribute written above (the datasets' checksums included), as stored; in a group of its
    // own, which a comparison of two files leaves out with the run metadata and the ledger it covers.
    const std::uint64_t digest = f.attribute_digest();
    f.create_group("/integrity");
    f.write_attribute("/integrity", "attributes_checksum", static_cast<std::int64_t>(digest));
    f.write_attribute("/", "complete", std::int64_t{1});  // last: a file without it was cut short
  });
  release();
  times_.hdf5 += now() - t0 - times_.order - times_.columns;
}

void write_state_file(const std::string& path, const StateHeader& header, DiscStore& discs, const ContactTable& pairs,
                      const ContactTable& wall_rows, const WallSet& walls, const Communicator& comm,
                      const std::vector<std::string>& fields, double wall_seconds) {
  StateWriter().write(path, header, discs, pairs, wall_rows, walls, comm, fields, wall_seconds, {});
}

std::size_t peak_checkpoint_structure_bytes() { return g_peak_bytes; }

void note_checkpoint_structure_bytes(std::size_t bytes) { note_bytes(bytes); }

}  // namespace rondel
