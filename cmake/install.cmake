# `cmake --install`: the libraries, the `masnet` executable, the public headers (the protocol
# API and what it includes; nothing of the radio's internals, the world or ground truth), the
# scenario files, and a package find_package(masnet 0.2) finds (docs/protocol-api.md).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# One target a program links to get everything, masnet::masnet, in the build tree and installed:
# the protocol API (with its include paths, C++20, Eigen and spdlog) and the command line.
add_library(masnet_all INTERFACE)
add_library(masnet::masnet ALIAS masnet_all)
target_link_libraries(masnet_all INTERFACE masnet_protocols ${MASNET_CLI_LIBRARY})
set_target_properties(masnet_all PROPERTIES EXPORT_NAME masnet)

foreach(target IN LISTS MASNET_INSTALLED_LIBRARIES)
  string(REPLACE "masnet_" "" short_name ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${short_name})
endforeach()

install(TARGETS ${MASNET_INSTALLED_LIBRARIES} masnet_all EXPORT masnetTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} ${CMAKE_INSTALL_INCLUDEDIR}/masnet)
install(TARGETS masnet RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# The public headers: a protocol's interfaces, its hosts and parameters, the registry, the
# geometry and Lloyd helpers it may use, the command line a program hands its arguments to, and
# the headers those include. Installed as <masnet/protocols/registry.hpp>.
set(MASNET_PUBLIC_HEADERS
  sim/assert.hpp sim/event_action.hpp sim/event_queue.hpp sim/fingerprint.hpp sim/free_slots.hpp
  sim/ids.hpp sim/log.hpp sim/random.hpp sim/simulator.hpp sim/time.hpp
  net/messages.hpp net/vec2.hpp
  protocols/density_scaling.hpp protocols/geometry.hpp protocols/heard_cell.hpp
  protocols/host.hpp protocols/lloyd.hpp protocols/protocol.hpp protocols/protocol_params.hpp
  protocols/registry.hpp
  ${MASNET_CLI_HEADER})
foreach(header IN LISTS MASNET_PUBLIC_HEADERS)
  get_filename_component(folder ${header} DIRECTORY)
  install(FILES ${PROJECT_SOURCE_DIR}/${header}
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/masnet/${folder})
endforeach()

install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenarios/paper ${PROJECT_SOURCE_DIR}/scenarios/examples
  ${PROJECT_SOURCE_DIR}/scenarios/sweeps
  DESTINATION ${CMAKE_INSTALL_DATADIR}/masnet/scenarios FILES_MATCHING PATTERN "*.yaml")

set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/masnet)
install(EXPORT masnetTargets NAMESPACE masnet:: DESTINATION ${config_dir})
configure_package_config_file(cmake/masnetConfig.cmake.in
  ${PROJECT_BINARY_DIR}/masnetConfig.cmake INSTALL_DESTINATION ${config_dir}
  PATH_VARS CMAKE_INSTALL_DATADIR)
# 0.x: a minor version may change the API, so 0.2 accepts 0.2.* only.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/masnetConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/masnetConfig.cmake
  ${PROJECT_BINARY_DIR}/masnetConfigVersion.cmake DESTINATION ${config_dir})
