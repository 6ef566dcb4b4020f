# `cmake --install`: libpena as pena::<module> for find_package(pena), its public headers, the
# tools and daemons into bin/, and the DDS profiles and example configs into share/pena/
# (the daemons find share/pena/dds relative to their own binary). Every file belongs to one
# component, the Debian package it goes into (cmake/PenaPackage.cmake): dev (libpena-dev), tools
# (pena-tools), services (pena-services). The system files of pena-services (systemd units,
# /etc/pena) have absolute destinations and install only for the package (component system).
#
# Libraries and lib/cmake/pena go to CMAKE_INSTALL_LIBDIR (GNUInstallDirs). On a multiarch system
# (Debian: the compiler reports CMAKE_LIBRARY_ARCHITECTURE, e.g. x86_64-linux-gnu) its default is
# lib/<multiarch tuple> for every prefix, not only for /usr as GNUInstallDirs would choose: the
# build tree is configured for /usr/local, and CPack installs that same tree under /usr, where
# Debian wants /usr/lib/<tuple>. find_package searches <prefix>/lib/<tuple>/cmake too. A tree
# configured before this rule, with GNUInstallDirs' "lib", moves once; -DCMAKE_INSTALL_LIBDIR=lib
# given afterwards (or on the first configure) is kept.
if(CMAKE_LIBRARY_ARCHITECTURE AND NOT PENA_INSTALL_LIBDIR_CHOSEN)
  if(NOT DEFINED CMAKE_INSTALL_LIBDIR OR
     (CMAKE_INSTALL_LIBDIR STREQUAL "lib" AND DEFINED _GNUInstallDirs_LAST_CMAKE_INSTALL_PREFIX))
    set(CMAKE_INSTALL_LIBDIR lib/${CMAKE_LIBRARY_ARCHITECTURE} CACHE PATH
        "Object code libraries (lib/<multiarch tuple> on a multiarch system)" FORCE)
  endif()
  set(PENA_INSTALL_LIBDIR_CHOSEN ON CACHE INTERNAL "CMAKE_INSTALL_LIBDIR's default was applied")
endif()
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PENA_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/pena)
set(PENA_MODULES common geometry sensors dead_reckoning scan_matching odometry slam localisation line_map
                 grid io eval viz sim pipeline fusion)
list(TRANSFORM PENA_MODULES PREPEND pena_ OUTPUT_VARIABLE pena_module_targets)
install(TARGETS ${pena_module_targets} pena_all pena_proto EXPORT penaTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/libpena/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        COMPONENT dev)
install(EXPORT penaTargets NAMESPACE pena:: DESTINATION ${PENA_INSTALL_CMAKEDIR} COMPONENT dev)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/penaConfig.cmake.in
  ${PROJECT_BINARY_DIR}/penaConfig.cmake INSTALL_DESTINATION ${PENA_INSTALL_CMAKEDIR})
# 0.x: a minor version may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/penaConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/penaConfig.cmake ${PROJECT_BINARY_DIR}/penaConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/PenaOpenCV.cmake
        DESTINATION ${PENA_INSTALL_CMAKEDIR} COMPONENT dev)

# Programs for users. The benchmarks (pena-load, pena-traffic, pena-grid-bandwidth) run from the
# build tree and are not installed.
include(PenaManPages)
if(PENA_BUILD_TOOLS)
  install(TARGETS pena RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tools)
  pena_man_page(pena tools "personal localisation and mapping tools (PeNa)")
endif()
set(pena_daemons)
if(PENA_BUILD_SERVICES)
  list(APPEND pena_daemons pena-entity pena-fusion pena-sensor-replay pena-monitor pena-console
                           pena-link-plot pena-link-gridcost)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/deploy/dds ${PROJECT_SOURCE_DIR}/deploy/config
          DESTINATION ${CMAKE_INSTALL_DATADIR}/pena COMPONENT services)
endif()
if(PENA_BUILD_GATEWAY)
  list(APPEND pena_daemons pena-gateway)
endif()
if(pena_daemons)
  install(TARGETS ${pena_daemons} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT services)
  set(description_pena-entity "the PeNa service of one firefighter or robot")
  set(description_pena-fusion "the central PeNa fusion service")
  set(description_pena-sensor-replay "publish a sensor log on the live sensor topics")
  set(description_pena-monitor "pose age and global-map state at the command post")
  set(description_pena-console "the command post's live view in a browser")
  set(description_pena-link-plot "a chart PNG from a series,x,y CSV")
  set(description_pena-link-gridcost "grid PNG bytes per map update for one entity")
  set(description_pena-gateway "carry alarms, poses, corrections and line maps across a slow link")
  foreach(daemon ${pena_daemons})
    pena_man_page(${daemon} services "${description_${daemon}}")
  endforeach()
endif()

include(PenaPackage)
