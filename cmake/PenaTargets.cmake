# Helpers that give every PeNa target the same warnings and layout.

# pena_set_warnings(<target>): warnings on for our code; -Werror when PENA_WERROR is set.
function(pena_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wconversion -Wshadow)
  if(PENA_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# pena_add_module(<name> SOURCES ... DEPS ...): a libpena module as pena_<name> with alias pena::<name>.
function(pena_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(pena_${name} STATIC ${ARG_SOURCES})
  add_library(pena::${name} ALIAS pena_${name})
  # Installed as pena::<name> too (cmake/PenaInstall.cmake), headers under <prefix>/include.
  set_target_properties(pena_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(pena_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/libpena/include> $<INSTALL_INTERFACE:include>)
  target_link_libraries(pena_${name} PUBLIC ${ARG_DEPS})
  pena_set_warnings(pena_${name})
endfunction()

# pena_add_test(<name> [SERIAL] SOURCES ... DEPS ...): one GoogleTest executable per area,
# discovered by CTest. SERIAL: its tests run alone (multi-process runs whose outcome depends on
# timing, which a parallel ctest on 2 cores disturbs).
function(pena_add_test name)
  cmake_parse_arguments(ARG "SERIAL" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest_main)
  # tests/common: the temporary directories and data paths every test uses.
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/common)
  target_compile_definitions(${name} PRIVATE
    PENA_DATA_DIR="${PENA_DATA_DIR}"
    PENA_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  pena_set_warnings(${name})
  include(GoogleTest)
  set(properties TIMEOUT 600)
  if(ARG_SERIAL)
    list(APPEND properties RUN_SERIAL TRUE)
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES ${properties})
endfunction()
