# cmake -DPROJECT_DIR=... -DWORK_DIR=... -DPENA_CMAKE_DIR=... -DCXX_COMPILER=... -P layering_test.cmake
# Builds tests/layering/project four ways and fails unless each builds or fails as the layering
# says it must.

# run_case(<name> <upper_deps> <app_deps> <expected: "builds" or the header the compiler must miss>)
function(run_case name upper_deps app_deps expected)
  set(dir ${WORK_DIR}/${name})
  file(REMOVE_RECURSE ${dir})
  execute_process(
    COMMAND ${CMAKE_COMMAND} -S ${PROJECT_DIR} -B ${dir} -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
            -DPENA_CMAKE_DIR=${PENA_CMAKE_DIR} -DUPPER_DEPS=${upper_deps} -DAPP_DEPS=${app_deps}
    RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${name}: the project does not configure:\n${output}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${dir}
                  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(expected STREQUAL "builds")
    if(NOT result EQUAL 0)
      message(FATAL_ERROR "${name}: expected to build, but:\n${output}")
    endif()
  else()
    if(result EQUAL 0)
      message(FATAL_ERROR "${name}: built, although it includes ${expected} without linking its "
                          "module: the include roots do not enforce the layering")
    endif()
    # GCC: "x.hpp: No such file or directory"; Clang (the sanitizer build): "'x.hpp' file not found".
    string(FIND "${output}" "${expected}: No such file or directory" at_gcc)
    string(FIND "${output}" "'${expected}' file not found" at_clang)
    if(at_gcc EQUAL -1 AND at_clang EQUAL -1)
      message(FATAL_ERROR "${name}: failed, but not for the missing ${expected}:\n${output}")
    endif()
  endif()
  if(expected STREQUAL "builds")
    message(STATUS "${name}: builds, as expected")
  else()
    message(STATUS "${name}: does not compile without ${expected}, as expected")
  endif()
  file(REMOVE_RECURSE ${dir})
endfunction()

run_case(linked pena::lower pena::lower_internal builds)
run_case(module_without_link "" pena::lower_internal pena/lower/lower.hpp)
run_case(private_header_without_internal pena::lower pena::upper pena/lower/internal/secret.hpp)
