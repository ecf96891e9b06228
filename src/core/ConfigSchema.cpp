#include "core/ConfigSchema.hpp"

#include <cstdint>
#include <string>

namespace rondel {

namespace po = boost::program_options;

namespace {
template <class T>
po::typed_value<T>* def(T v) {
  return po::value<T>()->default_value(v);
}
po::typed_value<std::string>* def(const char* v) { return po::value<std::string>()->default_value(v); }
template <class T>
po::typed_value<T>* opt() {
  return po::value<T>();
}
}  // namespace

po::options_description config_schema() {
  po::options_description run("[run]");
  run.add_options()
      ("run.steps", def<std::int64_t>(1000), "[-] number of time steps")
      ("run.dt", def(0.0), "[s] time step; 0 = safety x critical step")
      ("run.safety", def(0.2), "[-] fraction of the critical step used when run.dt = 0, in (0, 1]")
      ("run.force_dt", def(false), "[-] accept a run.dt above the critical step")
      ("run.output", def("rondel-output"), "[path] output directory (must not exist unless run.overwrite)")
      ("run.overwrite", def(false), "[-] reuse an existing output directory")
      ("run.progress", def(true), "[-] progress line on rank 0")
      ("run.max_overlap", def(0.5), "[-] stop when an overlap exceeds this fraction of the smaller radius");
  po::options_description diag("[diagnostics]");
  diag.add_options()("diagnostics.every", def<std::int64_t>(100), "[steps] interval of diagnostics.csv rows");
  po::options_description domain("[domain]");
  domain.add_options()
      ("domain.xlo", opt<double>(), "[m] box lower x (required)")
      ("domain.xhi", opt<double>(), "[m] box upper x (required)")
      ("domain.ylo", opt<double>(), "[m] box lower y (required)")
      ("domain.yhi", opt<double>(), "[m] box upper y (required)")
      ("domain.periodic_x", def(false), "[-] periodic in x")
      ("domain.periodic_y", def(false), "[-] periodic in y");
  po::options_description grav("[gravity]");
  grav.add_options()("gravity.x", def(0.0), "[m/s^2] gravity x")("gravity.y", def(0.0), "[m/s^2] gravity y");
  po::options_description mat("[material]");
  mat.add_options()
      ("material.density", def(2650.0), "[kg/m^3] disc density")
      ("material.thickness", def(1.0), "[m] disc thickness t (forces and energies are per t)");
  po::options_description contact("[contact]");
  contact.add_options()
      ("contact.normal", def("linear"), "[-] normal law: linear")
      ("contact.tangential", def("coulomb"), "[-] tangential law: coulomb | none")
      ("contact.rolling", def("none"), "[-] rolling law: none");
  po::options_description linear("[linear] normal spring-dashpot, no tension");
  linear.add_options()
      ("linear.k_n", opt<double>(), "[N/m] normal stiffness (required)")
      ("linear.zeta", opt<double>(), "[-] normal damping ratio >= 0 (default 0; give one of zeta, c_n, e)")
      ("linear.c_n", opt<double>(), "[N s/m] normal dashpot coefficient >= 0")
      ("linear.e", opt<double>(), "[-] restitution coefficient in (0, 1]");
  po::options_description coulomb("[coulomb] Cundall-Strack tangential spring with Coulomb cap");
  coulomb.add_options()
      ("coulomb.k_s", opt<double>(), "[N/m] tangential stiffness (required with coulomb)")
      ("coulomb.mu", opt<double>(), "[-] friction coefficient >= 0 (required with coulomb)")
      ("coulomb.zeta_t", def(0.0), "[-] tangential damping ratio >= 0");
  po::options_description wallc("[wall_contact] disc-wall parameters (default: the disc-disc ones)");
  wallc.add_options()
      ("wall_contact.k_n", opt<double>(), "[N/m] normal stiffness at walls")
      ("wall_contact.zeta", opt<double>(), "[-] normal damping ratio at walls")
      ("wall_contact.e", opt<double>(), "[-] restitution at walls, in (0, 1]")
      ("wall_contact.k_s", opt<double>(), "[N/m] tangential stiffness at walls")
      ("wall_contact.mu", opt<double>(), "[-] friction at walls >= 0");
  po::options_description neigh("[neighbour]");
  neigh.add_options()("neighbour.skin", def(0.0), "[m] Verlet skin; 0 = a quarter of the mean radius");
  po::options_description walls("[walls]");
  walls.add_options()
      ("walls.box", def(""), "[-] box sides that are walls: any of bottom left right top")
      ("walls.lines", def(""), "[m, m/s] infinite lines 'px py nx ny [vx vy]; ...' (n points to the discs)")
      ("walls.segments", def(""), "[m, m/s] segments 'x1 y1 x2 y2 [vx vy]; ...'");
  po::options_description scene("[scene]");
  scene.add_options()
      ("scene.type", opt<std::string>(), "[-] lattice_square | lattice_hex | random | csv (required)")
      ("scene.nx", def(0), "[-] lattice: discs per row")
      ("scene.ny", def(0), "[-] lattice: rows")
      ("scene.radius", def(0.0), "[m] lattice: disc radius")
      ("scene.spacing", def(0.0), "[m] lattice: centre distance; 0 = 2 x radius")
      ("scene.x0", def(0.0), "[m] lattice: centre of the first disc, x")
      ("scene.y0", def(0.0), "[m] lattice: centre of the first disc, y")
      ("scene.count", def<std::int64_t>(0), "[-] random: number of discs")
      ("scene.region", def(""), "[m] random: 'xlo xhi ylo yhi' region for centres+radii; empty = the box")
      ("scene.distribution", def("uniform_radius"), "[-] random: uniform_radius | uniform_area | list")
      ("scene.radius_min", def(0.0), "[m] random: smallest radius")
      ("scene.radius_max", def(0.0), "[m] random: largest radius")
      ("scene.sizes", def(""), "[m] random, list: radii 'r1 r2 ...'")
      ("scene.fractions", def(""), "[-] random, list: number fractions 'f1 f2 ...' (sum 1)")
      ("scene.seed", def<std::uint64_t>(1), "[-] random: seed (same scene on any rank count)")
      ("scene.max_attempts", def<std::int64_t>(1000), "[-] random: placement attempts per disc")
      ("scene.file", def(""), "[path] csv: 'id,x,y,radius[,vx,vy,omega]' rows, # comments")
      ("scene.replicate_x", def(1), "[-] csv: periodic copies in x")
      ("scene.replicate_y", def(1), "[-] csv: periodic copies in y")
      ("scene.vx", def(0.0), "[m/s] initial velocity x of every disc (csv: added to the file's)")
      ("scene.vy", def(0.0), "[m/s] initial velocity y")
      ("scene.omega", def(0.0), "[rad/s] initial angular velocity")
      ("scene.max_initial_overlap", def(0.01), "[-] largest initial overlap allowed, / smaller radius");
  po::options_description all;
  all.add(run).add(diag).add(domain).add(grav).add(mat).add(contact).add(linear).add(coulomb).add(wallc)
      .add(neigh).add(walls).add(scene);
  return all;
}

}  // namespace rondel
