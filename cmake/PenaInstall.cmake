# `cmake --install`: libpena as pena::<module> for find_package(pena), its public headers, the
# tools and daemons into bin/, and the DDS profiles and example configs into share/pena/
# (the daemons find share/pena/dds relative to their own binary).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PENA_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/pena)
set(PENA_MODULES geometry sensors dead_reckoning scan_matching odometry slam localisation line_map
                 grid io eval viz sim pipeline fusion)
list(TRANSFORM PENA_MODULES PREPEND pena_ OUTPUT_VARIABLE pena_module_targets)
install(TARGETS ${pena_module_targets} pena_all pena_proto EXPORT penaTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/libpena/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT penaTargets NAMESPACE pena:: DESTINATION ${PENA_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/penaConfig.cmake.in
  ${PROJECT_BINARY_DIR}/penaConfig.cmake INSTALL_DESTINATION ${PENA_INSTALL_CMAKEDIR})
# 0.x: a minor version may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/penaConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/penaConfig.cmake ${PROJECT_BINARY_DIR}/penaConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/PenaOpenCV.cmake
        DESTINATION ${PENA_INSTALL_CMAKEDIR})

# Programs for users. The benchmarks (pena-load, pena-traffic, pena-grid-bandwidth) run from the
# build tree and are not installed.
set(pena_programs)
if(PENA_BUILD_TOOLS)
  list(APPEND pena_programs pena)
endif()
if(PENA_BUILD_SERVICES)
  list(APPEND pena_programs pena-entity pena-fusion pena-sensor-replay pena-monitor pena-console pena-link-plot
                            pena-link-gridcost)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/deploy/dds ${PROJECT_SOURCE_DIR}/deploy/config
          DESTINATION ${CMAKE_INSTALL_DATADIR}/pena)
endif()
if(PENA_BUILD_GATEWAY)
  list(APPEND pena_programs pena-gateway)
endif()
if(pena_programs)
  install(TARGETS ${pena_programs} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
