#include "app/BondRecords.hpp"

#include <iterator>

#include "parallel/Hdf5File.hpp"

namespace rondel::bond_records {

RecordTable segments(const BondContext& c, const ContactTable& bonds) {
  const MinimumImage image(c.domain);
  RecordTable t;
  t.segments = true;
  for (const char* name : kSegmentReals) t.reals.push_back({name, {}});
  t.vectors = {{"end1", {}}, {"end2", {}}};
  for (std::size_t r = 0; r < bonds.size(); ++r) {
    const auto i = static_cast<std::size_t>(bonds.i1[r]), j = static_cast<std::size_t>(bonds.i2[r]);
    if (i >= c.discs.n_owned()) continue;
    const BondState s{bonds.slot[0][r], bonds.slot[1][r], bonds.slot[2][r]};
    const BondStresses stress = BondStresses::of(bonds::row_geometry(c, bonds, r), s);
    const double values[] = {s.Fb_n, s.Fb_s, s.Mb, stress.sigma, stress.tau};
    static_assert(std::size(values) == std::size(kSegmentReals));
    for (std::size_t k = 0; k < std::size(values); ++k) t.reals[k].second.push_back(values[k]);
    t.key.push_back(bonds.key[r]);
    const Vec2 x1 = c.discs.position[i];
    t.vectors[0].second.push_back(x1);
    t.vectors[1].second.push_back(x1 + image.separation(x1, c.discs.position[j]));
  }
  return t;
}

RecordTable breaks(const std::vector<BondBreak>& records) {
  RecordTable t;
  for (const char* name : kBreakReals) t.reals.push_back({name, {}});
  for (const char* name : kBreakIntegers) t.integers.push_back({name, {}});
  t.vectors = {{kBreakPosition, {}}};
  for (const BondBreak& b : records) {
    t.key.push_back(b.key);
    t.reals[0].second.push_back(b.sigma);
    t.reals[1].second.push_back(b.tau);
    t.integers[0].second.push_back(b.step);
    t.integers[1].second.push_back(static_cast<std::int64_t>(b.mode));
    t.vectors[0].second.push_back(b.position);
  }
  return t;
}

void read_breaks(const std::string& path, std::vector<BondBreak>& out, const Communicator& comm) {
  Hdf5File f(path, Hdf5File::Mode::read, comm);
  f.run([&] {
    if (!f.exists("/breaks")) return;
    const std::uint64_t total = f.rows("/breaks/key");
    const std::uint64_t begin = block_begin(total, comm.rank(), comm.size());
    const std::uint64_t count = block_begin(total, comm.rank() + 1, comm.size()) - begin;
    const auto key = f.read<ContactKey>("/breaks/key", begin, count);
    const auto position = f.read<Vec2>(std::string("/breaks/") + kBreakPosition, begin, count);
    const auto sigma = f.read<double>(std::string("/breaks/") + kBreakReals[0], begin, count);
    const auto tau = f.read<double>(std::string("/breaks/") + kBreakReals[1], begin, count);
    const auto step = f.read<std::int64_t>(std::string("/breaks/") + kBreakIntegers[0], begin, count);
    const auto mode = f.read<std::int64_t>(std::string("/breaks/") + kBreakIntegers[1], begin, count);
    for (std::uint64_t k = 0; k < count; ++k)
      out.push_back({key[k], position[k], static_cast<BondMode>(mode[k]), sigma[k], tau[k], step[k]});
  });
}

}  // namespace rondel::bond_records
