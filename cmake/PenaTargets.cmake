# Helpers that give every PeNa target the same warnings and layout.

# pena_set_warnings(<target>): warnings on for our code; -Werror when PENA_WERROR is set.
function(pena_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wconversion -Wshadow)
  if(PENA_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# Where pena_add_module finds a module's headers: <root>/pena/<name>/ (public) and the module's
# own source directory (private). A project that reuses these helpers (tests/layering) sets it.
if(NOT DEFINED PENA_MODULE_INCLUDE_ROOT)
  set(PENA_MODULE_INCLUDE_ROOT ${PROJECT_SOURCE_DIR}/libpena/include)
endif()

# pena_expose(<root> <link> <target>): makes <root>/<link> (a path under a build-tree include
# root) a symbolic link to <target>, so that only what is linked there is reachable from <root>.
function(pena_expose root link target)
  get_filename_component(parent ${root}/${link} DIRECTORY)
  file(MAKE_DIRECTORY ${parent})
  file(CREATE_LINK ${target} ${root}/${link} SYMBOLIC)
endfunction()

# pena_add_module(<name> SOURCES ... DEPS ...): a libpena module as pena_<name> with alias
# pena::<name>. Layering is enforced by the include path: the module's public include root (in
# the build tree) holds pena/<name>/ alone, so a target reaches pena/<other>/... only if it links
# pena::<other> (directly or through a module it links); an include that skips a link fails to
# compile ("pena/<other>/x.hpp: No such file or directory"). Its private headers, in its source
# directory, are reachable as "pena/<name>/internal/x.hpp" only through pena::<name>_internal,
# which the module's own tests link.
function(pena_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(pena_${name} STATIC ${ARG_SOURCES})
  add_library(pena::${name} ALIAS pena_${name})
  # Installed as pena::<name> too (cmake/PenaInstall.cmake), headers under <prefix>/include.
  set_target_properties(pena_${name} PROPERTIES EXPORT_NAME ${name})
  set(public_root ${PROJECT_BINARY_DIR}/pena_include/${name})
  pena_expose(${public_root} pena/${name} ${PENA_MODULE_INCLUDE_ROOT}/pena/${name})
  target_include_directories(pena_${name} PUBLIC
    $<BUILD_INTERFACE:${public_root}> $<INSTALL_INTERFACE:include>)
  target_link_libraries(pena_${name} PUBLIC ${ARG_DEPS})
  pena_set_warnings(pena_${name})

  set(internal_root ${PROJECT_BINARY_DIR}/pena_internal/${name})
  pena_expose(${internal_root} pena/${name}/internal ${CMAKE_CURRENT_SOURCE_DIR})
  add_library(pena_${name}_internal INTERFACE)
  add_library(pena::${name}_internal ALIAS pena_${name}_internal)
  target_include_directories(pena_${name}_internal INTERFACE $<BUILD_INTERFACE:${internal_root}>)
  target_link_libraries(pena_${name}_internal INTERFACE pena_${name})
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
