#include "app/Checkpointing.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "app/BondRecords.hpp"
#include "app/OutputNames.hpp"
#include "core/Errors.hpp"
#include "core/InputFile.hpp"
#include "core/WallKinds.hpp"
#include "parallel/Agreement.hpp"

namespace rondel {

namespace fs = std::filesystem;

namespace {
// Whether `path` is a file <kind>_<anything>.h5.
bool state_file_of(const fs::path& path, const char* kind) {
  return path.filename().string().rfind(std::string(kind) + "_", 0) == 0 && path.extension() == output::kStateExtension;
}
// The files <kind>_*.h5 of `dir`, in ascending name order (= ascending step: the step is zero-padded). Only
// regular files (Rondel writes nothing else): a symbolic link, a FIFO or a directory of such a name is not
// one of the run's files, so it is neither read nor pruned in place of one (`others` lists them).
std::vector<fs::path> h5_files(const fs::path& dir, const char* kind, std::vector<fs::path>* others = nullptr) {
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!state_file_of(e.path(), kind)) continue;
    if (file_kind(e.path().string(), false) == FileKind::regular)
      found.push_back(e.path());
    else if (others)
      others->push_back(e.path());
  }
  std::sort(found.begin(), found.end());
  if (others) std::sort(others->begin(), others->end());
  return found;
}

}  // namespace

Checkpointing::Checkpointing(std::string directory, int keep, bool verify, std::vector<std::string> snapshot_fields,
                             const Domain& domain, const Communicator& comm)
    : dir_(std::move(directory)),
      keep_(keep),
      verify_(verify),
      fields_(std::move(snapshot_fields)),
      domain_(domain),
      comm_(comm),
      token_(comm.max(comm.root() ? static_cast<std::int64_t>(getpid()) : std::int64_t{0})) {}

std::string Checkpointing::file_name(const char* prefix, std::int64_t step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%010lld%s", prefix, static_cast<long long>(step), output::kStateExtension);
  return buf;
}

std::string Checkpointing::write_checkpoint(const StateHeader& header, DiscStore& discs, const ContactTable& pairs,
                                            const ContactTable& wall_rows, const WallSet& walls, double wall_seconds,
                                            const StateExtras& extras) {
  const fs::path final_path = fs::path(dir_) / file_name(output::kCheckpoint, header.step);
  // Hidden and never matched by checkpoint_*.h5 until complete; a name of its own per attempt (rank 0's
  // process id and a counter), so that nothing a killed attempt left behind (the file, or an MPI-IO lock
  // named after it) is met again.
  std::string part_name = ".";
  part_name += file_name(output::kCheckpoint, header.step);
  part_name += '.';  // appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on a + chain
  part_name += std::to_string(token_);
  part_name += '-';
  part_name += std::to_string(attempts_++);
  part_name += ".part";
  const fs::path part = fs::path(dir_) / part_name;
  try {
    writer_.write(part.string(), header, discs, pairs, wall_rows, walls, comm_, {}, wall_seconds, extras);
    // Known good before it replaces anything: what the disk holds is what was meant (an MPI-IO layer may
    // not report a failed write on every rank, or at all).
    if (verify_) {
      try {
        verify_state_file(part.string(), comm_);
      } catch (const InputError& e) {
        throw IoError("checkpoint " + final_path.string() + " does not read back as written (" + e.what() +
                      "); the previous checkpoints are kept");
      }
    }
  } catch (...) {
    // Every rank is here (the writer's errors are agreed): the partial file goes, the previous checkpoints stay.
    std::error_code ec;
    if (comm_.root()) fs::remove(part, ec);
    throw;
  }
  comm_.barrier();  // every rank has closed the file
  agree(comm_, [&] {
    if (!comm_.root()) return;
    try {
      fs::rename(part, final_path);
      // The oldest of this run's checkpoints go; one of a later step is not this run's (a resume passed it
      // over: damaged, or another run's) and is left alone rather than kept in place of ours.
      std::vector<fs::path> existing = h5_files(dir_, output::kCheckpoint);
      existing.erase(std::upper_bound(existing.begin(), existing.end(), final_path), existing.end());
      for (std::size_t k = 0; k + static_cast<std::size_t>(keep_) < existing.size(); ++k) fs::remove(existing[k]);
    } catch (const fs::filesystem_error& e) {
      throw IoError("checkpoint " + final_path.string() + ": " + e.what());
    }
  });
  return final_path.string();
}

void Checkpointing::adopt_snapshots(std::int64_t step) {
  snapshots_.clear();
  std::vector<fs::path> later;
  for (const fs::path& p : h5_files(dir_, output::kSnapshot)) {
    try {
      const StateHeader h = read_state_header(p.string(), comm_);
      if (h.step > step) {
        later.push_back(p);  // written after the checkpoint: the resumed run writes it again
        continue;
      }
      // The file's own datasets and walls: it may come from a run with other output.snapshot_fields.
      snapshots_.push_back(
          {p.filename().string(), h.step, static_cast<std::int64_t>(state_file_discs(p.string(), comm_)), h.time,
           state_file_disc_datasets(p.string(), comm_), wall_outline(read_state_walls(p.string(), comm_), domain_),
           cell_outline(recorded_cell(h, domain_)), state_file_rows(p.string(), "/bonds/key", comm_),
           state_file_rows(p.string(), "/breaks/key", comm_)});
    } catch (const InputError&) {
      // not a complete snapshot: left out of the series
    }
  }
  if (!comm_.root()) return;
  // What a killed checkpoint attempt left (its temporary file) goes.
  for (const auto& e : fs::directory_iterator(dir_))
    if (e.path().filename().string().rfind(output::kHiddenCheckpoint, 0) == 0) fs::remove(e.path());
  if (later.empty()) return;
  for (const fs::path& p : later) fs::remove(p);
  write_xdmf();
}

void Checkpointing::remove_old_files() const {
  if (!comm_.root()) return;
  for (const auto& e : fs::directory_iterator(dir_)) {
    const std::string n = e.path().filename().string();
    const bool ours = state_file_of(e.path(), output::kCheckpoint) || state_file_of(e.path(), output::kSnapshot) ||
                      n.rfind(output::kHiddenCheckpoint, 0) == 0 || n == output::kXdmf || n == output::kXdmfPart;
    if (ours) fs::remove(e.path());
  }
}

std::string Checkpointing::write_snapshot(const StateHeader& header, DiscStore& discs, const WallSet& walls,
                                          std::int64_t n_discs, const StateExtras& extras) {
  const std::string name = file_name(output::kSnapshot, header.step);
  const ContactTable none;
  writer_.write((fs::path(dir_) / name).string(), header, discs, none, none, walls, comm_, fields_, 0.0, extras);
  std::vector<std::string> written = fields_;
  written.emplace_back(kIndexField);
  const auto rows = [this](const RecordTable* t) { return t ? comm_.sum(static_cast<std::int64_t>(t->size())) : 0; };
  snapshots_.push_back({name, header.step, n_discs, header.time, written, wall_outline(walls, domain_),
                        cell_outline(recorded_cell(header, domain_)), rows(extras.bond_segments), rows(extras.breaks)});
  agree(comm_, [&] {
    if (comm_.root()) write_xdmf();
  });
  return (fs::path(dir_) / name).string();
}

namespace {

// The part [lo, hi] of the line p + t d inside the domain box; empty (lo > hi) when it misses the box.
// The XDMF description of one data item of a snapshot file.
std::string hdf_item(const std::string& file, const std::string& set, const std::string& dims, const char* type,
                     int precision) {
  return "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + type + "\" Precision=\"" + std::to_string(precision) +
         "\" Format=\"HDF\">" + file + ":" + set + "</DataItem>";
}

void xdmf_discs(std::ostream& x, const std::string& file, std::int64_t discs, const std::vector<std::string>& has) {
  const std::string n = std::to_string(discs);
  const bool indexed = std::find(has.begin(), has.end(), kIndexField) != has.end();
  x << "     <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\" NodesPerElement=\"1\">"
    << (indexed ? hdf_item(file, std::string("/discs/") + kIndexField, n, "Int", 8) : "") << "</Topology>\n"
    << "     <Geometry GeometryType=\"XY\">"
    << hdf_item(file, std::string("/discs/") + kPositionField, n + " 2", "Float", 8) << "</Geometry>\n";
  // Every dataset of the file's disc fields but the geometry, as a node attribute.
  for (const DiscFieldInfo& f : snapshot_fields())
    if (f.name != kPositionField && std::find(has.begin(), has.end(), f.name) != has.end())
      x << "     <Attribute Name=\"" << f.name << "\" AttributeType=\"" << (f.components == 2 ? "Vector" : "Scalar")
        << "\" Center=\"Node\">"
        << hdf_item(file, "/discs/" + f.name, f.components == 2 ? n + " 2" : n, f.number, f.bytes) << "</Attribute>\n";
}

// Line cells of two points each, their points written into the XDMF file itself.
void xdmf_lines(std::ostream& x, const std::vector<Vec2>& outline) {
  const std::size_t n = outline.size() / 2;
  const std::string cells = std::to_string(n), dims = std::to_string(2 * n);
  x << "     <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << cells << "\" NodesPerElement=\"2\">"
    << "<DataItem Dimensions=\"" << dims << "\" NumberType=\"Int\" Format=\"XML\">";
  for (std::size_t k = 0; k < 2 * n; ++k) x << (k ? " " : "") << k;
  x << "</DataItem></Topology>\n     <Geometry GeometryType=\"XY\"><DataItem Dimensions=\"" << dims
    << " 2\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">";
  for (std::size_t k = 0; k < outline.size(); ++k) x << (k ? " " : "") << outline[k].x << ' ' << outline[k].y;
  x << "</DataItem></Geometry>\n";
}

void xdmf_walls(std::ostream& x, const std::string& file, const std::vector<Vec2>& outline) {
  const std::string cells = std::to_string(outline.size() / 2);
  xdmf_lines(x, outline);
  x << "     <Attribute Name=\"kind\" AttributeType=\"Scalar\" Center=\"Cell\">"
    << hdf_item(file, "/walls/kind", cells, "Int", 4) << "</Attribute>\n"
    << "     <Attribute Name=\"normal_force\" AttributeType=\"Scalar\" Center=\"Cell\">"
    << hdf_item(file, "/walls/normal_force", cells, "Float", 8) << "</Attribute>\n"
    << "     <Attribute Name=\"contacts\" AttributeType=\"Scalar\" Center=\"Cell\">"
    << hdf_item(file, "/walls/contacts", cells, "Int", 8) << "</Attribute>\n";
  for (const char* v : {"force", "velocity"})
    x << "     <Attribute Name=\"" << v << "\" AttributeType=\"Vector\" Center=\"Cell\">"
      << hdf_item(file, std::string("/walls/") + v, cells + " 2", "Float", 8) << "</Attribute>\n";
}

// A scalar node or cell attribute of the XDMF side-car from a dataset of `n` rows.
void xdmf_scalar(std::ostream& x, const std::string& file, const std::string& set, const std::string& name,
                 std::int64_t n, const char* center, const char* type) {
  x << "     <Attribute Name=\"" << name << "\" AttributeType=\"Scalar\" Center=\"" << center << "\">"
    << hdf_item(file, set, std::to_string(n), type, 8) << "</Attribute>\n";
}

// The bonds of a snapshot as line cells between their discs' centres (/bonds/points), their forces and stresses as
// cell attributes (docs/bonds.md).
void xdmf_bonds(std::ostream& x, const std::string& file, std::int64_t bonds) {
  const std::string cells = std::to_string(bonds), points = std::to_string(2 * bonds);
  x << "    <Grid Name=\"bonds\" GridType=\"Uniform\">\n"
    << "     <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << cells << "\" NodesPerElement=\"2\">"
    << hdf_item(file, "/bonds/index", points, "Int", 8) << "</Topology>\n"
    << "     <Geometry GeometryType=\"XY\">" << hdf_item(file, "/bonds/points", points + " 2", "Float", 8)
    << "</Geometry>\n";
  for (const char* name : bond_records::kSegmentReals)
    xdmf_scalar(x, file, std::string("/bonds/") + name, name, bonds, "Cell", "Float");
  x << "    </Grid>\n";
}

// The breaks since the last snapshot as vertex cells at the bonds' centres, with their step, mode and stresses.
void xdmf_breaks(std::ostream& x, const std::string& file, std::int64_t breaks) {
  const std::string n = std::to_string(breaks);
  x << "    <Grid Name=\"breaks\" GridType=\"Uniform\">\n"
    << "     <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\" NodesPerElement=\"1\">"
    << hdf_item(file, "/breaks/index", n, "Int", 8) << "</Topology>\n"
    << "     <Geometry GeometryType=\"XY\">"
    << hdf_item(file, std::string("/breaks/") + bond_records::kBreakPosition, n + " 2", "Float", 8) << "</Geometry>\n";
  for (const char* name : bond_records::kBreakIntegers)
    xdmf_scalar(x, file, std::string("/breaks/") + name, name, breaks, "Node", "Int");
  for (const char* name : bond_records::kBreakReals)
    xdmf_scalar(x, file, std::string("/breaks/") + name, name, breaks, "Node", "Float");
  x << "    </Grid>\n";
}

}  // namespace

std::vector<Vec2> Checkpointing::cell_outline(const Domain& c) {
  if (!(c.periodic_x && c.periodic_y)) return {};
  const Vec2 a{c.xlo, c.ylo}, b{c.xhi, c.ylo}, d{c.xhi + c.tilt, c.yhi}, e{c.xlo + c.tilt, c.yhi};
  return {a, b, b, d, d, e, e, a};
}

std::vector<Vec2> Checkpointing::wall_outline(const WallSet& walls, const Domain& domain) {
  std::vector<Vec2> out;
  for (const Wall& w : walls) WallKinds::with(w.kind, [&]<class K>() { K::outline(w, walls, domain, out); });
  return out;
}

void Checkpointing::write_xdmf() const {
  // One temporal collection of spatial ones (discs, walls, the cell): the Xdmf3 readers take two temporal collections
  // side by side for one data set of every step at once.
  std::ostringstream x;
  x.precision(17);  // times and wall ends round-trip
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"snapshots\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const Snapshot& s : snapshots_) {
    x << "   <Grid Name=\"step " << s.step << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
      << "    <Time Value=\"" << s.time << "\"/>\n    <Grid Name=\"discs\" GridType=\"Uniform\">\n";
    xdmf_discs(x, s.file, s.discs, s.fields);
    x << "    </Grid>\n";
    if (!s.walls.empty()) {  // an empty grid would not load
      x << "    <Grid Name=\"walls\" GridType=\"Uniform\">\n";
      xdmf_walls(x, s.file, s.walls);
      x << "    </Grid>\n";
    }
    if (!s.cell.empty()) {
      x << "    <Grid Name=\"cell\" GridType=\"Uniform\">\n";
      xdmf_lines(x, s.cell);
      x << "    </Grid>\n";
    }
    if (s.bonds > 0) xdmf_bonds(x, s.file, s.bonds);
    if (s.breaks > 0) xdmf_breaks(x, s.file, s.breaks);
    x << "   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  // Written whole under a temporary name and renamed: a reader never sees half a series.
  const fs::path path = fs::path(dir_) / output::kXdmf, part = fs::path(dir_) / output::kXdmfPart;
  std::ofstream out(part);
  out << x.str();
  out.close();
  std::error_code ec;
  if (out.fail()) {
    fs::remove(part, ec);
    throw IoError("cannot write '" + part.string() + "' (disk full, permissions?); " + path.string() + " is as it was");
  }
  fs::rename(part, path, ec);
  if (ec) throw IoError("cannot replace '" + path.string() + "': " + ec.message());
}

std::string Checkpointing::run_id_of(const std::string& directory) {
  std::ifstream in(fs::path(directory) / output::kConfig);
  const std::string tag = output::kRunIdComment;
  for (std::string line; std::getline(in, line);)
    if (line.rfind(tag, 0) == 0) return line.substr(tag.size());
  return "";
}

std::string Checkpointing::newest_checkpoint(const std::string& directory, const Communicator& comm,
                                             std::vector<std::string>* skipped) {
  std::vector<fs::path> found, others;
  std::error_code ec;
  if (fs::is_directory(directory, ec)) found = h5_files(directory, output::kCheckpoint, &others);
  std::reverse(found.begin(), found.end());  // newest first
  std::vector<std::string> reasons;
  for (const fs::path& p : others) {
    reasons.push_back(p.string() + ": " + file_type_name(p.string(), false) + ", not a file that Rondel wrote");
    if (skipped) skipped->push_back(reasons.back());
  }
  const std::string run = run_id_of(directory);
  for (const fs::path& p : found) {
    try {
      verify_state_file(p.string(), comm);  // its errors are agreed: every rank passes over it alike
      const std::string writer = run.empty() ? std::string() : read_state_header(p.string(), comm).run_id;
      if (!writer.empty() && writer != run)
        throw InputError("written by another run (run id " + writer + "; this directory's " + output::kConfig +
                         " names the run " + run + ")");
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
