# ctest install.package: `cmake --install` of the build into a scratch prefix, checks that the executables,
# libraries, headers, package configuration, tools, scenes and documentation are there and work from it, then
# configures, builds and runs tests/install/consumer, a project that finds Rondel with find_package(Rondel).
#   cmake -D BUILD_DIR=... -D SOURCE_DIR=... -D WORK_DIR=... -D GENERATOR=... -P test_install.cmake
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR GENERATOR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "test_install.cmake: -D ${var}=... is required")
  endif()
endforeach()

# Runs a command in WORK_DIR; stops the test with its output unless it exits 0.
function(run_checked what)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "install.package: ${what} failed (exit ${rc}):\n${ARGN}\n${out}")
  endif()
  message(STATUS "install.package: ${what}: ok")
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
run_checked("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# What the install must hold (the library directory is lib or lib64, as GNUInstallDirs chose).
file(GLOB config_dirs ${prefix}/lib*/cmake/Rondel)
if(NOT config_dirs)
  message(FATAL_ERROR "install.package: no lib*/cmake/Rondel under ${prefix}")
endif()
list(GET config_dirs 0 config_dir)
set(missing "")
foreach(f bin/rondel bin/rondel_bench bin/rondel_bench_io include/rondel/app/Simulation.hpp
          include/rondel/core/Config.hpp include/rondel/physics/LawRegistry.hpp include/rondel/parallel/StateFile.hpp
          share/rondel/tools/h5info.py share/rondel/tools/picture.py share/rondel/inputs/deposition.ini
          share/rondel/inputs/two_disc_impact.csv share/doc/rondel/README.md share/doc/rondel/FORMAT.md
          share/doc/rondel/architecture.md)
  if(NOT EXISTS ${prefix}/${f})
    list(APPEND missing ${f})
  endif()
endforeach()
foreach(f RondelConfig.cmake RondelConfigVersion.cmake RondelTargets.cmake FindMETIS.cmake)
  if(NOT EXISTS ${config_dir}/${f})
    list(APPEND missing ${config_dir}/${f})
  endif()
endforeach()
foreach(lib core physics parallel app)
  if(NOT EXISTS ${config_dir}/../../librondel_${lib}.a)
    list(APPEND missing librondel_${lib}.a)
  endif()
endforeach()
if(missing)
  message(FATAL_ERROR "install.package: not installed under ${prefix}: ${missing}")
endif()
# The checkout's own scripts (they cd to the repository root) must not be installed.
if(EXISTS ${prefix}/share/rondel/tools/setup.sh OR EXISTS ${prefix}/share/rondel/tools/run_tests.sh)
  message(FATAL_ERROR "install.package: the checkout scripts (setup.sh, run_tests.sh) were installed")
endif()

# The installed programs run from the prefix.
run_checked("installed rondel --help" ${prefix}/bin/rondel --help)
if(NOT last_output MATCHES "run\\.steps")
  message(FATAL_ERROR "install.package: 'rondel --help' does not list run.steps:\n${last_output}")
endif()
run_checked("installed tools/h5info.py --help" /usr/bin/python3 ${prefix}/share/rondel/tools/h5info.py --help)
# The Python driver, when it was built, beside the reader: PYTHONPATH=<prefix>/share/rondel/tools (docs/python.md).
file(GLOB driver ${prefix}/share/rondel/tools/rondel/_driver*.so)
if(PYTHON_DRIVER AND NOT driver)
  message(FATAL_ERROR "install.package: the Python driver was built but not installed beside the reader")
endif()
if(driver)
  run_checked("the installed Python driver steps a scene" ${CMAKE_COMMAND} -E env
              PYTHONPATH=${prefix}/share/rondel/tools --unset=RONDEL_DRIVER_DIR /usr/bin/python3 -c
              "import rondel\ns = rondel.Simulation('${prefix}/share/rondel/inputs/two_disc_impact.ini', files=False)\ns.step(10)\nprint('driver', s.step_count, rondel.__path__)")
  if(NOT last_output MATCHES "driver 10 \\['${prefix}/share/rondel/tools/rondel'\\]")
    message(FATAL_ERROR "install.package: unexpected output of the installed driver:\n${last_output}")
  endif()
endif()

# A project of its own finds the package in the prefix (and nowhere else) and links Rondel::app.
set(consumer ${WORK_DIR}/consumer-build)
run_checked("configure the consumer" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/consumer -B ${consumer}
            -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix}
            -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
file(STRINGS ${consumer}/CMakeCache.txt rondel_dir REGEX "^Rondel_DIR:")
if(NOT rondel_dir MATCHES "${config_dir}")
  message(FATAL_ERROR "install.package: the consumer found Rondel elsewhere: ${rondel_dir} (want ${config_dir})")
endif()
run_checked("build the consumer" ${CMAKE_COMMAND} --build ${consumer})
# The determinism rule travels with the package (the headers hold inline kernels).
file(GLOB_RECURSE flag_files ${consumer}/CMakeFiles/rondel_consumer.dir/flags.make)
if(flag_files)
  file(READ "${flag_files}" flags)
  if(NOT flags MATCHES "-ffp-contract=off")
    message(FATAL_ERROR "install.package: the consumer compiles without -ffp-contract=off:\n${flags}")
  endif()
endif()
run_checked("run the consumer" ${consumer}/rondel_consumer)
if(NOT last_output MATCHES "rolling laws: none .*jiang_plastic" OR NOT last_output MATCHES "steps 10, normal law linear")
  message(FATAL_ERROR "install.package: unexpected consumer output:\n${last_output}")
endif()
message(STATUS "install.package: passed")
