# Sanitizer and fuzzing builds. Both instrument every target of the build, so they
# belong in a build directory of their own:
#   cmake -B build-asan -DTOONWATER_SANITIZE=ON                       (GCC or Clang)
#   cmake -B build-fuzz -DTOONWATER_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++-14
# scripts/test.sh runs the test suite in the first and scripts/fuzz.sh the fuzzers of the second.
option(TOONWATER_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(TOONWATER_FUZZ "Build the libFuzzer targets of tests/fuzz (Clang; implies the sanitizers)" OFF)

if(TOONWATER_SANITIZE OR TOONWATER_FUZZ)
  # Undefined behaviour aborts (instead of printing and going on), so a test or fuzzer fails.
  set(TOONWATER_SANITIZER_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=all)
  # -g1: line tables for the reports' stack traces, at a fraction of full debug info's build time.
  add_compile_options(${TOONWATER_SANITIZER_FLAGS} -fno-omit-frame-pointer -g1)
  add_link_options(${TOONWATER_SANITIZER_FLAGS})
  # GCC's manual (Instrumentation Options): the sanitizers raise the rate of false positives,
  # most notably of -Wmaybe-uninitialized (here, all inside libstdc++'s std::regex and OpenMesh).
  # The Release build keeps the warning.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    add_compile_options(-Wno-maybe-uninitialized)
  endif()
endif()

if(TOONWATER_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "TOONWATER_FUZZ needs Clang (libFuzzer): -DCMAKE_CXX_COMPILER=clang++-14")
  endif()
  # Coverage feedback for every library; the fuzz executables add libFuzzer's main.
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
