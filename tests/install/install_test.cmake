# Install.ExternalProjectRunsLaserOdometry (cmake -P): installs this build into a fresh prefix,
# configures and builds tests/install/consumer against it with find_package(pena), and runs it on
# the first 200 scans of LOG. Everything happens in one mktemp directory, removed at the end.
# -DBUILD_DIR=... -DCONSUMER_DIR=... -DLOG=... -DLIBDIR=<CMAKE_INSTALL_LIBDIR of the build, e.g.
# lib/x86_64-linux-gnu> [-DCXX_COMPILER=...] [-DEXPECT_TOOLS=ON]
# [-DEXPECT_SERVICES=ON] (check that bin/pena, the daemons and share/pena were installed too)
if(NOT LIBDIR)
  message(FATAL_ERROR "-DLIBDIR=<the build's CMAKE_INSTALL_LIBDIR> is required")
endif()
execute_process(COMMAND mktemp -d -t pena-install-test.XXXXXX
                OUTPUT_VARIABLE work OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "mktemp failed")
endif()

# step(<what> <command...>): runs the command; on failure removes the work dir and fails.
function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    file(REMOVE_RECURSE "${work}")
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}")
  endif()
  message(STATUS "${what}: ok")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

step("install" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${work}/prefix")
set(expected ${LIBDIR}/cmake/pena/penaConfig.cmake ${LIBDIR}/cmake/pena/penaConfigVersion.cmake
             ${LIBDIR}/libpena_odometry.a include/pena/odometry/laser_odometry.hpp)
if(EXPECT_TOOLS)
  list(APPEND expected bin/pena)
endif()
if(EXPECT_SERVICES)
  list(APPEND expected bin/pena-entity bin/pena-fusion share/pena/dds/pena-loopback.xml
                       share/pena/dds/pena-qos.xml share/pena/config/entity.conf)
endif()
foreach(file ${expected})
  if(NOT EXISTS "${work}/prefix/${file}")
    file(REMOVE_RECURSE "${work}")
    message(FATAL_ERROR "not installed: ${file}")
  endif()
endforeach()
set(compiler)
if(CXX_COMPILER)
  set(compiler "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
endif()
step("configure the consumer" ${CMAKE_COMMAND} -S "${CONSUMER_DIR}" -B "${work}/consumer"
     "-DCMAKE_PREFIX_PATH=${work}/prefix" -DCMAKE_BUILD_TYPE=Release ${compiler})
step("build the consumer" ${CMAKE_COMMAND} --build "${work}/consumer")
step("run the consumer" "${work}/consumer/odometry_on_log" "${LOG}" 200)
message(STATUS "${step_output}")
file(REMOVE_RECURSE "${work}")
