// rondel._driver: the compiled half of the Python package `rondel` (tools/rondel/driver.py wraps it; docs/python.md).
// It drives the same composition root as the executable: prepare_launch (app/Launch.hpp), Simulation and Runner.
// Nothing here steps, writes or restarts by itself; it converts arguments, errors and views.
#include <mpi.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "app/Launch.hpp"
#include "app/Runner.hpp"
#include "app/Simulation.hpp"
#include "app/Steering.hpp"
#include "core/Errors.hpp"
#include "parallel/Communicator.hpp"

namespace py = pybind11;

namespace rondel {
namespace {

static_assert(sizeof(Vec2) == 2 * sizeof(double), "a Vec2 column is viewed as an (n, 2) array of doubles");

// A simulation driven from Python: its own duplicate of the script's communicator (collective to make and to
// free), the Simulation and its Runner.
class Driver {
 public:
  Driver(const std::vector<std::string>& args, const std::string* ini_text, MPI_Comm comm, bool write_files) {
    MPI_Comm_dup(comm, &comm_handle_);
    comm_ = std::make_unique<Communicator>(comm_handle_);
    Launch launch = prepare_launch({args, ini_text}, *comm_);
    sim_ = std::make_unique<Simulation>(std::move(launch.config), *comm_, write_files, launch.checkpoint);
    runner_ = std::make_unique<Runner>(*sim_);
  }
  Driver(const Driver&) = delete;
  Driver& operator=(const Driver&) = delete;
  ~Driver() {
    // Not collective (the garbage collector runs on each rank in its own time): the communicator is freed by close().
    runner_.reset();
    sim_.reset();
  }

  Simulation& sim() {
    if (!sim_) throw std::runtime_error("the simulation is closed");
    return *sim_;
  }
  // Steps n (past run.steps too) with the run's schedules of output; the signal that stopped them (0: none).
  int step(std::int64_t n) {
    if (n < 0) throw InputError("step(n): n = " + std::to_string(n) + " must be >= 0");
    if (finished_) throw std::runtime_error("the run is finished (finish() or run() was called): no more steps");
    start();
    py::gil_scoped_release free;
    ++generation_;
    return runner_->advance(n);
  }
  RunSummary finish() {
    if (finished_) return summary_;
    start();
    summary_ = runner_->finish();
    finished_ = true;
    return summary_;
  }
  RunSummary run() {
    start();
    const std::int64_t left = sim().config().steps - sim().step_count();
    if (left > 0) step(left);
    return finish();
  }
  void close() {
    runner_.reset();
    sim_.reset();
    if (comm_handle_ != MPI_COMM_NULL) MPI_Comm_free(&comm_handle_);
  }
  std::string checkpoint() {
    start();
    return runner_->checkpoint();
  }
  void snapshot() {
    start();
    runner_->snapshot();
  }
  std::uint64_t generation() const { return generation_; }
  bool finished() const { return finished_; }
  // A write: views of the discs taken before it are stale too.
  void touched() { ++generation_; }

 private:
  void start() {
    if (!runner_->started()) runner_->start();
  }
  MPI_Comm comm_handle_ = MPI_COMM_NULL;
  std::unique_ptr<Communicator> comm_;
  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<Runner> runner_;
  std::uint64_t generation_ = 0;
  bool finished_ = false;
  RunSummary summary_;
};

// A read-only numpy view of the first n_owned entries of a column, kept alive by `owner` (the Driver's Python object).
template <class T>
py::array column(const std::vector<T>& v, std::size_t n, py::handle owner) {
  py::array a(py::dtype::of<T>(), {n}, {sizeof(T)}, v.data(), owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}
py::array column(const std::vector<Vec2>& v, std::size_t n, py::handle owner) {
  py::array a(py::dtype::of<double>(), {n, std::size_t{2}}, {sizeof(Vec2), sizeof(double)},
              reinterpret_cast<const double*>(v.data()), owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

py::dict summary_dict(const RunSummary& s) {
  py::dict d;
  d["stop_signal"] = s.stop_signal;
  d["last_checkpoint"] = s.last_checkpoint;
  d["steps"] = s.steps;
  d["discs"] = s.discs;
  d["wall_seconds"] = s.wall_seconds;
  d["disc_steps_per_second"] = s.disc_steps_per_second;
  d["dt"] = s.dt;
  d["critical_dt"] = s.critical.dt;
  d["critical_mode"] = s.critical.mode;
  d["ledger_residual"] = s.ledger_residual;
  return d;
}

std::vector<Vec2> vec2s(const py::array_t<double, py::array::c_style | py::array::forcecast>& a, const char* what) {
  if (a.ndim() != 2 || a.shape(1) != 2)
    throw InputError(std::string(what) + ": an array of shape (n, 2) expected, one row (x, y) per gid");
  std::vector<Vec2> out(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t k = 0; k < a.shape(0); ++k) out[static_cast<std::size_t>(k)] = {a.at(k, 0), a.at(k, 1)};
  return out;
}

}  // namespace
}  // namespace rondel

namespace {

using DriverClass = py::class_<rondel::Driver>;

// The errors of the code as Python exceptions: configuration and input mistakes are ValueErrors.
void register_errors(py::module_& m) {
  using namespace rondel;
  static py::exception<ConfigError> config_error(m, "ConfigError", PyExc_ValueError);
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<InstabilityError> instability(m, "InstabilityError", PyExc_RuntimeError);
  static py::exception<IoError> io_error(m, "IoError", PyExc_OSError);
  static py::exception<StoppedInSetup> stopped(m, "StoppedInSetup", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ConfigError& e) {
      config_error(e.what());
    } catch (const InputError& e) {
      input_error(e.what());
    } catch (const InstabilityError& e) {
      instability(e.what());
    } catch (const IoError& e) {
      io_error(e.what());
    } catch (const StoppedInSetup& e) {
      stopped(e.what());
    } catch (const HelpRequested& h) {
      PyErr_SetString(PyExc_ValueError, h.text.c_str());
    }
  });
}

// Construction, stepping, the end of the run and the read-only state.
void bind_life(DriverClass& c) {
  using namespace rondel;
  c.def(py::init([](const std::vector<std::string>& args, std::optional<std::string> ini_text,
                    std::int64_t fortran_comm, bool write_files) {
          const std::string* text = ini_text ? &*ini_text : nullptr;
          return std::make_unique<Driver>(args, text, MPI_Comm_f2c(static_cast<MPI_Fint>(fortran_comm)), write_files);
        }),
        py::arg("args"), py::arg("ini_text"), py::arg("fortran_comm"), py::arg("write_files"))
      .def("step", &Driver::step)
      .def("run", [](Driver& d) { return summary_dict(d.run()); })
      .def("finish", [](Driver& d) { return summary_dict(d.finish()); })
      .def("close", &Driver::close)
      .def_property_readonly("generation", &Driver::generation)
      .def_property_readonly("finished", &Driver::finished)
      .def_property_readonly("time", [](Driver& d) { return d.sim().time(); })
      .def_property_readonly("step_count", [](Driver& d) { return d.sim().step_count(); })
      .def_property_readonly("dt", [](Driver& d) { return d.sim().dt(); })
      .def_property_readonly("critical_dt", [](Driver& d) { return d.sim().critical().dt; })
      .def_property_readonly("critical_mode", [](Driver& d) { return d.sim().critical().mode; })
      .def_property_readonly("critical_pair", [](Driver& d) { return d.sim().critical().pair; })
      .def_property_readonly("rank", [](Driver& d) { return d.sim().comm().rank(); })
      .def_property_readonly("ranks", [](Driver& d) { return d.sim().comm().size(); })
      .def_property_readonly("output", [](Driver& d) { return d.sim().config().output; })
      .def_property_readonly("run_steps", [](Driver& d) { return d.sim().config().steps; });
}

// This rank's discs as numpy views.
void bind_views(DriverClass& c) {
  using namespace rondel;
  c.def("columns", [](py::object self) {
    Driver& d = self.cast<Driver&>();
    const DiscStore& s = d.sim().discs();
    const std::size_t n = s.n_owned();
    py::dict c;
    c["gid"] = column(s.gid, n, self);
    c["position"] = column(s.position, n, self);
    c["velocity"] = column(s.velocity, n, self);
    c["omega"] = column(s.omega, n, self);
    c["theta"] = column(s.theta, n, self);
    c["radius"] = column(s.radius, n, self);
    c["mass"] = column(s.mass, n, self);
    c["material"] = column(s.material, n, self);
    c["force"] = column(s.force, n, self);
    c["torque"] = column(s.torque, n, self);
    c["flags"] = column(s.flags, n, self);
    return c;
  });
}

// The checked writes (app/Steering.hpp).
void bind_writes(DriverClass& c) {
  using namespace rondel;
  c.def("set_velocity",
        [](Driver& d, std::vector<std::int64_t> gids, py::array_t<double> v) {
          steering::set_velocity(d.sim(), gids, vec2s(v, "velocity"));
          d.touched();
        })
      .def("set_omega",
           [](Driver& d, std::vector<std::int64_t> gids, std::vector<double> w) {
             steering::set_omega(d.sim(), gids, w);
             d.touched();
           })
      .def("set_fixed",
           [](Driver& d, std::vector<std::int64_t> gids, bool fixed) {
             steering::set_fixed(d.sim(), gids, fixed);
             d.touched();
           })
      .def("set_body_force", [](Driver& d, std::vector<std::int64_t> gids,
                                py::array_t<double> f) { steering::set_body_force(d.sim(), gids, vec2s(f, "force")); })
      .def("set_cell_rates",
           [](Driver& d, double xx, double yy, double xy) { steering::set_cell_rates(d.sim(), xx, yy, xy); })
      .def("set_cell_stress", [](Driver& d, double xx, double yy) { steering::set_cell_stress(d.sim(), xx, yy); })
      .def("set_wall_velocity",
           [](Driver& d, std::size_t wall, double vx, double vy) {
             steering::set_wall_velocity(d.sim(), wall, {vx, vy});
           })
      .def("set_wall_stress",
           [](Driver& d, std::size_t wall, double stress) { steering::set_wall_stress(d.sim(), wall, stress); })
      .def("set_wall_strain_rate",
           [](Driver& d, std::size_t wall, double rate) { steering::set_wall_strain_rate(d.sim(), wall, rate); });
}

// The walls, the ledger, the tables' rows and the outputs on demand.
void bind_tables(DriverClass& c) {
  using namespace rondel;
  c.def("walls",
        [](Driver& d) {
          d.sim().settle_errors();  // collective: the loads of this step
          py::list out;
          for (const Wall& w : d.sim().walls()) {
            py::dict x;
            x["control"] = w.control == Wall::Control::velocity ? "velocity"
                           : w.control == Wall::Control::servo  ? "servo"
                                                                : "strain_rate";
            x["velocity"] = py::make_tuple(w.velocity.x, w.velocity.y);
            x["target_stress"] = w.target_stress;
            x["strain_rate"] = w.strain_rate;
            x["force"] = py::make_tuple(w.force.x, w.force.y);
            x["normal_force"] = w.normal_force;
            x["contacts"] = w.contacts;
            x["p0"] = py::make_tuple(w.p0.x, w.p0.y);
            x["p1"] = py::make_tuple(w.p1.x, w.p1.y);
            out.append(x);
          }
          return out;
        })
      .def("cell",
           [](Driver& d) {
             Simulation& s = d.sim();
             const Domain& c = s.config().domain;
             py::dict x;
             x["deforms"] = s.config().cell_deforms();
             x["lo"] = py::make_tuple(c.xlo, c.ylo);
             x["length"] = py::make_tuple(c.length_x(), c.length_y());
             x["tilt"] = c.tilt;
             x["rate"] = py::make_tuple(c.L.xx, c.L.yy, c.L.xy);
             x["target_stress"] =
                 py::make_tuple(s.steered_cell_control().target(0), s.steered_cell_control().target(1));
             return x;
           })
      .def("ledger",
           [](Driver& d) {
             const EnergyLedger g = d.sim().global_ledger();
             py::dict out;
             g.for_each_term([&](const LedgerTermInfo& t, double v) { out[py::str(std::string(t.name))] = v; });
             return out;
           })
      .def("diagnostics",
           [](Driver& d) {
             const DiagnosticsRow row = d.sim().diagnostics();
             return py::make_tuple(DiagnosticsWriter::header(), DiagnosticsWriter::format(row));
           })
      .def("measures",
           [](Driver& d) {
             const MeasuresRow row = d.sim().measures();
             return py::make_tuple(MeasuresRow::header(), row.csv());
           })
      .def("write_checkpoint", &Driver::checkpoint)
      .def("write_snapshot", &Driver::snapshot);
}

}  // namespace

PYBIND11_MODULE(_driver, m) {
  m.doc() = "The compiled driver of rondel (use rondel.Simulation; docs/python.md).";
  register_errors(m);
  DriverClass c(m, "Driver");
  bind_life(c);
  bind_views(c);
  bind_writes(c);
  bind_tables(c);
}
