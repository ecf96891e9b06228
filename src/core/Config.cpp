#include "core/Config.hpp"

#include <algorithm>
#include <boost/any.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/ConfigRead.hpp"
#include "core/ConfigSchema.hpp"
#include "core/Errors.hpp"

namespace rondel {

namespace po = boost::program_options;

namespace {

using namespace config;

std::string value_text(const boost::any& v) {
  std::ostringstream s;
  s.precision(17);
  if (auto p = boost::any_cast<double>(&v))
    s << *p;
  else if (auto p = boost::any_cast<std::int64_t>(&v))
    s << *p;
  else if (auto p = boost::any_cast<std::uint64_t>(&v))
    s << *p;
  else if (auto p = boost::any_cast<int>(&v))
    s << *p;
  else if (auto p = boost::any_cast<bool>(&v))
    s << (*p ? "true" : "false");
  else if (auto p = boost::any_cast<std::string>(&v))
    s << *p;
  return s.str();
}

// INI text of every key that has a value, grouped by section in declaration order.
// Blocks of laws that are not selected are left out (their defaults would read as a stale block).
std::string resolved_text(const LawCatalog& laws, const po::options_description& schema, const po::variables_map& vm,
                          const Config& c) {
  std::ostringstream out;
  std::string section;
  for (const auto& opt : schema.options()) {
    const std::string& name = opt->long_name();
    if (!vm.count(name)) continue;
    const auto dot = name.rfind('.');  // [material.glass] density = ..., [linear.glass.steel] k_n = ...
    const std::string sec = name.substr(0, dot);
    if (config::unselected_law_block(laws, c, sec.substr(0, sec.find('.')))) continue;
    if (sec == "material" && c.materials.front().name != "default") continue;  // [material.NAME] instead
    if (sec != section) {
      out << (section.empty() ? "" : "\n") << "[" << sec << "]\n";
      section = sec;
    }
    out << name.substr(dot + 1) << " = " << value_text(vm[name].value()) << "\n";
  }
  return out.str();
}

void read_run(const Reader& r, Config& c) {
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
  c.max_energy_gain = r.get<double>("run.max_energy_gain");
  check(c.max_energy_gain > 0.0 && std::isfinite(c.max_energy_gain), "run.max_energy_gain", "must be > 0 and finite",
        num(c.max_energy_gain));
  c.local_damping = r.get<double>("run.local_damping");
  check(c.local_damping >= 0.0 && c.local_damping < 1.0, "run.local_damping",
        "must be in [0, 1): the fraction alpha of each force component taken against the motion (0 = off)",
        num(c.local_damping));
  c.reset_history = r.get<bool>("run.reset_history");
  c.accept_materials = r.get<bool>("run.accept_materials");
}

void read_output(const Reader& r, Config& c) {
  c.snapshot_every = r.get<std::int64_t>("output.snapshot_every");
  check(c.snapshot_every >= 0, "output.snapshot_every", "must be >= 0", std::to_string(c.snapshot_every));
  {
    std::istringstream in(r.get<std::string>("output.snapshot_fields"));
    const std::string allowed =
        " gid material radius mass inertia position velocity theta omega force torque flags rank ";
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
  c.verify_checkpoints = r.get<bool>("output.verify_checkpoints");
  c.thermo_every = r.get<std::int64_t>("output.thermo_every");
  check(c.thermo_every >= 0, "output.thermo_every", "must be >= 0", std::to_string(c.thermo_every));
  c.final_format = r.get<std::string>("output.final_format");
  check(c.final_format == "hex" || c.final_format == "decimal", "output.final_format", "hex or decimal",
        c.final_format);
  if (r.vm.count("resume")) c.resume_dir = r.vm["resume"].as<std::string>();
  c.diag_every = r.get<std::int64_t>("diagnostics.every");
  check(c.diag_every > 0, "diagnostics.every", "must be > 0", std::to_string(c.diag_every));
}

// [domain], [gravity], [material], [neighbour], [parallel].
void read_domain(const Reader& r, Config& c) {
  const char* box_keys[4] = {"domain.xlo", "domain.xhi", "domain.ylo", "domain.yhi"};
  for (const char* k : box_keys) r.required(k, " (the simulation box)");
  c.domain.xlo = r.get<double>("domain.xlo");
  c.domain.xhi = r.get<double>("domain.xhi");
  c.domain.ylo = r.get<double>("domain.ylo");
  c.domain.yhi = r.get<double>("domain.yhi");
  check(c.domain.xhi > c.domain.xlo, "domain.xhi", "must be > domain.xlo", num(c.domain.xhi));
  check(c.domain.yhi > c.domain.ylo, "domain.yhi", "must be > domain.ylo", num(c.domain.yhi));
  check(std::isfinite(c.domain.length_x()), "domain.xhi", "domain.xhi - domain.xlo must be a finite length",
        num(c.domain.xhi) + " - " + num(c.domain.xlo));
  check(std::isfinite(c.domain.length_y()), "domain.yhi", "domain.yhi - domain.ylo must be a finite length",
        num(c.domain.yhi) + " - " + num(c.domain.ylo));
  c.domain.periodic_x = r.get<bool>("domain.periodic_x");
  c.domain.periodic_y = r.get<bool>("domain.periodic_y");
  c.gravity = {r.get<double>("gravity.x"), r.get<double>("gravity.y")};
  c.skin = r.get<double>("neighbour.skin");
  non_negative(c.skin, "neighbour.skin");
  c.partitioner = r.get<std::string>("parallel.partitioner");
  check(c.partitioner == "sfc" || c.partitioner == "metis" || c.partitioner == "grid", "parallel.partitioner",
        "sfc | grid | metis", c.partitioner);
  c.balance_every = r.get<std::int64_t>("parallel.balance_every");
  check(c.balance_every >= 0, "parallel.balance_every", "must be >= 0", std::to_string(c.balance_every));
  c.balance_threshold = r.get<double>("parallel.balance_threshold");
  check(c.balance_threshold > 1.0, "parallel.balance_threshold", "must be > 1", num(c.balance_threshold));
  c.force_balance = r.get<bool>("parallel.force_balance");
  c.check_every = r.get<std::int64_t>("parallel.check_every");
  check(c.check_every >= 1 && c.check_every <= 1000, "parallel.check_every", "1 to 1000",
        std::to_string(c.check_every));
}

Config build(const LawCatalog& laws, const DynamicSections& dynamic, const po::variables_map& vm) {
  const po::options_description schema = config_schema(laws, dynamic);
  const Reader r{vm};
  // The one validation pass: every value given is finite and in the range declared with its key.
  validate_values(config_keys(laws, dynamic), vm);
  Config c;
  read_run(r, c);
  read_output(r, c);
  read_domain(r, c);
  read_materials(r, dynamic, c);
  read_contact(laws, r, c);
  read_walls(r, c);
  read_pairs(laws, r, dynamic, c);
  read_scene(r, c);
  read_scene_materials(r, c);
  c.resolved_text = resolved_text(laws, schema, vm, c);
  return c;
}

std::string read_text(const std::string& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw ConfigError("the configuration file '" + file + "' is a directory, not an INI file");
  std::ifstream in(file);
  if (!in) throw ConfigError("cannot read the configuration file '" + file + "'");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw ConfigError("cannot read the configuration file '" + file + "'");
  return s.str();
}

// Boost's default style guesses an option from a prefix (--scene.x would be scene.x0): only whole keys.
constexpr int kCommandLineStyle = po::command_line_style::default_style & ~po::command_line_style::allow_guessing;

// The message of a Boost parse error, with the closest declared key for an unknown one.
std::string parse_message(const po::error& e, const std::vector<KeySpec>& keys) {
  std::string message = e.what();
  if (const auto* unknown = dynamic_cast<const po::unknown_option*>(&e)) {
    std::string name = unknown->get_option_name();
    name.erase(0, name.find_first_not_of('-'));
    const std::string near = closest_key(name, keys);
    if (!near.empty()) message += " (did you mean '" + near + "'?)";
  }
  return message;
}

po::options_description command_line(const po::options_description& schema) {
  po::options_description cli("Command line");
  cli.add_options()("help,h", "print every key with its default, unit and meaning")(
      "config", po::value<std::string>(), "INI file (also the first positional argument)")(
      "resume", po::value<std::string>(), "continue from the newest complete checkpoint of this output directory");
  cli.add(schema);
  return cli;
}

// The INI file named on the command line ("" when none, or when the command line does not parse: the real
// parse then reports it).
std::string configuration_file(const LawCatalog& laws, const std::vector<std::string>& args) {
  po::positional_options_description pos;
  pos.add("config", 1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args)
                  .options(command_line(config_schema(laws)))
                  .positional(pos)
                  .style(kCommandLineStyle)
                  .allow_unregistered()
                  .run(),
              vm);
  } catch (const po::error&) {
    return "";
  }
  return vm.count("config") && !vm.count("help") ? vm["config"].as<std::string>() : "";
}

po::variables_map parse(const LawCatalog& laws, const std::vector<std::string>& args, std::string* file_out,
                        const std::string* ini_text, DynamicSections* dynamic_out) {
  // The names of [material.NAME] and pair sections come from the keys given (INI and command line).
  std::string file_text;
  std::vector<std::string> keys = argument_keys(args);
  if (!ini_text) {
    const std::string file = configuration_file(laws, args);
    if (!file.empty()) file_text = read_text(file);
  }
  for (std::string& k : ini_keys(ini_text ? *ini_text : file_text)) keys.push_back(std::move(k));
  *dynamic_out = dynamic_sections(laws, keys);
  const auto schema = config_schema(laws, *dynamic_out);
  const std::vector<KeySpec> specs = config_keys(laws, *dynamic_out);
  po::options_description cli = command_line(schema);
  po::positional_options_description pos;
  pos.add("config", 1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(args).options(cli).positional(pos).style(kCommandLineStyle).run(), vm);
    if (vm.count("help")) throw HelpRequested{config_help(laws)};
    refuse_empty_flags(specs, args, ini_text ? *ini_text : file_text);
    if (ini_text) {
      std::istringstream in(*ini_text);
      po::store(po::parse_config_file(in, schema, false), vm);
    } else if (vm.count("config")) {
      const std::string file = vm["config"].as<std::string>();
      std::istringstream in(file_text.empty() ? read_text(file) : file_text);
      *file_out = file;
      try {
        po::store(po::parse_config_file(in, schema, false), vm);
      } catch (const po::error& e) {
        throw ConfigError("in '" + file + "': " + parse_message(e, specs) + " (rondel --help lists every key)");
      }
    } else if (!vm.count("resume")) {
      throw ConfigError("no configuration file given: usage 'rondel FILE.ini [--section.key=value ...]'");
    }
    po::notify(vm);
  } catch (const po::error& e) {
    throw ConfigError(parse_message(e, specs) + " (rondel --help lists every key)");
  }
  return vm;
}

}  // namespace

std::string config_help(const LawCatalog& laws) {
  std::ostringstream s;
  s << "Usage: mpirun -n N rondel FILE.ini [--section.key=value ...]\n"
       "Every key may be set in FILE.ini (under [section] as 'key = value') or on the command line,\n"
       "which wins. Units in brackets; the range a value must lie in after its meaning (every number,\n"
       "and every number of a list, must be finite).\n\n"
    << config_schema(laws, {}, true);
  return s.str();
}

Config parse_config(const LawCatalog& laws, int argc, const char* const* argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string file;
  DynamicSections dynamic;
  const auto vm = parse(laws, args, &file, nullptr, &dynamic);
  Config c = build(laws, dynamic, vm);
  c.source_file = file;
  return c;
}

Config parse_config_text(const LawCatalog& laws, const std::string& ini, const std::vector<std::string>& overrides) {
  std::string file;
  DynamicSections dynamic;
  const auto vm = parse(laws, overrides, &file, &ini, &dynamic);
  return build(laws, dynamic, vm);
}

}  // namespace rondel
