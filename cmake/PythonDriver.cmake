# rondel._driver: the compiled half of the Python package rondel (tools/rondel/driver.py; docs/python.md), built
# with pybind11 (Debian: python3-pybind11, python3-dev) for /usr/bin/python3. Without pybind11 it is not built and
# `import rondel` still reads files; a driver call then says what to install.
# In the build tree it lands in build/python/rondel/, where tools/rondel/__init__.py finds it; installed, beside
# the reader in share/rondel/tools/rondel/ (PYTHONPATH=<prefix>/share/rondel/tools).
option(RONDEL_PYTHON "Build the Python driver (rondel._driver)" ON)
if(NOT RONDEL_PYTHON)
  return()
endif()
# The interpreter of the tools, not one found first on PATH (a pyenv shim, say).
set(RONDEL_PYTHON_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The Python the driver is built for")
set(PYTHON_EXECUTABLE ${RONDEL_PYTHON_EXECUTABLE} CACHE FILEPATH "Python (set from RONDEL_PYTHON_EXECUTABLE)" FORCE)
find_package(pybind11 CONFIG QUIET HINTS /usr/lib/python3/dist-packages/pybind11/share/cmake/pybind11)
if(NOT pybind11_FOUND)
  message(STATUS "Rondel: pybind11 not found: no Python driver (apt-get install -y python3-pybind11 python3-dev)")
  return()
endif()
pybind11_add_module(rondel_python MODULE NO_EXTRAS src/app/python/DriverModule.cpp)
set_target_properties(rondel_python PROPERTIES OUTPUT_NAME _driver LIBRARY_OUTPUT_DIRECTORY
                                                                    ${CMAKE_BINARY_DIR}/python/rondel)
target_link_libraries(rondel_python PRIVATE rondel_app)
# Calls between the layers bound inside the module at link time (no PLT): the executable's call costs.
target_link_options(rondel_python PRIVATE -Wl,-Bsymbolic-functions)
install(TARGETS rondel_python LIBRARY DESTINATION ${CMAKE_INSTALL_DATADIR}/rondel/tools/rondel)
set(RONDEL_PYTHON_DIR ${CMAKE_BINARY_DIR}/python)
