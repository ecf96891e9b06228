// Test support of the checkpoint refusals (test_checkpoint_errors.cpp) and of --resume's choice of checkpoint
// (test_checkpoint_resume.cpp): a scene with history, a valid checkpoint made once per suite, the refusal probes
// and the HDF5 edits of a closed file. Internal to each test file (an unnamed namespace).
#pragma once
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "app/Checkpointing.hpp"
#include "app/Simulation.hpp"
#include "core/Config.hpp"
#include "core/Errors.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Hdf5File.hpp"
#include "parallel/StateFile.hpp"
#include "support/Assertions.hpp"
#include "support/Quiet.hpp"
#include "support/Restamp.hpp"
#include "support/Scenes.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;

using test::QuietCout;
using test::TempDir;

// Discs dropped into a box with a wall moving in from the left, Coulomb friction and a rolling law with
// history (the law block follows contact.rolling).
std::string scene(const std::string& law = "wang") { return test::moving_wall_box_ini(law); }

inline Config config_for(const fs::path& out, const std::string& law = "wang", std::vector<std::string> more = {}) {
  more.push_back("--run.output=" + out.string());
  return parse_config_text(scene(law), more);
}

// A valid checkpoint after `steps` steps, written into `out`; returns its path.
inline fs::path make_checkpoint(const fs::path& out, int steps, const std::string& law = "wang") {
  const Communicator self(MPI_COMM_SELF);
  QuietCout quiet;
  Simulation sim(config_for(out, law, {"--run.overwrite=true"}), self, true);
  for (int s = 0; s < steps; ++s) sim.step();
  return sim.write_checkpoint();
}

// Constructs a restart from `file` with `config`; returns the message of the expected error type, or ""
// after recording a failure when the restart is accepted or throws something else.
template <class Error>
inline std::string restart_refusal(const fs::path& file, Config config) {
  const Communicator self(MPI_COMM_SELF);
  try {
    QuietCout quiet;
    Simulation sim(std::move(config), self, true, file.string());
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "restart from " << file << ": expected "
                  << (std::is_same_v<Error, InputError> ? "InputError" : "ConfigError") << ", got " << typeid(e).name()
                  << ": " << e.what();
    return "";
  }
  ADD_FAILURE() << "the restart from " << file << " was accepted";
  return "";
}

template <class Error>
std::string restart_refusal(const fs::path& file, const fs::path& out, const std::string& law = "wang",
                            const std::vector<std::string>& more = {}) {
  return restart_refusal<Error>(file, config_for(out, law, more));
}

// The same through scene.type = file (a new run whose discs come from `file`).
inline std::string scene_file_refusal(const fs::path& file, const fs::path& out) {
  const Communicator self(MPI_COMM_SELF);
  try {
    QuietCout quiet;
    Simulation sim(config_for(out, "wang", {"--scene.type=file", "--scene.file=" + file.string()}), self, true);
  } catch (const InputError& e) {
    return e.what();
  } catch (const ConfigError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "scene.file = " << file << ": got " << typeid(e).name() << ": " << e.what();
    return "";
  }
  ADD_FAILURE() << "scene.file = " << file << " was accepted";
  return "";
}

inline std::string newest_refusal(const fs::path& dir) {
  try {
    const std::string found = Checkpointing::newest_checkpoint(dir.string(), Communicator(MPI_COMM_SELF));
    ADD_FAILURE() << "newest_checkpoint(" << dir << ") returned " << found;
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

inline void overwrite_bytes(const fs::path& file, std::uintmax_t offset, std::size_t count, char value = 'Z') {
  std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>(offset));
  const std::string bytes(count, value);
  f.write(bytes.data(), static_cast<std::streamsize>(count));
}

// HDF5 edits of a closed file (serial access).
struct H5 {
  hid_t file;
  explicit H5(const fs::path& p) : file(H5Fopen(p.string().c_str(), H5F_ACC_RDWR, H5P_DEFAULT)) {
    if (file < 0) throw std::runtime_error("cannot open " + p.string());
  }
  ~H5() { H5Fclose(file); }
  void set_int(const char* object, const char* name, std::int64_t v) const {
    // The object held open while its attribute is written (HDF5 1.10 cannot write one opened by path).
    const hid_t o = H5Oopen(file, object, H5P_DEFAULT);
    const hid_t a = H5Aopen(o, name, H5P_DEFAULT);
    H5Awrite(a, H5T_NATIVE_INT64, &v);
    H5Aclose(a);
    H5Oclose(o);
  }
  void remove(const char* object, const char* name) const { H5Adelete_by_name(file, object, name, H5P_DEFAULT); }
  void set_string(const char* object, const char* name, const std::string& v) const {
    if (H5Aexists_by_name(file, object, name, H5P_DEFAULT) > 0) remove(object, name);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, v.size());
    H5Tset_strpad(type, H5T_STR_NULLPAD);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate_by_name(file, object, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, type, v.data());
    H5Aclose(a);
    H5Sclose(space);
    H5Tclose(type);
  }
  haddr_t offset_of(const char* dataset) const {
    const hid_t d = H5Dopen2(file, dataset, H5P_DEFAULT);
    const haddr_t at = H5Dget_offset(d);
    H5Dclose(d);
    return at;
  }
  hsize_t storage_of(const char* dataset) const {
    const hid_t d = H5Dopen2(file, dataset, H5P_DEFAULT);
    const hsize_t n = H5Dget_storage_size(d);
    H5Dclose(d);
    return n;
  }
};

// A fixture with one valid checkpoint (step 1500, Wang rolling), made once for the suite.
class CheckpointErrors : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("rondel-ckerr");
    valid_ = new fs::path(make_checkpoint(*dir_ / "source", 1500));
  }
  static void TearDownTestSuite() {
    delete valid_;
    delete dir_;
  }
  // A fresh copy of the valid checkpoint.
  fs::path copy(const std::string& name) const {
    const fs::path p = *dir_ / name;
    fs::create_directories(p.parent_path());
    fs::copy_file(*valid_, p, fs::copy_options::overwrite_existing);
    return p;
  }
  fs::path out(const std::string& name) const { return *dir_ / ("out-" + name); }
  inline static TempDir* dir_ = nullptr;
  inline static fs::path* valid_ = nullptr;
};

}  // namespace
}  // namespace rondel
