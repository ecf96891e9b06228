# `cmake --install build --prefix P`: the executables in P/bin, the libraries and headers with an exported
# package configuration (P/lib/cmake/Rondel, for find_package(Rondel)), the Python tools and the scenes in
# P/share/rondel, the documentation in P/share/doc/rondel.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(RONDEL_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/Rondel)
set(RONDEL_INSTALL_DOCDIR ${CMAKE_INSTALL_DATAROOTDIR}/doc/rondel)
install(TARGETS rondel rondel_bench rondel_bench_io RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS rondel_core rondel_physics rondel_parallel rondel_app EXPORT RondelTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
# The headers keep their layout under src/ (#include "core/Config.hpp"), one directory down so that core/
# and app/ do not collide with other packages' headers.
install(DIRECTORY src/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rondel FILES_MATCHING PATTERN "*.hpp")
install(EXPORT RondelTargets NAMESPACE Rondel:: DESTINATION ${RONDEL_INSTALL_CMAKEDIR})
configure_package_config_file(cmake/RondelConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/RondelConfig.cmake
                              INSTALL_DESTINATION ${RONDEL_INSTALL_CMAKEDIR})
# 0.x: a minor version may change the interface.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/RondelConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/RondelConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/RondelConfigVersion.cmake
              cmake/FindMETIS.cmake DESTINATION ${RONDEL_INSTALL_CMAKEDIR})

# The tools keep their layout (and execute bits), so that they still import each other; the scripts that
# set up, build and test a checkout stay in the checkout.
install(DIRECTORY tools/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rondel/tools USE_SOURCE_PERMISSIONS
        PATTERN "__pycache__" EXCLUDE PATTERN "setup.sh" EXCLUDE PATTERN "run_default.sh" EXCLUDE
        PATTERN "run_tests.sh" EXCLUDE PATTERN "check_format.sh" EXCLUDE)
install(DIRECTORY inputs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rondel/inputs)
install(FILES README.md FORMAT.md DESTINATION ${RONDEL_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${RONDEL_INSTALL_DOCDIR})
