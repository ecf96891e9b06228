#include "core/Config.hpp"

#include <algorithm>
#include <boost/any.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>

#include "core/ConfigRead.hpp"
#include "core/ConfigSchema.hpp"
#include "core/DiscStore.hpp"
#include "core/Errors.hpp"
#include "core/InputFile.hpp"

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
    if (sec == "material" && c.materials.front().name != kDefaultMaterial) continue;  // [material.NAME] instead
    if (sec != section) {
      out << (section.empty() ? "" : "\n") << "[" << sec << "]\n";
      section = sec;
    }
    out << name.substr(dot + 1) << " = " << value_text(vm[name].value()) << "\n";
  }
  return out.str();
}

}  // namespace

namespace config {

void read_run(const Reader&, Config& c) {
  check(!c.output.empty(), "run.output", "a directory name", "''");
  if (std::find(c.snapshot_fields.begin(), c.snapshot_fields.end(), kPositionField) == c.snapshot_fields.end())
    c.snapshot_fields.emplace_back(kPositionField);  // the XDMF geometry
  const Domain& d = c.domain;
  check(d.xhi > d.xlo, "domain.xhi", "must be > domain.xlo", num(d.xhi));
  check(d.yhi > d.ylo, "domain.yhi", "must be > domain.ylo", num(d.yhi));
  check(std::isfinite(d.length_x()), "domain.xhi", "domain.xhi - domain.xlo must be a finite length",
        num(d.xhi) + " - " + num(d.xlo));
  check(std::isfinite(d.length_y()), "domain.yhi", "domain.yhi - domain.ylo must be a finite length",
        num(d.yhi) + " - " + num(d.ylo));
  const std::pair<const char*, double> rates[] = {
      {"cell.rate_xx", d.L.xx}, {"cell.rate_xy", d.L.xy}, {"cell.rate_yy", d.L.yy}};
  for (const auto& [key, value] : rates)
    check(value == 0.0 || (d.periodic_x && d.periodic_y), key,
          "0 unless the cell is periodic in x and y (domain.periodic_x = true, domain.periodic_y = true)", num(value));
  const std::tuple<const char*, double, const char*, double> targets[] = {
      {"cell.stress_xx", c.cell_stress_xx, "cell.rate_xx", d.L.xx},
      {"cell.stress_yy", c.cell_stress_yy, "cell.rate_yy", d.L.yy}};
  for (const auto& [key, target, rate_key, rate] : targets) {
    if (target == 0.0) continue;
    check(d.periodic_x && d.periodic_y, key,
          "0 unless the cell is periodic in x and y (domain.periodic_x = true, domain.periodic_y = true)", num(target));
    check(rate == 0.0, key, std::string("0 when ") + rate_key + " is given (a component has a rate or a target)",
          num(target));
    check(c.cell_servo_gain > 0.0, "cell.servo_gain", std::string("> 0 with ") + key + " (the servo that holds it)",
          num(c.cell_servo_gain));
  }
  c.domain.rates();
}

}  // namespace config

namespace {

Config build(const LawCatalog& laws, const DynamicSections& dynamic, const po::variables_map& vm) {
  po::options_description schema = config_schema(laws, dynamic);
  std::vector<KeyReader<Config>> readers;
  {
    po::options_description declared;
    std::vector<KeySpec> keys;
    config::declare_fixed_keys(laws, declared, keys, &readers);
  }
  const Reader r{vm};
  // The one validation pass: every value given is finite and in the range declared with its key.
  validate_values(config_keys(laws, dynamic), vm);
  Config c;
  for (const auto& read : readers) read(vm, c);
  if (vm.count("resume")) c.resume_dir = vm["resume"].as<std::string>();
  read_run(r, c);
  read_materials(r, dynamic, c);
  read_contact(laws, r, c);
  read_walls(c);
  read_pairs(laws, r, dynamic, c);
  read_scene(c);
  read_scene_materials(c);
  c.resolved_text = resolved_text(laws, schema, vm, c);
  return c;
}

std::string read_text(const std::string& file) {
  const std::string problem = input_file_problem(file, "the configuration file", kMaxIniBytes);
  if (!problem.empty()) throw ConfigError(problem);
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
    // The INI on its own first: Boost keeps the command line's value of a key and would never parse the
    // INI's (a repeated key, or a value that is not a number, would pass unseen when the command line sets it).
    const auto store_ini = [&](const std::string& text) {
      std::istringstream alone(text), in(text);
      po::variables_map check;
      po::store(po::parse_config_file(alone, schema, false), check);
      po::store(po::parse_config_file(in, schema, false), vm);
    };
    if (ini_text) {
      store_ini(*ini_text);
    } else if (vm.count("config")) {
      const std::string file = vm["config"].as<std::string>();
      *file_out = file;
      try {
        store_ini(file_text.empty() ? read_text(file) : file_text);
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
       "and every number of a list, must be finite).\n"
       "Environment: RONDEL_HUGE_PAGES = 1 (the default: malloc asks for transparent huge pages, the program\n"
       "running itself again with GLIBC_TUNABLES=glibc.malloc.hugetlb=1) or 0 (4 KiB pages).\n\n"
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
