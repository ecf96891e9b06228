// scene.type = csv: the discs of scene.file, rows 'id,x,y,radius[,vx,vy,omega][,material]' or the columns a
// header line names (decimal or C99 hexadecimal floats, as final.csv writes them, so a final.csv is a scene; '#'
// comments), optionally replicated scene.replicate_x x scene.replicate_y times over the periodic box and then
// numbered in rows.
#include "core/SceneCsv.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "core/ConfigRead.hpp"
#include "core/DiscStore.hpp"
#include "core/Errors.hpp"
#include "core/InputFile.hpp"
#include "core/MemoryLimit.hpp"
#include "core/SceneTypes.hpp"

namespace rondel {

namespace {

void check_csv(SceneConfig& s) {
  if (s.file.empty()) throw ConfigError("missing required key 'scene.file' (scene.type = csv)");
  scene::check_numbering_placement(s);
}

std::string csv_keys(const SceneConfig& s) {
  return "the discs of scene.file '" + s.file + "', scene.replicate_x, scene.replicate_y";
}
std::string file_radius(const SceneConfig& s) { return "the radii of scene.file '" + s.file + "'"; }

// The columns of a CSV scene. With a header line, columns are found by name (any order; `gid` for `id`, so
// that a final.csv is a scene; `theta` is read and not used: a scene starts at angle 0); without one, by
// position: id,x,y,radius[,vx,vy,omega][,material].
enum Column : int { kId, kX, kY, kRadius, kVx, kVy, kOmega, kMaterial, kTheta, kColumns };
constexpr const char* kColumnNames[kColumns] = {"id", "x", "y", "radius", "vx", "vy", "omega", "material", "theta"};
constexpr const char* kAllowed = "id (or gid), x, y, radius, vx, vy, omega, material, theta";

// One line of the file cut into fields: at commas when the file's first line has one (spaces and tabs around a
// field are dropped), else at runs of spaces and tabs.
std::vector<std::string> fields_of(const std::string& line, bool commas) {
  if (!commas) return config::split_words(line);
  std::vector<std::string> out;
  std::size_t at = 0;
  for (;;) {
    const std::size_t comma = line.find(',', at);
    std::string f = line.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    const std::size_t b = f.find_first_not_of(" \t"), e = f.find_last_not_of(" \t");
    out.push_back(b == std::string::npos ? std::string() : f.substr(b, e - b + 1));
    if (comma == std::string::npos) return out;
    at = comma + 1;
  }
}

bool is_number(const std::string& f, double& v) {
  // strtod reads decimal and hexadecimal floats (final.csv is written in hexadecimal, bit-exact).
  char* end = nullptr;
  v = std::strtod(f.c_str(), &end);
  return !f.empty() && end == f.c_str() + f.size();
}

// The reader of a block of the file: the column of each field from the file's first line with content, then the
// block's rows as discs.
class CsvReader {
 public:
  CsvReader(const SceneConfig& s, const std::string& head, std::int64_t head_at) : s_(s), lineno_(head_at) {
    commas_ = head.find(',') != std::string::npos;
    const std::vector<std::string> f = fields_of(head, commas_);
    double v = 0.0;
    if (f.size() > 1 && !is_number(f[0], v)) {  // names, not an id
      header(f);
      header_at_ = head_at;
    } else {
      positional(f.size());
    }
  }

  void line(const std::string& text, std::int64_t lineno) {
    lineno_ = lineno;
    if (lineno == header_at_) return;
    row(fields_of(text, commas_));
  }

  scene_csv::Rows& rows() { return rows_; }

 private:
  [[noreturn]] void refuse(const std::string& what) const {
    throw InputError("scene.file '" + s_.file + "' line " + std::to_string(lineno_) + ": " + what);
  }

  void header(const std::vector<std::string>& f) {
    for (std::size_t k = 0; k < f.size(); ++k) {
      std::string name = f[k];
      if (name == "gid") name = "id";  // final.csv's name of the id: a final.csv is a scene
      const auto it = std::find(std::begin(kColumnNames), std::end(kColumnNames), name);
      if (f[k].empty()) refuse("column " + std::to_string(k + 1) + " of the header has no name (a trailing comma?)");
      if (it == std::end(kColumnNames))
        refuse("the header names a column '" + f[k] + "', which a CSV scene does not have (allowed: " + kAllowed + ")");
      const int c = static_cast<int>(it - std::begin(kColumnNames));
      if (std::find(columns_.begin(), columns_.end(), c) != columns_.end())
        refuse("the header names the column '" + f[k] + "' twice");
      columns_.push_back(c);
    }
    for (int c : {kId, kX, kY, kRadius})
      if (std::find(columns_.begin(), columns_.end(), c) == columns_.end())
        refuse(std::string("the header has no column '") + kColumnNames[c] +
               "' (required: id, x, y, radius; allowed: " + kAllowed + ")");
  }

  void positional(std::size_t n) {
    static const std::vector<int> kFour{kId, kX, kY, kRadius}, kSeven{kId, kX, kY, kRadius, kVx, kVy, kOmega};
    columns_ = n == 4 || n == 5 ? kFour : kSeven;
    if (n == 5 || n == 8) columns_.push_back(kMaterial);
    if (n != 4 && n != 5 && n != 7 && n != 8)
      refuse(
          "expected 'id,x,y,radius' or 'id,x,y,radius,vx,vy,omega', each optionally with a last column material, "
          "or a header line naming the columns (" +
          std::string(kAllowed) + ")");
  }

  void row(const std::vector<std::string>& f) {
    if (f.size() != columns_.size())
      refuse(std::to_string(f.size()) + " fields, but the file has " + std::to_string(columns_.size()) +
             " columns (a missing or extra field, a trailing comma, or a number with a space in it?)");
    std::string material;
    double value[kColumns] = {};
    bool given[kColumns] = {};
    std::string raw[kColumns];
    for (std::size_t k = 0; k < f.size(); ++k) {
      const int c = columns_[k];
      given[c] = true;
      raw[c] = f[k];
      if (c == kMaterial) {
        material = f[k];
        if (material.empty()) refuse("the material field is empty");
        continue;
      }
      if (!is_number(f[k], value[c]))
        refuse(std::string(kColumnNames[c]) + " = '" + f[k] + "' is not a number" +
               (f[k].empty() ? " (an empty field)" : ""));
    }
    const auto check = [&](int c, bool ok, const char* allowed) {
      if (given[c] && !ok) refuse(std::string(kColumnNames[c]) + " = '" + raw[c] + "' is not allowed: " + allowed);
    };
    const double id = value[kId];
    check(kId, id >= 0.0 && id < static_cast<double>(kMaxGid) && id == std::floor(id), "an integer from 0 to 2^53 - 1");
    for (int c : {kX, kY, kOmega, kTheta}) check(c, std::isfinite(value[c]), "a finite number");
    check(kRadius, value[kRadius] > 0.0 && std::isfinite(value[kRadius]), "radius must be > 0 and finite");
    for (int c : {kVx, kVy})
      check(c, std::isfinite(value[c]) && std::fabs(value[c]) <= config::kLightSpeed,
            "a finite speed below the speed of light");
    SceneDisc d{static_cast<std::int64_t>(id), {value[kX], value[kY]}, value[kRadius], s_.velocity, s_.omega};
    if (!material.empty()) {
      const auto it = std::find(s_.material_names.begin(), s_.material_names.end(), material);
      if (it == s_.material_names.end()) refuse("material '" + material + "' is not defined ([material.NAME])");
      d.material = static_cast<int>(it - s_.material_names.begin());
    }
    // Only the columns given are added (adding 0 could turn a -0.0 of scene.vx into +0.0).
    if (given[kVx]) d.v.x += value[kVx];
    if (given[kVy]) d.v.y += value[kVy];
    if (given[kOmega]) d.omega += value[kOmega];
    if (!std::isfinite(d.v.x) || !std::isfinite(d.v.y) || !std::isfinite(d.omega))
      refuse("the velocity plus scene.vx, scene.vy, scene.omega is not finite");
    rows_.discs.push_back(d);
    rows_.lines.push_back(lineno_);
  }

  const SceneConfig& s_;
  std::vector<int> columns_;
  scene_csv::Rows rows_;
  std::int64_t lineno_ = 0, header_at_ = -1;
  bool commas_ = true;
};

// Calls f(line, number) for each line of a block (blank and comment lines too); returns the number of lines. LF
// pieces are split at CRs (a CR before the LF ends nothing).
template <class F>
std::int64_t for_each_line(std::string_view text, bool file_start, std::int64_t first_line, F&& f) {
  if (file_start && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // a UTF-8 byte order mark
  std::int64_t lineno = first_line;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t lf = std::min(text.find('\n', at), text.size());
    std::string_view chunk = text.substr(at, lf - at);
    at = lf + 1;
    if (!chunk.empty() && chunk.back() == '\r') chunk.remove_suffix(1);
    for (std::size_t from = 0;;) {
      const std::size_t cr = chunk.find('\r', from);
      if (!f(chunk.substr(from, cr == std::string_view::npos ? std::string_view::npos : cr - from), lineno++))
        return lineno - first_line;
      if (cr == std::string_view::npos) break;
      from = cr + 1;
    }
  }
  return lineno - first_line;
}

bool has_content(std::string_view line) {
  const std::size_t first = line.find_first_not_of(" \t");
  return first != std::string_view::npos && line[first] != '#';
}

}  // namespace

// The whole file on this process (a replicated scene's tile, or no parallel reader).
std::vector<SceneDisc> scene_csv::whole_file(const SceneConfig& s, const std::string& path) {
  // A file larger than the memory this process may use cannot become a scene (0: no bound known).
  const std::uint64_t bound = memory_bound().bytes;
  if (const std::string why = input_file_problem(path, "scene.file", bound > 0 ? bound : UINT64_MAX); !why.empty())
    throw InputError(why);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("scene.file '" + s.file + "' cannot be read");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError("scene.file '" + s.file + "' cannot be read (an I/O error)");
  std::string head;
  std::int64_t head_at = 0;
  if (!scene_csv::head_line(text, true, 1, head, head_at)) return {};
  scene_csv::Rows rows = scene_csv::rows(s, head, head_at, text, true, 1);
  std::vector<std::pair<std::int64_t, std::int64_t>> ids(rows.discs.size());
  for (std::size_t k = 0; k < ids.size(); ++k) ids[k] = {rows.discs[k].gid, rows.lines[k]};
  std::sort(ids.begin(), ids.end());
  for (std::size_t k = 1; k < ids.size(); ++k)
    if (ids[k].first == ids[k - 1].first)
      throw InputError(scene_csv::duplicate_message(s, ids[k].first, ids[k - 1].second, ids[k].second));
  return std::move(rows.discs);
}

namespace {

// The copies, numbered anew in rows across the whole box: numbered one after the other, every row of the file
// would have a seam whose partners lay a whole copy of ids away.
std::vector<SceneDisc> replicate(const SceneConfig& s, const Domain& domain, const std::vector<SceneDisc>& base) {
  const double copies = static_cast<double>(s.replicate_x) * s.replicate_y;
  check_memory(static_cast<double>(base.size()) * copies, 0.0, 0.0,
               "scene.replicate_x x scene.replicate_y copies of the " + std::to_string(base.size()) + " discs of '" +
                   s.file + "'");
  const double px = domain.length_x() / s.replicate_x, py = domain.length_y() / s.replicate_y;
  std::vector<SceneDisc> out;  // scene_csv::replicated_block builds a rank's block of the same discs
  out.reserve(base.size() * static_cast<std::size_t>(s.replicate_x) * static_cast<std::size_t>(s.replicate_y));
  for (int cy = 0; cy < s.replicate_y; ++cy)
    for (int cx = 0; cx < s.replicate_x; ++cx)
      for (auto d : base) {
        d.x += Vec2{cx * px, cy * py};
        out.push_back(d);
      }
  scene::number_in_rows(out, domain.ylo);
  return out;
}

std::vector<SceneDisc> csv(const SceneInputs& in) {
  const SceneConfig& s = in.scene;
  const std::string path = scene::resolve(s.file, in.config_dir);
  if (in.files && scene::in_blocks(s)) return in.files->csv(s, path);  // each rank its block
  std::vector<SceneDisc> base = scene_csv::whole_file(s, path);
  if (s.replicate_x == 1 && s.replicate_y == 1) return base;
  return replicate(s, in.domain, base);
}

}  // namespace

namespace scene_csv {

std::vector<SceneDisc> replicated_block(const SceneConfig& s, const Domain& domain, const std::vector<SceneDisc>& base,
                                        int rank, int ranks) {
  if (base.empty()) return {};
  const std::int64_t copies_x = s.replicate_x, copies_y = s.replicate_y;
  const std::int64_t n = static_cast<std::int64_t>(base.size()) * copies_x * copies_y;
  const std::int64_t q = n / ranks, rem = n % ranks;
  const auto first_of = [&](int r) { return q * r + rem * r / ranks; };
  const std::int64_t lo = first_of(rank), hi = first_of(rank + 1);
  check_memory(static_cast<double>(hi - lo), 0.0, 0.0,
               "scene.replicate_x x scene.replicate_y copies of the " + std::to_string(base.size()) + " discs of '" +
                   s.file + "'");
  // As replicate and number_in_rows compute them: the shifts, the rows' height and each copy's row.
  const double px = domain.length_x() / s.replicate_x, py = domain.length_y() / s.replicate_y;
  double R_max = 0.0;
  for (const auto& d : base) R_max = std::max(R_max, d.radius);
  const double row_height = 2.0 * R_max, ylo = domain.ylo;
  const auto row_of = [&](double y) { return std::floor((y - ylo) / row_height); };
  const auto y_of = [&](const SceneDisc& d, std::int64_t cy) { return d.x.y + static_cast<int>(cy) * py; };
  // The discs of each row of the whole box (each copy of a file row lies in the same row whatever its column), and
  // the first id of each: the rows that hold ids of [lo, hi) are this rank's.
  std::map<double, std::int64_t> in_row;
  for (std::int64_t cy = 0; cy < copies_y; ++cy)
    for (const auto& d : base) in_row[row_of(y_of(d, cy))] += copies_x;
  std::map<double, std::int64_t> first;  // of the rows this rank builds
  std::int64_t id = 0;
  for (const auto& [row, count] : in_row) {
    if (id < hi && id + count > lo) first[row] = id;
    id += count;
  }
  // Their discs in the order replicate gives them (copy row, copy column, file order), then numbered as
  // number_in_rows numbers them: by row, by x within a row, ties in that order (a stable sort).
  std::vector<SceneDisc> out;
  for (std::int64_t cy = 0; cy < copies_y; ++cy) {
    std::vector<std::size_t> mine;
    for (std::size_t k = 0; k < base.size(); ++k)
      if (first.count(row_of(y_of(base[k], cy)))) mine.push_back(k);
    for (int cx = 0; cx < s.replicate_x; ++cx)
      for (std::size_t k : mine) {
        SceneDisc d = base[k];
        d.x += Vec2{cx * px, static_cast<int>(cy) * py};
        out.push_back(d);
      }
  }
  std::stable_sort(out.begin(), out.end(), [&](const SceneDisc& a, const SceneDisc& b) {
    const double ra = row_of(a.x.y), rb = row_of(b.x.y);
    return ra != rb ? ra < rb : a.x.x < b.x.x;
  });
  std::vector<SceneDisc> block;
  block.reserve(static_cast<std::size_t>(hi - lo));
  for (std::size_t k = 0; k < out.size();) {
    const double row = row_of(out[k].x.y);
    const std::int64_t row_first = first.at(row);
    for (std::int64_t j = 0; k < out.size() && row_of(out[k].x.y) == row; ++k, ++j)
      if (row_first + j >= lo && row_first + j < hi) {
        out[k].gid = row_first + j;
        block.push_back(out[k]);
      }
  }
  return block;
}

std::int64_t count_lines(std::string_view text, bool file_start) {
  return for_each_line(text, file_start, 0, [](std::string_view, std::int64_t) { return true; });
}

bool head_line(std::string_view text, bool file_start, std::int64_t first_line, std::string& head, std::int64_t& at) {
  bool found = false;
  for_each_line(text, file_start, first_line, [&](std::string_view line, std::int64_t lineno) {
    if (!has_content(line)) return true;
    head.assign(line), at = lineno, found = true;
    return false;
  });
  return found;
}

Rows rows(const SceneConfig& s, const std::string& head, std::int64_t head_at, std::string_view text, bool file_start,
          std::int64_t first_line) {
  CsvReader reader(s, head, head_at);
  std::string line;
  for_each_line(text, file_start, first_line, [&](std::string_view l, std::int64_t lineno) {
    if (has_content(l)) line.assign(l), reader.line(line, lineno);
    return true;
  });
  return std::move(reader.rows());
}

std::string duplicate_message(const SceneConfig& s, std::int64_t gid, std::int64_t a, std::int64_t b) {
  return "scene.file '" + s.file + "' lines " + std::to_string(a) + " and " + std::to_string(b) + ": disc id " +
         std::to_string(gid) + " appears twice (every disc has an id of its own)";
}

}  // namespace scene_csv

extern const SceneType kCsvScene{"csv",       "the discs of scene.file, a CSV file", check_csv, csv_keys,
                                 file_radius, SceneType::Source::csv_file,           false,     csv};

}  // namespace rondel
