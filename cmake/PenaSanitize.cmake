# Sanitizer and fuzzing builds (docs/fuzzing.md). Both apply to every target of the build dir,
# so use a build dir of their own (scripts/sanitizers.sh: build-asan; scripts/fuzz.sh).
#
# PENA_SANITIZE: a -fsanitize= list, e.g. "address,undefined". Any report ends the process with
# a non-zero status (-fno-sanitize-recover=all), so a report fails its test.
# PENA_FUZZ: builds the libFuzzer targets of tests/fuzz (clang only) and instruments every
# target for coverage (-fsanitize=fuzzer-no-link), so the fuzzers see into libpena and the
# gateway. Use it together with PENA_SANITIZE=address,undefined.
set(PENA_SANITIZE "" CACHE STRING "Sanitizers for every target, e.g. address,undefined (empty: none)")
option(PENA_FUZZ "Build the libFuzzer targets of tests/fuzz (clang only)" OFF)

if(PENA_SANITIZE)
  add_compile_options(-fsanitize=${PENA_SANITIZE} -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${PENA_SANITIZE})
endif()

if(PENA_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "PENA_FUZZ needs clang's libFuzzer: configure with -DCMAKE_CXX_COMPILER=clang++ "
                        "(got ${CMAKE_CXX_COMPILER_ID})")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
