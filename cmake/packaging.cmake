# Install rules and the .deb (included by the top-level CMakeLists.txt once every target exists).
include(CMakePackageConfigHelpers)

# The programs.
install(TARGETS netmc netmc-server netmc-axis netmc-drive-emulator RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  COMPONENT runtime)

# The pure libraries and their headers: a project that links netmc::control needs Eigen, and
# neither Fast DDS nor protobuf.
foreach(library control plant netsim random)
  set_target_properties(netmc_${library} PROPERTIES EXPORT_NAME ${library})
endforeach()
install(TARGETS netmc_control netmc_plant netmc_netsim netmc_random EXPORT netmcTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
# A component plugin (control/plugin/component_plugin.hpp) is a shared object that may link these
# archives: they are built position-independent (without semantic interposition, so the programs
# that link them lose no inlining), and netmc::control tells an installed plugin the version it
# is built against (NETMC_VERSION, checked when netmc loads the plugin).
set_target_properties(netmc_control netmc_plant netmc_netsim PROPERTIES POSITION_INDEPENDENT_CODE ON)
foreach(library control plant netsim)
  target_compile_options(netmc_${library} PRIVATE $<$<CXX_COMPILER_ID:GNU,Clang>:-fno-semantic-interposition>)
endforeach()
target_compile_definitions(netmc_control INTERFACE $<INSTALL_INTERFACE:NETMC_VERSION="${PROJECT_VERSION}">)
foreach(dir control plant netsim)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/netmc/${dir}
    COMPONENT dev FILES_MATCHING PATTERN "*.hpp")
endforeach()
# The drive plugin ABI (a C header, no code): netmc::drive_plugin gives <netmc/drive_plugin.h>
# to a lab's plugin; the example plugin is its starting point.
set_target_properties(netmc_drive_plugin_abi PROPERTIES EXPORT_NAME drive_plugin)
install(TARGETS netmc_drive_plugin_abi EXPORT netmcTargets COMPONENT dev)
install(FILES ${PROJECT_SOURCE_DIR}/server/drive/include/netmc/drive_plugin.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/netmc COMPONENT dev)
install(FILES ${PROJECT_SOURCE_DIR}/examples/drive_plugin/CMakeLists.txt
  ${PROJECT_SOURCE_DIR}/examples/drive_plugin/example_drive.c ${PROJECT_SOURCE_DIR}/examples/drive_plugin/README.md
  DESTINATION ${CMAKE_INSTALL_DATADIR}/netmc/examples/drive_plugin COMPONENT dev)
# The example component plugin: a PD axis loop and paper 001's servo axis in C++, built out of
# tree with find_package(netmc).
install(FILES ${PROJECT_SOURCE_DIR}/examples/controller_plugin/CMakeLists.txt
  ${PROJECT_SOURCE_DIR}/examples/controller_plugin/example_controller.cpp
  ${PROJECT_SOURCE_DIR}/examples/controller_plugin/README.md
  DESTINATION ${CMAKE_INSTALL_DATADIR}/netmc/examples/controller_plugin COMPONENT dev)
# The example FMU plant (built by examples/fmu_axis), with its source and README: netmc runs it
# with no development package, so it goes with the programs.
install(FILES ${PROJECT_BINARY_DIR}/examples/fmu_axis/ball_screw_axis.fmu
  ${PROJECT_SOURCE_DIR}/examples/fmu_axis/ball_screw_axis.c ${PROJECT_SOURCE_DIR}/examples/fmu_axis/README.md
  DESTINATION ${CMAKE_INSTALL_DATADIR}/netmc/examples/fmu_axis COMPONENT runtime)
set(NETMC_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/netmc)
install(EXPORT netmcTargets NAMESPACE netmc:: DESTINATION ${NETMC_CMAKE_DIR} COMPONENT dev)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/netmcConfig.cmake.in
  ${PROJECT_BINARY_DIR}/netmcConfig.cmake INSTALL_DESTINATION ${NETMC_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/netmcConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/netmcConfig.cmake ${PROJECT_BINARY_DIR}/netmcConfigVersion.cmake
  DESTINATION ${NETMC_CMAKE_DIR} COMPONENT dev)

# systemd units (their ExecStart names the installed programs) and what an operator starts from.
# Written at install time: the prefix (cmake --install --prefix, or /usr in the .deb) is known
# only then.
foreach(unit netmc-server.service netmc-axis@.service)
  install(CODE "
    set(NETMC_BINDIR \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}\")
    set(NETMC_DOCDIR \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DOCDIR}\")
    set(NETMC_EXAMPLES \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_DATADIR}/netmc/examples/etc-netmc\")
    configure_file(\"${PROJECT_SOURCE_DIR}/server/systemd/${unit}.in\"
      \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/lib/systemd/system/${unit}\" @ONLY)
    message(STATUS \"Installing: \$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/lib/systemd/system/${unit}\")"
    COMPONENT runtime)
endforeach()
install(FILES ${PROJECT_SOURCE_DIR}/server/systemd/server.env ${PROJECT_SOURCE_DIR}/server/systemd/axis.env
  DESTINATION ${CMAKE_INSTALL_DATADIR}/netmc/examples/etc-netmc COMPONENT runtime)
# Drop-ins that hand root-owned keys to the units' dynamic users as credentials.
install(FILES ${PROJECT_SOURCE_DIR}/server/systemd/security-axis.conf
  DESTINATION ${CMAKE_INSTALL_DATADIR}/netmc/examples/systemd/netmc-axis@.service.d RENAME security.conf
  COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/server/systemd/security-server.conf
  DESTINATION ${CMAKE_INSTALL_DATADIR}/netmc/examples/systemd/netmc-server.service.d RENAME security.conf
  COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/server/systemd/admin-token-server.conf
  DESTINATION ${CMAKE_INSTALL_DATADIR}/netmc/examples/systemd/netmc-server.service.d RENAME admin-token.conf
  COMPONENT runtime)
# Example job specs, one per preset, written by the program itself at build time.
set(NETMC_EXAMPLE_SPECS ${PROJECT_BINARY_DIR}/example-specs)
add_custom_command(OUTPUT ${NETMC_EXAMPLE_SPECS}/seed001.json
  COMMAND ${CMAKE_COMMAND} -DNETMC=$<TARGET_FILE:netmc> -DOUT=${NETMC_EXAMPLE_SPECS}
          -P ${PROJECT_SOURCE_DIR}/cmake/write_example_specs.cmake
  DEPENDS netmc ${PROJECT_SOURCE_DIR}/cmake/write_example_specs.cmake
  COMMENT "netmc sim --preset NAME --print-spec, for every preset")
add_custom_target(netmc_example_specs ALL DEPENDS ${NETMC_EXAMPLE_SPECS}/seed001.json)
install(DIRECTORY ${NETMC_EXAMPLE_SPECS}/ DESTINATION ${CMAKE_INSTALL_DATADIR}/netmc/examples/specs COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/server/dds/profiles/udp_only.xml
  DESTINATION ${CMAKE_INSTALL_DATADIR}/netmc/examples/dds-profiles COMPONENT runtime)
# The default Modbus register map: what a drive's own map file starts from.
install(FILES ${PROJECT_SOURCE_DIR}/server/drive/modbus/default-map.json
  DESTINATION ${CMAKE_INSTALL_DATADIR}/netmc/examples/drive-maps COMPONENT runtime)
install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/make-lab-pki.sh DESTINATION ${CMAKE_INSTALL_DATADIR}/netmc COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR}
  COMPONENT runtime)

# Three .debs: `cpack -G DEB` in the build directory. netmc (the programs, units, examples): its
# dependencies are the Debian runtime packages of the programs' shared libraries, found by
# dpkg-shlibdeps. netmc-dev (the pure libraries, headers, CMake package): needs Eigen's headers.
# python3-netmc (the Python package, with NETMC_PYTHON): Debian's python3, numpy and pandas.
set(CPACK_GENERATOR DEB)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime dev)
if(NETMC_PYTHON)
  # python3-netmc: the Python package (python/) in Debian's dist-packages, for Debian's python3.
  list(APPEND CPACK_COMPONENTS_ALL python)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-netmc)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS "python3 (>= 3.11), python3 (<< 3.12), python3-numpy, python3-pandas")
  set(CPACK_DEBIAN_PYTHON_PACKAGE_SUGGESTS "python3-distributed, python3-matplotlib")
  set(CPACK_COMPONENT_PYTHON_DESCRIPTION "netmc's studies from Python: import netmc (sim, sweep, Dask sweeps)")
endif()
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME netmc)
set(CPACK_DEBIAN_DEV_PACKAGE_NAME netmc-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "libeigen3-dev (>= 3.4)")
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_COMPONENT_DEV_DESCRIPTION "netmc's pure libraries (control, plant, netsim) and drive plugin ABI for find_package(netmc)")
set(CPACK_PACKAGE_NAME netmc)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Networked motion control over DDS: server, axis nodes, client and libraries")
set(CPACK_PACKAGE_CONTACT "netmc <netmc@localhost>")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# gnuplot draws `--plot` figures; dygraphs draws the console's plots (netmc-server --http).
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS "gnuplot-nox, libjs-dygraphs")
set(CPACK_STRIP_FILES ON)
include(CPack)
