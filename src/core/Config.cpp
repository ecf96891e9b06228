#include "core/Config.hpp"

#include <boost/any.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "core/ConfigSchema.hpp"
#include "core/Errors.hpp"

namespace rondel {

namespace po = boost::program_options;

namespace {

std::string value_text(const boost::any& v) {
  std::ostringstream s;
  s.precision(17);
  if (auto p = boost::any_cast<double>(&v)) s << *p;
  else if (auto p = boost::any_cast<std::int64_t>(&v)) s << *p;
  else if (auto p = boost::any_cast<std::uint64_t>(&v)) s << *p;
  else if (auto p = boost::any_cast<int>(&v)) s << *p;
  else if (auto p = boost::any_cast<bool>(&v)) s << (*p ? "true" : "false");
  else if (auto p = boost::any_cast<std::string>(&v)) s << *p;
  return s.str();
}

// INI text of every key that has a value, grouped by section in declaration order.
// Blocks of laws that are not selected are left out (their defaults would read as a stale block).
std::string resolved_text(const po::options_description& schema, const po::variables_map& vm, const Config& c) {
  const std::map<std::string, bool> law_block = {
      {"coulomb", c.tangential_law == "coulomb"},
      {"jiang", c.rolling_law == "jiang_plastic" || c.rolling_law == "jiang_brittle"},
      {"wang", c.rolling_law == "wang"},
      {"iwashita_oda", c.rolling_law == "iwashita_oda"},
      {"force_proportional", c.rolling_law == "force_proportional"},
      {"constant_torque", c.rolling_law == "constant_torque"},
      {"displacement_damping", c.rolling_law == "displacement_damping"}};
  std::ostringstream out;
  std::string section;
  for (const auto& opt : schema.options()) {
    const std::string& name = opt->long_name();
    if (!vm.count(name)) continue;
    const auto dot = name.find('.');
    const std::string sec = name.substr(0, dot);
    const auto block = law_block.find(sec);
    if (block != law_block.end() && !block->second) continue;
    if (sec != section) {
      out << (section.empty() ? "" : "\n") << "[" << sec << "]\n";
      section = sec;
    }
    out << name.substr(dot + 1) << " = " << value_text(vm[name].value()) << "\n";
  }
  return out.str();
}

struct Reader {
  const po::variables_map& vm;
  template <class T>
  T get(const std::string& key) const {
    return vm[key].as<T>();
  }
  bool given(const std::string& key) const { return vm.count(key) && !vm[key].defaulted(); }
  double required(const std::string& key, const std::string& why) const {
    if (!vm.count(key)) throw ConfigError("missing required key '" + key + "'" + why);
    return vm[key].as<double>();
  }
};

void check(bool ok, const std::string& key, const std::string& allowed, const std::string& got) {
  if (!ok) throw ConfigError("key '" + key + "' = " + got + " is not allowed: " + allowed);
}
std::string num(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}
void positive(const Reader& r, const std::string& key) {
  const double v = r.get<double>(key);
  check(v > 0.0 && std::isfinite(v), key, "must be > 0", num(v));
}
void non_negative(double v, const std::string& key) {
  check(v >= 0.0 && std::isfinite(v), key, "must be >= 0", num(v));
}

std::vector<double> numbers(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::vector<double> out;
  std::string tok;
  while (in >> tok) {
    try {
      std::size_t used = 0;
      out.push_back(std::stod(tok, &used));
      if (used != tok.size()) throw std::invalid_argument(tok);
    } catch (const std::exception&) {
      throw ConfigError("key '" + key + "': '" + tok + "' is not a number");
    }
  }
  return out;
}

std::vector<std::vector<double>> records(const std::string& text, const std::string& key) {
  std::vector<std::vector<double>> out;
  std::istringstream in(text);
  std::string rec;
  while (std::getline(in, rec, ';')) {
    auto v = numbers(rec, key);
    if (!v.empty()) out.push_back(std::move(v));
  }
  return out;
}

void read_walls(const Reader& r, Config& c) {
  for (const auto& rec : records(r.get<std::string>("walls.lines"), "walls.lines")) {
    check(rec.size() == 4 || rec.size() == 6, "walls.lines", "'px py nx ny [vx vy]' per wall", "a record of " + std::to_string(rec.size()) + " numbers");
    Wall w;
    w.kind = Wall::Kind::line;
    w.p0 = {rec[0], rec[1]};
    const double len = std::hypot(rec[2], rec[3]);
    check(len > 0.0, "walls.lines", "a non-zero normal", "normal (0, 0)");
    w.normal = {rec[2] / len, rec[3] / len};
    if (rec.size() == 6) w.velocity = {rec[4], rec[5]};
    c.walls.push_back(w);
  }
  for (const auto& rec : records(r.get<std::string>("walls.segments"), "walls.segments")) {
    check(rec.size() == 4 || rec.size() == 6, "walls.segments", "'x1 y1 x2 y2 [vx vy]' per wall", "a record of " + std::to_string(rec.size()) + " numbers");
    Wall w;
    w.kind = Wall::Kind::segment;
    w.p0 = {rec[0], rec[1]};
    w.p1 = {rec[2], rec[3]};
    check(rec[0] != rec[2] || rec[1] != rec[3], "walls.segments", "two distinct ends", "a zero-length segment");
    if (rec.size() == 6) w.velocity = {rec[4], rec[5]};
    c.walls.push_back(w);
  }
  std::istringstream box(r.get<std::string>("walls.box"));
  std::string side;
  const Domain& d = c.domain;
  const auto region = numbers(r.get<std::string>("walls.box_region"), "walls.box_region");
  double b[4] = {d.xlo, d.xhi, d.ylo, d.yhi};
  if (region.size() == 4 && region[0] < region[1] && region[2] < region[3]) std::copy(region.begin(), region.end(), b);
  else if (!region.empty()) throw ConfigError("key 'walls.box_region' must be 'xlo xhi ylo yhi' with xlo < xhi and ylo < yhi");
  const char* sides[4] = {"bottom", "left", "right", "top"};
  while (box >> side) {
    Wall w;
    w.kind = Wall::Kind::line;
    if (side == "bottom") w.p0 = {b[0], b[2]}, w.normal = {0, 1}, w.box_side = 0;
    else if (side == "left") w.p0 = {b[0], b[2]}, w.normal = {1, 0}, w.box_side = 1;
    else if (side == "right") w.p0 = {b[1], b[2]}, w.normal = {-1, 0}, w.box_side = 2;
    else if (side == "top") w.p0 = {b[0], b[3]}, w.normal = {0, -1}, w.box_side = 3;
    else throw ConfigError("key 'walls.box': '" + side + "' is not a side; allowed: bottom left right top");
    const bool periodic = (side == "left" || side == "right") ? d.periodic_x : d.periodic_y;
    check(!periodic, "walls.box", "no wall across a periodic direction", side);
    c.walls.push_back(w);
    c.box_walls.push_back(side);
  }
  auto box_wall = [&](const std::string& name, const char* key, const std::string& spec) -> Wall& {
    for (Wall& w : c.walls)
      if (w.box_side >= 0 && name == sides[w.box_side]) return w;
    throw ConfigError("key '" + std::string(key) + "': '" + name + "' in '" + spec + "' is not a side listed in walls.box");
  };
  std::istringstream control(r.get<std::string>("walls.control"));
  for (std::string spec; control >> spec;) {
    const auto a = spec.find(':'), z = spec.rfind(':');
    if (a == std::string::npos || a == z)
      throw ConfigError("key 'walls.control': '" + spec + "' is not 'side:servo:STRESS', 'side:strain_rate:RATE' or 'side:shear:VELOCITY'");
    const std::string name = spec.substr(0, a), mode = spec.substr(a + 1, z - a - 1);
    const auto parsed = numbers(spec.substr(z + 1), "walls.control");
    if (parsed.size() != 1) throw ConfigError("key 'walls.control': '" + spec + "' needs one number after the mode");
    const double value = parsed[0];
    Wall& wall = box_wall(name, "walls.control", spec);
    if ((mode == "servo" || mode == "strain_rate") && wall.control != Wall::Control::velocity)
      throw ConfigError("key 'walls.control': '" + spec + "': wall '" + name + "' already has a servo or strain rate (one per wall)");
    if (mode == "servo") {
      check(value > 0.0, "walls.control", "a servo stress > 0 [Pa]", spec);
      wall.control = Wall::Control::servo, wall.target_stress = value;
    } else if (mode == "strain_rate") {
      wall.control = Wall::Control::strain_rate, wall.strain_rate = value;
    } else if (mode == "shear") {
      wall.shear_velocity = value;
    } else {
      throw ConfigError("key 'walls.control': mode '" + mode + "' in '" + spec + "' is not servo, strain_rate or shear");
    }
  }
  std::istringstream rough(r.get<std::string>("walls.rough"));
  for (std::string name; rough >> name;) box_wall(name, "walls.rough", name).rough = true;
  c.rough_depth = r.get<double>("walls.rough_depth");
  non_negative(c.rough_depth, "walls.rough_depth");
  c.servo_gain = r.get<double>("walls.servo_gain");
  check(c.servo_gain > 0.0 && c.servo_gain < 1.0, "walls.servo_gain", "must be in (0, 1)", num(c.servo_gain));
  c.servo_max_speed = r.get<double>("walls.servo_max_speed");
  check(c.servo_max_speed > 0.0, "walls.servo_max_speed", "must be > 0", num(c.servo_max_speed));
}

double required_non_negative(const Reader& r, const std::string& key, const std::string& law) {
  const double v = r.required(key, " (required with contact.rolling = " + law + ")");
  non_negative(v, key);
  return v;
}
double required_positive(const Reader& r, const std::string& key, const std::string& law) {
  r.required(key, " (required with contact.rolling = " + law + ")");
  positive(r, key);
  return r.get<double>(key);
}

void read_rolling(const Reader& r, const std::string& law, ContactParams& p) {
  if (law == "jiang_plastic" || law == "jiang_brittle") {
    p.delta = required_positive(r, "jiang.delta", law);
  } else if (law == "wang") {
    p.k_r = required_positive(r, "wang.k_r", law);
    p.mu_r = required_non_negative(r, "wang.mu_r", law);
    non_negative(p.c_r = r.get<double>("wang.c_r"), "wang.c_r");
  } else if (law == "iwashita_oda") {
    p.K_r = required_positive(r, "iwashita_oda.K_r", law);
    p.C_r = required_non_negative(r, "iwashita_oda.C_r", law);
    p.eta = required_non_negative(r, "iwashita_oda.eta", law);
  } else if (law == "force_proportional") {
    p.mu_r = required_non_negative(r, "force_proportional.mu_r", law);
  } else if (law == "constant_torque") {
    p.mu_r = required_non_negative(r, "constant_torque.mu_r", law);
    non_negative(p.f_lim = r.get<double>("constant_torque.f_lim"), "constant_torque.f_lim");
  } else if (law == "displacement_damping") {
    p.mu_r = required_non_negative(r, "displacement_damping.mu_r", law);
    positive(r, "displacement_damping.theta_rmax");
    p.theta_rmax = r.get<double>("displacement_damping.theta_rmax");
    non_negative(p.nu = r.get<double>("displacement_damping.nu"), "displacement_damping.nu");
    non_negative(p.f_visc = r.get<double>("displacement_damping.f"), "displacement_damping.f");
  }
}

void read_contact(const Reader& r, Config& c) {
  c.normal_law = r.get<std::string>("contact.normal");
  c.tangential_law = r.get<std::string>("contact.tangential");
  c.rolling_law = r.get<std::string>("contact.rolling");
  check(c.normal_law == "linear", "contact.normal", "linear", c.normal_law);
  check(c.tangential_law == "coulomb" || c.tangential_law == "none", "contact.tangential", "coulomb | none", c.tangential_law);
  const std::string rolling_laws = "none | jiang_plastic | jiang_brittle | wang | iwashita_oda | force_proportional | "
                                   "constant_torque | displacement_damping";
  check((" | " + rolling_laws + " | ").find(" | " + c.rolling_law + " | ") != std::string::npos, "contact.rolling",
        rolling_laws, c.rolling_law);
  // A parameter block for a law that is not selected is a mistake (a typo in the law, or a stale block).
  const std::map<std::string, std::pair<std::string, std::string>> blocks = {
      {"coulomb", {c.tangential_law, " coulomb "}},
      {"jiang", {c.rolling_law, " jiang_plastic jiang_brittle "}},
      {"wang", {c.rolling_law, " wang "}},
      {"iwashita_oda", {c.rolling_law, " iwashita_oda "}},
      {"force_proportional", {c.rolling_law, " force_proportional "}},
      {"constant_torque", {c.rolling_law, " constant_torque "}},
      {"displacement_damping", {c.rolling_law, " displacement_damping "}}};
  for (const auto& [key, value] : r.vm) {
    const auto it = blocks.find(key.substr(0, key.find('.')));
    if (it == blocks.end() || value.defaulted()) continue;
    const auto& [selected, users] = it->second;
    if (users.find(" " + selected + " ") == std::string::npos)
      throw ConfigError("key '" + key + "' belongs to the [" + it->first + "] block, but that law is not selected (" +
                        (it->first == "coulomb" ? "contact.tangential = " : "contact.rolling = ") + selected + ")");
  }
  ContactParams p;
  p.k_n = r.required("linear.k_n", " (the normal stiffness of the linear law)");
  positive(r, "linear.k_n");
  int damping_keys = 0;
  for (const char* k : {"linear.zeta", "linear.c_n", "linear.e"}) damping_keys += r.vm.count(k) ? 1 : 0;
  if (damping_keys > 1) throw ConfigError("keys 'linear.zeta', 'linear.c_n', 'linear.e': give at most one");
  if (r.vm.count("linear.zeta")) non_negative(p.zeta_n = r.get<double>("linear.zeta"), "linear.zeta");
  if (r.vm.count("linear.c_n")) non_negative(p.c_n_fixed = r.get<double>("linear.c_n"), "linear.c_n");
  if (r.vm.count("linear.e")) {
    const double e = r.get<double>("linear.e");
    check(e > 0.0 && e <= 1.0, "linear.e", "restitution in (0, 1]", num(e));
    p.e_n = e;  // converted to zeta_n by the physics layer at set-up
  }
  if (c.tangential_law == "coulomb") {
    p.k_s = r.required("coulomb.k_s", " (tangential stiffness, required with contact.tangential = coulomb)");
    positive(r, "coulomb.k_s");
    p.mu = r.required("coulomb.mu", " (friction coefficient, required with contact.tangential = coulomb)");
    non_negative(p.mu, "coulomb.mu");
    non_negative(p.zeta_t = r.get<double>("coulomb.zeta_t"), "coulomb.zeta_t");
  }
  read_rolling(r, c.rolling_law, p);
  ContactParams w = p;
  w.rolling = r.get<bool>("wall_contact.rolling");
  if (r.vm.count("wall_contact.k_n")) positive(r, "wall_contact.k_n"), w.k_n = r.get<double>("wall_contact.k_n");
  if (r.vm.count("wall_contact.zeta") && r.vm.count("wall_contact.e"))
    throw ConfigError("keys 'wall_contact.zeta' and 'wall_contact.e': give at most one");
  if (r.vm.count("wall_contact.zeta")) non_negative(w.zeta_n = r.get<double>("wall_contact.zeta"), "wall_contact.zeta"), w.c_n_fixed = -1.0, w.e_n = -1.0;
  if (r.vm.count("wall_contact.e")) {
    const double e = r.get<double>("wall_contact.e");
    check(e > 0.0 && e <= 1.0, "wall_contact.e", "restitution in (0, 1]", num(e));
    w.e_n = e;
    w.c_n_fixed = -1.0;
  }
  for (const char* k : {"wall_contact.k_s", "wall_contact.mu"})
    if (r.vm.count(k) && c.tangential_law != "coulomb")
      throw ConfigError(std::string("key '") + k + "' needs contact.tangential = coulomb");
  if (r.vm.count("wall_contact.k_s")) positive(r, "wall_contact.k_s"), w.k_s = r.get<double>("wall_contact.k_s");
  if (r.vm.count("wall_contact.mu")) non_negative(w.mu = r.get<double>("wall_contact.mu"), "wall_contact.mu");
  c.params = ContactParamTable(1);
  c.params.pair(0, 0) = p;
  c.params.wall(0) = w;
}

void read_scene(const Reader& r, Config& c) {
  SceneConfig& s = c.scene;
  if (!r.vm.count("scene.type")) throw ConfigError("missing required key 'scene.type' (lattice_square | lattice_hex | random | csv)");
  s.type = r.get<std::string>("scene.type");
  s.nx = r.get<int>("scene.nx");
  s.ny = r.get<int>("scene.ny");
  s.radius = r.get<double>("scene.radius");
  s.spacing = r.get<double>("scene.spacing");
  s.x0 = r.get<double>("scene.x0");
  s.y0 = r.get<double>("scene.y0");
  s.count = r.get<std::int64_t>("scene.count");
  s.distribution = r.get<std::string>("scene.distribution");
  s.radius_min = r.get<double>("scene.radius_min");
  s.radius_max = r.get<double>("scene.radius_max");
  s.sizes = numbers(r.get<std::string>("scene.sizes"), "scene.sizes");
  s.fractions = numbers(r.get<std::string>("scene.fractions"), "scene.fractions");
  s.seed = r.get<std::uint64_t>("scene.seed");
  s.max_attempts = r.get<std::int64_t>("scene.max_attempts");
  s.file = r.get<std::string>("scene.file");
  s.replicate_x = r.get<int>("scene.replicate_x");
  s.replicate_y = r.get<int>("scene.replicate_y");
  s.velocity = {r.get<double>("scene.vx"), r.get<double>("scene.vy")};
  s.omega = r.get<double>("scene.omega");
  s.max_initial_overlap = r.get<double>("scene.max_initial_overlap");
  non_negative(s.max_initial_overlap, "scene.max_initial_overlap");
  // The default region is the box of the walls (walls.box_region), else the domain.
  auto region = numbers(r.get<std::string>("scene.region"), "scene.region");
  if (region.empty()) region = numbers(r.get<std::string>("walls.box_region"), "walls.box_region");
  const Domain& d = c.domain;
  const double box[4] = {d.xlo, d.xhi, d.ylo, d.yhi};
  if (region.empty()) std::copy(box, box + 4, s.region);
  else if (region.size() == 4 && region[0] < region[1] && region[2] < region[3]) std::copy(region.begin(), region.end(), s.region);
  else throw ConfigError("key 'scene.region' must be 'xlo xhi ylo yhi' with xlo < xhi and ylo < yhi");

  if (s.type == "lattice_square" || s.type == "lattice_hex") {
    check(s.nx > 0, "scene.nx", "must be > 0 for a lattice", std::to_string(s.nx));
    check(s.ny > 0, "scene.ny", "must be > 0 for a lattice", std::to_string(s.ny));
    positive(r, "scene.radius");
    if (s.spacing == 0.0) s.spacing = 2.0 * s.radius;
    check(s.spacing > 0.0, "scene.spacing", "must be > 0 (or 0 for 2 x radius)", num(s.spacing));
  } else if (s.type == "random") {
    check(s.count > 0, "scene.count", "must be > 0 for a random scene", std::to_string(s.count));
    check(s.max_attempts > 0, "scene.max_attempts", "must be > 0", std::to_string(s.max_attempts));
    if (s.distribution == "uniform_radius" || s.distribution == "uniform_area") {
      positive(r, "scene.radius_min");
      check(s.radius_max >= s.radius_min, "scene.radius_max", ">= scene.radius_min", num(s.radius_max));
    } else if (s.distribution == "list") {
      check(!s.sizes.empty() && s.sizes.size() == s.fractions.size(), "scene.fractions",
            "one fraction per size in scene.sizes", std::to_string(s.fractions.size()) + " fractions for " + std::to_string(s.sizes.size()) + " sizes");
      double sum = 0.0;
      for (double v : s.sizes) check(v > 0.0, "scene.sizes", "radii must be > 0", num(v));
      for (double f : s.fractions) check(f >= 0.0, "scene.fractions", "fractions must be >= 0", num(f)), sum += f;
      check(std::fabs(sum - 1.0) < 1e-9, "scene.fractions", "fractions must sum to 1", num(sum));
    } else {
      throw ConfigError("key 'scene.distribution' = " + s.distribution + " is not allowed: uniform_radius | uniform_area | list");
    }
  } else if (s.type == "file") {
    if (s.file.empty()) throw ConfigError("missing required key 'scene.file' (scene.type = file: a checkpoint or snapshot)");
  } else if (s.type == "csv") {
    if (s.file.empty()) throw ConfigError("missing required key 'scene.file' (scene.type = csv)");
    check(s.replicate_x >= 1, "scene.replicate_x", "must be >= 1", std::to_string(s.replicate_x));
    check(s.replicate_y >= 1, "scene.replicate_y", "must be >= 1", std::to_string(s.replicate_y));
  } else {
    throw ConfigError("key 'scene.type' = " + s.type + " is not allowed: lattice_square | lattice_hex | random | csv | file");
  }
}

Config build(const po::options_description& schema, const po::variables_map& vm) {
  Reader r{vm};
  Config c;
  c.steps = r.get<std::int64_t>("run.steps");
  check(c.steps >= 0, "run.steps", "must be >= 0", std::to_string(c.steps));
  c.dt = r.get<double>("run.dt");
  non_negative(c.dt, "run.dt");
  c.safety = r.get<double>("run.safety");
  check(c.safety > 0.0 && c.safety <= 1.0, "run.safety", "must be in (0, 1]", num(c.safety));
  c.force_dt = r.get<bool>("run.force_dt");
  c.output = r.get<std::string>("run.output");
  check(!c.output.empty(), "run.output", "a directory name", "''");
  c.overwrite = r.get<bool>("run.overwrite");
  c.progress = r.get<bool>("run.progress");
  c.max_overlap = r.get<double>("run.max_overlap");
  check(c.max_overlap > 0.0, "run.max_overlap", "must be > 0", num(c.max_overlap));
  c.max_residual = r.get<double>("run.max_residual");
  check(c.max_residual > 0.0, "run.max_residual", "must be > 0", num(c.max_residual));
  c.reset_history = r.get<bool>("run.reset_history");
  c.snapshot_every = r.get<std::int64_t>("output.snapshot_every");
  check(c.snapshot_every >= 0, "output.snapshot_every", "must be >= 0", std::to_string(c.snapshot_every));
  {
    std::istringstream in(r.get<std::string>("output.snapshot_fields"));
    const std::string allowed = " gid material radius mass inertia position velocity theta omega force torque flags rank ";
    for (std::string f; in >> f;) {
      check(allowed.find(" " + f + " ") != std::string::npos, "output.snapshot_fields", allowed, f);
      c.snapshot_fields.push_back(f);
    }
    if (std::find(c.snapshot_fields.begin(), c.snapshot_fields.end(), "position") == c.snapshot_fields.end())
      c.snapshot_fields.push_back("position");  // the XDMF geometry
  }
  c.checkpoint_every = r.get<std::int64_t>("output.checkpoint_every");
  check(c.checkpoint_every >= 0, "output.checkpoint_every", "must be >= 0", std::to_string(c.checkpoint_every));
  c.checkpoint_minutes = r.get<double>("output.checkpoint_minutes");
  non_negative(c.checkpoint_minutes, "output.checkpoint_minutes");
  c.checkpoint_keep = r.get<int>("output.checkpoint_keep");
  check(c.checkpoint_keep >= 1, "output.checkpoint_keep", "must be >= 1", std::to_string(c.checkpoint_keep));
  c.checkpoint_at_end = r.get<bool>("output.checkpoint_at_end");
  if (vm.count("resume")) c.resume_dir = vm["resume"].as<std::string>();
  c.diag_every = r.get<std::int64_t>("diagnostics.every");
  check(c.diag_every > 0, "diagnostics.every", "must be > 0", std::to_string(c.diag_every));

  const char* box_keys[4] = {"domain.xlo", "domain.xhi", "domain.ylo", "domain.yhi"};
  for (const char* k : box_keys) r.required(k, " (the simulation box)");
  c.domain.xlo = r.get<double>("domain.xlo");
  c.domain.xhi = r.get<double>("domain.xhi");
  c.domain.ylo = r.get<double>("domain.ylo");
  c.domain.yhi = r.get<double>("domain.yhi");
  check(c.domain.xhi > c.domain.xlo, "domain.xhi", "must be > domain.xlo", num(c.domain.xhi));
  check(c.domain.yhi > c.domain.ylo, "domain.yhi", "must be > domain.ylo", num(c.domain.yhi));
  c.domain.periodic_x = r.get<bool>("domain.periodic_x");
  c.domain.periodic_y = r.get<bool>("domain.periodic_y");
  c.gravity = {r.get<double>("gravity.x"), r.get<double>("gravity.y")};
  positive(r, "material.density");
  positive(r, "material.thickness");
  c.density = r.get<double>("material.density");
  c.thickness = r.get<double>("material.thickness");
  c.skin = r.get<double>("neighbour.skin");
  non_negative(c.skin, "neighbour.skin");
  c.partitioner = r.get<std::string>("parallel.partitioner");
  check(c.partitioner == "metis" || c.partitioner == "grid", "parallel.partitioner", "metis | grid", c.partitioner);
  c.balance_every = r.get<std::int64_t>("parallel.balance_every");
  check(c.balance_every >= 0, "parallel.balance_every", "must be >= 0", std::to_string(c.balance_every));
  c.balance_threshold = r.get<double>("parallel.balance_threshold");
  check(c.balance_threshold > 1.0, "parallel.balance_threshold", "must be > 1", num(c.balance_threshold));
  c.force_balance = r.get<bool>("parallel.force_balance");
  read_contact(r, c);
  read_walls(r, c);
  read_scene(r, c);
  c.resolved_text = resolved_text(schema, vm, c);
  return c;
}

po::variables_map parse(const std::vector<std::string>& args, std::string* file_out, const std::string* ini_text) {
  const auto schema = config_schema();
  po::options_description cli("Command line");
  cli.add_options()("help,h", "print every key with its default, unit and meaning")
      ("config", po::value<std::string>(), "INI file (also the first positional argument)")
      ("resume", po::value<std::string>(), "continue from the newest complete checkpoint of this output directory");
  cli.add(schema);
  po::positional_options_description pos;
  pos.add("config", 1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args).options(cli).positional(pos).run(), vm);
    if (vm.count("help")) throw HelpRequested{config_help()};
    if (ini_text) {
      std::istringstream in(*ini_text);
      po::store(po::parse_config_file(in, schema, false), vm);
    } else if (vm.count("config")) {
      const std::string file = vm["config"].as<std::string>();
      std::ifstream in(file);
      if (!in) throw ConfigError("cannot read the configuration file '" + file + "'");
      *file_out = file;
      try {
        po::store(po::parse_config_file(in, schema, false), vm);
      } catch (const po::error& e) {
        throw ConfigError("in '" + file + "': " + std::string(e.what()) + " (rondel --help lists every key)");
      }
    } else if (!vm.count("resume")) {
      throw ConfigError("no configuration file given: usage 'rondel FILE.ini [--section.key=value ...]'");
    }
    po::notify(vm);
  } catch (const po::error& e) {
    throw ConfigError(std::string(e.what()) + " (rondel --help lists every key)");
  }
  return vm;
}

}  // namespace

std::string config_help() {
  std::ostringstream s;
  s << "Usage: mpirun -n N rondel FILE.ini [--section.key=value ...]\n"
       "Every key may be set in FILE.ini (under [section] as 'key = value') or on the command line,\n"
       "which wins. Units in brackets.\n\n"
    << config_schema();
  return s.str();
}

Config parse_config(int argc, const char* const* argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string file;
  const auto vm = parse(args, &file, nullptr);
  Config c = build(config_schema(), vm);
  c.source_file = file;
  return c;
}

Config parse_config_text(const std::string& ini, const std::vector<std::string>& overrides) {
  std::string file;
  const auto vm = parse(overrides, &file, &ini);
  return build(config_schema(), vm);
}

}  // namespace rondel
