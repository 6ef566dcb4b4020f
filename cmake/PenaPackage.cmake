# Debian packages with CPack (docs/deploy.md): `cpack -G DEB` in the build tree, or
# scripts/package.sh. One package per group of install components (cmake/PenaInstall.cmake):
#   libpena-dev    dev:      static libraries, public headers, the CMake package (find_package(pena))
#   pena-tools     tools:    the pena command-line tool
#   pena-services  services: the daemons and their DDS tools, share/pena; system: the systemd
#                            units, /etc/pena (conffiles), the maintainer scripts (system user)
# Each package also gets its copyright and changelog (component <group>_debian). The system
# and *_debian components are EXCLUDE_FROM_ALL: `cmake --install` into a prefix never writes
# /etc or /lib/systemd.
#
# The Maintainer field (and the changelog's signature) is PENA_PACKAGE_MAINTAINER. The source tree
# names its authors ("the PeNa authors", deploy/debian/copyright) but no address, so the default
# is a placeholder under the reserved .invalid domain (RFC 2606: no mail can reach it): whoever
# distributes the packages sets their own, -DPENA_PACKAGE_MAINTAINER="Name <address>".
set(pena_placeholder_maintainer "PeNa authors <maintainer@pena.invalid>")
set(PENA_PACKAGE_MAINTAINER "${pena_placeholder_maintainer}" CACHE STRING
    "Maintainer field of the Debian packages: \"Name <address>\" of whoever distributes them")
if(PENA_PACKAGE_MAINTAINER STREQUAL pena_placeholder_maintainer)
  message(STATUS "Debian packages: Maintainer is the placeholder ${PENA_PACKAGE_MAINTAINER}; "
                 "set -DPENA_PACKAGE_MAINTAINER=\"Name <address>\" to distribute them")
elseif(NOT PENA_PACKAGE_MAINTAINER MATCHES "^[^<>]+ <[^<>@ ]+@[^<>@ ]+>$")
  message(FATAL_ERROR "PENA_PACKAGE_MAINTAINER must be \"Name <address>\", got "
                      "'${PENA_PACKAGE_MAINTAINER}'")
endif()

set(pena_deb_dir ${PROJECT_BINARY_DIR}/debian)
set(pena_deb_src ${PROJECT_SOURCE_DIR}/deploy/debian)

# Per package: /usr/share/doc/<package>/copyright and changelog.gz (a native package's).
string(TIMESTAMP pena_changelog_date "%a, %d %b %Y %H:%M:%S +0000" UTC)
function(pena_package_docs group package)
  set(dir ${pena_deb_dir}/${package})
  file(MAKE_DIRECTORY ${dir})
  file(WRITE ${dir}/changelog
       "${package} (${PROJECT_VERSION}) unstable; urgency=medium\n\n"
       "  * Built from the PeNa source tree with CPack (docs/deploy.md).\n\n"
       " -- ${PENA_PACKAGE_MAINTAINER}  ${pena_changelog_date}\n")
  execute_process(COMMAND gzip -9nf ${dir}/changelog RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "gzip ${dir}/changelog failed")
  endif()
  install(FILES ${pena_deb_src}/copyright ${dir}/changelog.gz
          DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/${package}
          COMPONENT ${group}_debian EXCLUDE_FROM_ALL)
  list(APPEND CPACK_COMPONENTS_ALL ${group} ${group}_debian)
  string(TOUPPER ${group} upper)
  set(CPACK_COMPONENT_${upper}_GROUP ${group} PARENT_SCOPE)
  set(CPACK_COMPONENT_${upper}_DEBIAN_GROUP ${group} PARENT_SCOPE)
  set(CPACK_DEBIAN_${upper}_PACKAGE_NAME ${package} PARENT_SCOPE)
  set(CPACK_COMPONENTS_ALL ${CPACK_COMPONENTS_ALL} PARENT_SCOPE)
endfunction()

set(CPACK_COMPONENTS_ALL)
pena_package_docs(dev libpena-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
    "libeigen3-dev (>= 3.4), libopencv-core-dev, libopencv-imgproc-dev, libopencv-imgcodecs-dev, libprotobuf-dev, zlib1g-dev, libnanoflann-dev")
set(CPACK_DEBIAN_DEV_PACKAGE_SUGGESTS "cmake")
set(CPACK_DEBIAN_DEV_DESCRIPTION
"PeNa localisation and mapping library (development files)
libpena holds the algorithms of PeNa, personal localisation and mapping
for search-and-rescue teams of people and robots: dead reckoning, laser
scan matching and odometry, occupancy grids, line maps, localisation on
a priori plans, map fusion, evaluation and simulation.
.
This package holds the static libraries, the public headers and the
CMake package: find_package(pena) gives pena::odometry, pena::io and the
other modules.")

if(PENA_BUILD_TOOLS)
  pena_package_docs(tools pena-tools)
  set(CPACK_DEBIAN_TOOLS_PACKAGE_SECTION science)
  set(CPACK_DEBIAN_TOOLS_DESCRIPTION
"PeNa command-line tool
pena simulates missions with ground truth, runs dead reckoning, laser
odometry, mapping and localisation on mission logs and CARMEN logs,
evaluates trajectories and maps, and writes the team demo's report.")
endif()

if(PENA_BUILD_SERVICES)
  pena_package_docs(services pena-services)
  list(APPEND CPACK_COMPONENTS_ALL system)
  set(CPACK_COMPONENT_SYSTEM_GROUP services)
  set(CPACK_DEBIAN_SERVICES_PACKAGE_SECTION net)
  set(CPACK_DEBIAN_SERVICES_PACKAGE_DEPENDS "adduser")
  set(CPACK_DEBIAN_SERVICES_PACKAGE_SUGGESTS "pena-tools")
  set(CPACK_DEBIAN_SERVICES_DESCRIPTION
"PeNa services: per-entity localisation, map fusion, gateway, console
The PeNa daemons under systemd: pena-entity@<id> (one per firefighter or
robot), pena-fusion (the central global map and its corrections),
pena-gateway (the slow radio link to the command post) and pena-console
(the operator's live view in a browser), with their DDS tools
(pena-sensor-replay, pena-monitor).
.
Configuration is in /etc/pena. The shipped DDS profile keeps every
participant on the loopback interface until the deployment's network
profile replaces it.")

  # The units, /etc/pena and the DDS profiles the configs name (identical to deploy/dds).
  set(pena_units pena-entity@.service pena-fusion.service pena-gateway.service pena-console.service)
  list(TRANSFORM pena_units PREPEND ${PROJECT_SOURCE_DIR}/deploy/systemd/)
  install(FILES ${pena_units} DESTINATION /lib/systemd/system COMPONENT system EXCLUDE_FROM_ALL)
  set(pena_etc ${PROJECT_SOURCE_DIR}/deploy/etc/pena)
  install(FILES ${pena_etc}/fusion.conf ${pena_etc}/gateway.env ${pena_etc}/console.env
          DESTINATION /etc/pena COMPONENT system EXCLUDE_FROM_ALL)
  install(FILES ${pena_etc}/entity/example.conf DESTINATION /etc/pena/entity
          COMPONENT system EXCLUDE_FROM_ALL)
  install(FILES ${PROJECT_SOURCE_DIR}/deploy/dds/pena-loopback.xml
                ${PROJECT_SOURCE_DIR}/deploy/dds/pena-qos.xml
          DESTINATION /etc/pena/dds COMPONENT system EXCLUDE_FROM_ALL)
  file(WRITE ${pena_deb_dir}/pena-services/conffiles
       "/etc/pena/console.env\n/etc/pena/dds/pena-loopback.xml\n/etc/pena/dds/pena-qos.xml\n"
       "/etc/pena/entity/example.conf\n/etc/pena/fusion.conf\n/etc/pena/gateway.env\n")
  # dpkg knows the maintainer scripts by their plain names.
  foreach(script postinst prerm postrm)
    configure_file(${pena_deb_src}/pena-services.${script} ${pena_deb_dir}/pena-services/${script} COPYONLY)
  endforeach()
  set(CPACK_DEBIAN_SERVICES_PACKAGE_CONTROL_EXTRA ${pena_deb_dir}/pena-services/conffiles
      ${pena_deb_dir}/pena-services/postinst ${pena_deb_dir}/pena-services/prerm
      ${pena_deb_dir}/pena-services/postrm)
endif()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME pena)
set(CPACK_PACKAGE_VENDOR PeNa)
set(CPACK_PACKAGE_CONTACT "${PENA_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ONE_PER_GROUP)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_COMPRESSION_TYPE xz)
# Maintainer scripts 0755, conffiles 0644, whatever their mode in the tree.
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
