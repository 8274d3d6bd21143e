# Every reader of bytes a student or a platform controls, fuzzed (tests/fuzz/): a libFuzzer target for each, built
# with AddressSanitizer and UBSan into bin/fuzz-<reader> where a clang with libFuzzer is found (the project's build
# may use another compiler: the targets are a project of their own, tests/fuzz/clang, made in <build>/fuzz), each
# with its seed corpus (tests/fuzz/<reader>/ and the tree's own files of its format, tests/fuzz/seeds.sh) and, where
# the format has one, a dictionary (tests/fuzz/<reader>.dict). `ctest -L fuzz` runs each for a few seconds (the
# smoke, fuzz/<reader>); tests/fuzz/run is the longer campaign, which keeps what it finds.
set(simlab_fuzz_readers
  wire answer book-answers project-toml gradescope-yaml gradescope-json intake roster manual course-toml rubric
  corpus-case record elf similarity study-line)

find_program(SIMLAB_FUZZ_COMPILER NAMES clang++ clang++-14 clang++-15 clang++-16 clang++-17 clang++-18
             DOC "clang++ with libFuzzer, for the fuzz targets")
option(SIMLAB_FUZZ "Build the fuzz targets, bin/fuzz-<reader> (default: ON where clang with libFuzzer is found)" ON)
if(SIMLAB_FUZZ AND SIMLAB_FUZZ_COMPILER AND NOT (SIMLAB_FUZZ_WORKS AND SIMLAB_FUZZ_CHECKED STREQUAL SIMLAB_FUZZ_COMPILER))
  # libFuzzer and the sanitizers' runtimes come with clang's runtime package (Debian's libclang-rt-dev): checked
  # again at each configure until they are there.
  set(probe ${CMAKE_CURRENT_BINARY_DIR}/fuzz-probe)
  file(WRITE ${probe}.cpp "#include <cstddef>\n#include <cstdint>\n"
             "extern \"C\" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }\n")
  execute_process(COMMAND ${SIMLAB_FUZZ_COMPILER} -fsanitize=fuzzer,address,undefined ${probe}.cpp -o ${probe}
                  RESULT_VARIABLE failed OUTPUT_QUIET ERROR_QUIET)
  file(REMOVE ${probe} ${probe}.cpp)
  if(failed)
    set(works OFF)
  else()
    set(works ON)
  endif()
  set(SIMLAB_FUZZ_WORKS ${works} CACHE INTERNAL "clang links -fsanitize=fuzzer,address,undefined")
  set(SIMLAB_FUZZ_CHECKED ${SIMLAB_FUZZ_COMPILER} CACHE INTERNAL "the compiler SIMLAB_FUZZ_WORKS is of")
endif()

if(NOT SIMLAB_FUZZ)
  message(STATUS "Fuzz targets: off (SIMLAB_FUZZ=OFF)")
elseif(NOT SIMLAB_FUZZ_COMPILER OR NOT SIMLAB_FUZZ_WORKS)
  message(STATUS "Fuzz targets: not built (no clang++ that links -fsanitize=fuzzer; scripts/install-deps installs "
                 "clang and its runtimes, libclang-rt-dev)")
else()
  message(STATUS "Fuzz targets: bin/fuzz-<reader>, by ${SIMLAB_FUZZ_COMPILER}")
  include(ExternalProject)
  set(fuzz_programs "")
  foreach(reader IN LISTS simlab_fuzz_readers)
    list(APPEND fuzz_programs ${CMAKE_RUNTIME_OUTPUT_DIRECTORY}/fuzz-${reader})
  endforeach()
  string(REPLACE ";" "|" fuzz_reader_list "${simlab_fuzz_readers}")
  set(fuzz_ccache "")
  if(SIMLAB_CCACHE AND SIMLAB_CCACHE_PROGRAM)
    set(fuzz_ccache -DSIMLAB_CCACHE_PROGRAM=${SIMLAB_CCACHE_PROGRAM} -DSIMLAB_CCACHE_DIR=${PROJECT_BINARY_DIR}/ccache)
  endif()
  # Built with everything else; its own build decides what changed (a reader's source, a target's).
  ExternalProject_Add(simlab_fuzz_targets
    SOURCE_DIR ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/clang
    BINARY_DIR ${PROJECT_BINARY_DIR}/fuzz
    LIST_SEPARATOR |
    CMAKE_ARGS -DCMAKE_CXX_COMPILER=${SIMLAB_FUZZ_COMPILER} -DCMAKE_BUILD_TYPE= -DSIMLAB_SOURCE_DIR=${PROJECT_SOURCE_DIR}
               -DSIMLAB_OUTPUT_DIR=${CMAKE_RUNTIME_OUTPUT_DIRECTORY} -DSIMLAB_FUZZ_READERS=${fuzz_reader_list}
               ${fuzz_ccache}
    BUILD_ALWAYS TRUE
    BUILD_BYPRODUCTS ${fuzz_programs}
    INSTALL_COMMAND "")
  foreach(reader IN LISTS simlab_fuzz_readers)
    add_test(NAME fuzz/${reader} COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/fuzz/smoke ${reader})
    set_tests_properties(fuzz/${reader} PROPERTIES ENVIRONMENT "${script_env}" LABELS fuzz)
  endforeach()
endif()
