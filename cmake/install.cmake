# `cmake --install build [--prefix P]` and the .deb (`cpack -G DEB` in build/): the CLI, the
# Python module, the scenarios and the docs, in GNUInstallDirs places, one component each:
#   cli      bin/shudder (and bin/shudder-mpi, `sweep --mpi`)
#   python   lib/python3/dist-packages/shudder.*.so  (Debian's path for the system python3;
#            -DSHUDDER_INSTALL_PYTHONDIR=... for another)
#   data     share/shudder/scenarios/  (the scenario files and fluids, as in the source tree)
#   docs     share/doc/shudder/  (README.md and docs/)
#   (fmu)    share/shudder/fmu/shudder_clutch.fmu, installed by fmu/CMakeLists.txt (docs/fmu.md)
include(GNUInstallDirs)
set(SHUDDER_INSTALL_PYTHONDIR "lib/python3/dist-packages" CACHE STRING
    "Where the Python module is installed, relative to the prefix")

install(TARGETS shudder RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT cli)
if(SHUDDER_MPI)
  # `shudder sweep --mpi` runs the shudder-mpi beside shudder (app/mpi_sweep.hpp): same directory.
  install(TARGETS shudder-mpi RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT cli)
endif()
if(SHUDDER_PYTHON)
  install(TARGETS shudder_python LIBRARY DESTINATION ${SHUDDER_INSTALL_PYTHONDIR} COMPONENT python)
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenarios/ DESTINATION ${CMAKE_INSTALL_DATADIR}/shudder/scenarios
        COMPONENT data)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT docs)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT docs)

# The .deb: one package with every component. Depends are the Debian 12 runtime packages of
# the libraries shudder links (named by hand: dpkg-shlibdeps needs dpkg-dev, not a dependency).
set(CPACK_PACKAGE_NAME shudder)
set(CPACK_PACKAGE_VENDOR "shudder")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Stick-slip and shudder in wet-clutch drivetrains: simulator, Python module")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "shudder maintainers <shudder@localhost>")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(shudder_deb_depends "libc6, libstdc++6, libhdf5-103-1, libfftw3-double3")
if(SHUDDER_MPI)
  string(APPEND shudder_deb_depends ", libopenmpi3, openmpi-bin")
endif()
if(SHUDDER_PYTHON)
  string(APPEND shudder_deb_depends ", python3, python3-numpy")
endif()
set(CPACK_DEBIAN_PACKAGE_DEPENDS "${shudder_deb_depends}")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "gnuplot-nox, python3-h5py, python3-matplotlib")
include(CPack)

if(BUILD_TESTING)
  # Installs into a scratch prefix and runs what was installed (tests/install/check_install.sh).
  add_test(NAME install_prefix
           COMMAND bash ${PROJECT_SOURCE_DIR}/tests/install/check_install.sh ${CMAKE_BINARY_DIR}
                   ${CMAKE_CURRENT_BINARY_DIR}/install_test ${SHUDDER_INSTALL_PYTHONDIR})
  set_tests_properties(install_prefix PROPERTIES TIMEOUT 120)
  add_test(NAME deb_package
           COMMAND bash ${PROJECT_SOURCE_DIR}/tests/install/check_deb.sh ${CMAKE_BINARY_DIR}
                   ${CMAKE_CURRENT_BINARY_DIR}/deb_test)
  set_tests_properties(deb_package PROPERTIES TIMEOUT 120)
  add_test(NAME version_fallback
           COMMAND bash ${PROJECT_SOURCE_DIR}/tests/install/check_version_fallback.sh ${PROJECT_SOURCE_DIR}
                   ${CMAKE_CURRENT_BINARY_DIR}/version_test ${PROJECT_VERSION})
endif()
