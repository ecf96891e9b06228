#include "app/Checkpointing.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/Errors.hpp"

namespace rondel {

namespace fs = std::filesystem;

namespace {
// The files <prefix>*.h5 of `dir`, in ascending name order (= ascending step: the step is zero-padded).
std::vector<fs::path> h5_files(const fs::path& dir, const char* prefix) {
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n.rfind(prefix, 0) == 0 && e.path().extension() == ".h5") found.push_back(e.path());
  }
  std::sort(found.begin(), found.end());
  return found;
}
}  // namespace

Checkpointing::Checkpointing(std::string directory, int keep, std::vector<std::string> snapshot_fields,
                             const Communicator& comm)
    : dir_(std::move(directory)), keep_(keep), fields_(std::move(snapshot_fields)), comm_(comm) {}

std::string Checkpointing::file_name(const char* prefix, std::int64_t step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%010lld.h5", prefix, static_cast<long long>(step));
  return buf;
}

std::string Checkpointing::write_checkpoint(const StateHeader& header, DiscStore& discs, const ContactTable& pairs,
                                            const ContactTable& wall_rows, const WallSet& walls, double wall_seconds) {
  const fs::path final_path = fs::path(dir_) / file_name("checkpoint", header.step);
  std::string part_name = ".";  // hidden and never matched by checkpoint_*.h5 until complete
  part_name += file_name("checkpoint", header.step);
  part_name += ".part";
  const fs::path part = fs::path(dir_) / part_name;
  write_state_file(part.string(), header, discs, pairs, wall_rows, walls, comm_, {}, wall_seconds);
  comm_.barrier();
  if (comm_.root()) {
    fs::rename(part, final_path);
    const std::vector<fs::path> existing = h5_files(dir_, "checkpoint_");
    for (std::size_t k = 0; k + static_cast<std::size_t>(keep_) < existing.size(); ++k) fs::remove(existing[k]);
  }
  comm_.barrier();
  return final_path.string();
}

void Checkpointing::adopt_snapshots(std::int64_t step) {
  snapshots_.clear();
  for (const fs::path& p : h5_files(dir_, "snapshot_")) {
    try {
      const StateHeader h = read_state_header(p.string(), comm_);
      if (h.step > step) continue;
      snapshots_.push_back(
          {p.filename().string(), h.step, static_cast<std::int64_t>(state_file_discs(p.string(), comm_)), h.time});
    } catch (const InputError&) {
      // not a complete snapshot: left out of the series
    }
  }
}

void Checkpointing::remove_old_files() const {
  if (!comm_.root()) return;
  for (const auto& e : fs::directory_iterator(dir_)) {
    const std::string n = e.path().filename().string();
    const bool ours =
        ((n.rfind("checkpoint_", 0) == 0 || n.rfind("snapshot_", 0) == 0) && e.path().extension() == ".h5") ||
        n.rfind(".checkpoint_", 0) == 0 || n == "snapshots.xdmf";
    if (ours) fs::remove(e.path());
  }
}

std::string Checkpointing::write_snapshot(const StateHeader& header, DiscStore& discs, const WallSet& walls,
                                          std::int64_t n_discs) {
  const std::string name = file_name("snapshot", header.step);
  const ContactTable none;
  write_state_file((fs::path(dir_) / name).string(), header, discs, none, none, walls, comm_, fields_, 0.0);
  snapshots_.push_back({name, header.step, n_discs, header.time});
  if (comm_.root()) write_xdmf();
  return (fs::path(dir_) / name).string();
}

void Checkpointing::write_xdmf() const {
  std::ofstream x(fs::path(dir_) / "snapshots.xdmf");
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"discs\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  auto has = [this](const char* f) { return std::find(fields_.begin(), fields_.end(), f) != fields_.end(); };
  for (const Snapshot& s : snapshots_) {
    const std::string n = std::to_string(s.discs);
    auto item = [&](const std::string& set, const std::string& dims, const char* type, int precision) {
      return "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + type + "\" Precision=\"" +
             std::to_string(precision) + "\" Format=\"HDF\">" + s.file + ":/discs/" + set + "</DataItem>";
    };
    x << "   <Grid Name=\"step " << s.step << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << s.time << "\"/>\n"
      << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\" NodesPerElement=\"1\"/>\n"
      << "    <Geometry GeometryType=\"XY\">" << item("position", n + " 2", "Float", 8) << "</Geometry>\n";
    for (const char* f : {"radius", "omega", "theta", "mass"})
      if (has(f))
        x << "    <Attribute Name=\"" << f << "\" AttributeType=\"Scalar\" Center=\"Node\">" << item(f, n, "Float", 8)
          << "</Attribute>\n";
    for (const char* f : {"velocity", "force"})
      if (has(f))
        x << "    <Attribute Name=\"" << f << "\" AttributeType=\"Vector\" Center=\"Node\">"
          << item(f, n + " 2", "Float", 8) << "</Attribute>\n";
    for (const char* f : {"rank", "gid"})
      if (has(f))
        x << "    <Attribute Name=\"" << f << "\" AttributeType=\"Scalar\" Center=\"Node\">"
          << item(f, n, "Int", std::string(f) == "gid" ? 8 : 4) << "</Attribute>\n";
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
}

std::string Checkpointing::newest_checkpoint(const std::string& directory, const Communicator& comm,
                                             std::vector<std::string>* skipped) {
  std::vector<fs::path> found;
  if (fs::is_directory(directory)) found = h5_files(directory, "checkpoint_");
  std::reverse(found.begin(), found.end());  // newest first
  std::vector<std::string> reasons;
  for (const fs::path& p : found) {
    try {
      read_state_header(p.string(), comm);
      return p.string();
    } catch (const InputError& e) {
      reasons.push_back(p.string() + ": " + e.what());
      if (skipped) skipped->push_back(reasons.back());
    }
  }
  std::string why = found.empty() ? " (there is none)" : "; passed over:";
  for (const auto& r : reasons) why += "\n  " + r;
  throw InputError("--resume " + directory + ": no complete checkpoint (checkpoint_<step>.h5) in that directory" + why);
}

}  // namespace rondel
