# Parser fuzzing (tests/fuzz/README.md).
#  - Always: pm_fuzz_replay_<target> runs every committed corpus input (crash reproducers
#    included) through the fuzz target once, as the ctest fuzz_corpus_<target>.
#  - With -DPMRENDER_FUZZ=ON and clang: the libFuzzer targets pm_fuzz_<target>, with the
#    parsers (pm_core) built with AddressSanitizer and coverage.
#    tests/fuzz/run.sh configures such a build in build-fuzz/ and runs them for a bounded time.
set(PM_FUZZ_DIR ${CMAKE_CURRENT_LIST_DIR})
set(PM_FUZZ_TARGETS scene frame_spec gltf exr checkpoint texture)

foreach(target ${PM_FUZZ_TARGETS})
  add_executable(pm_fuzz_replay_${target} ${PM_FUZZ_DIR}/${target}_fuzzer.cpp ${PM_FUZZ_DIR}/replay_main.cpp)
  target_link_libraries(pm_fuzz_replay_${target} PRIVATE pm_core)
  target_compile_options(pm_fuzz_replay_${target} PRIVATE -Wall -Wextra -Wno-unused-parameter)
  add_test(NAME fuzz_corpus_${target} COMMAND pm_fuzz_replay_${target} ${PM_FUZZ_DIR}/corpus/${target})
endforeach()

option(PMRENDER_FUZZ "Build the libFuzzer targets (clang only)" OFF)
if(PMRENDER_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "PMRENDER_FUZZ=ON needs clang++ (-DCMAKE_CXX_COMPILER=clang++), got ${CMAKE_CXX_COMPILER_ID}")
  endif()
  target_compile_options(pm_core PRIVATE $<$<COMPILE_LANGUAGE:CXX>:-fsanitize=address,fuzzer-no-link -g>)
  target_link_options(pm_core INTERFACE -fsanitize=address)
  foreach(target ${PM_FUZZ_TARGETS})
    add_executable(pm_fuzz_${target} ${PM_FUZZ_DIR}/${target}_fuzzer.cpp)
    target_link_libraries(pm_fuzz_${target} PRIVATE pm_core)
    target_compile_options(pm_fuzz_${target} PRIVATE -fsanitize=address,fuzzer -g)
    target_link_options(pm_fuzz_${target} PRIVATE -fsanitize=address,fuzzer)
  endforeach()
endif()
