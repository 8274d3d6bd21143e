# How simlab builds student code, and how an assignment is declared.
#
# Student files are compiled by one command line, whatever builds them: the lab programs (`apple`, ...) built
# here by CMake, and the probes that `simlab check` and `simlab grade` link on the fly. That command line lives
# in SIMLAB_SUBMISSION_COMMAND below and is written to the build manifest (simlab-build.json) for the engine, so
# the precompiled Simbody header always matches the flags it is used with. To it each assignment adds one include
# folder, its contract: the assignment's header and the support headers a student may include, copied into the
# build tree. A student file sees nothing else of the course - no tests, rubric, solution or build tree.

# SIMLAB_SOURCE_DIR is the course's tree (its support headers, its starter/ and solutions/): this project's, or an
# installed simlab's copy of it where a lab is built out of the tree (simlabConfig.cmake).
if(NOT SIMLAB_SOURCE_DIR)
  set(SIMLAB_SOURCE_DIR ${PROJECT_SOURCE_DIR})
endif()
set(SIMLAB_CMAKE_DIR ${CMAKE_CURRENT_LIST_DIR})
set(SIMLAB_PCH_DIR ${PROJECT_BINARY_DIR}/pch)
set(SIMLAB_PCH_HEADER ${SIMLAB_PCH_DIR}/simlab_pch.h)
set(SIMLAB_MANIFEST ${PROJECT_BINARY_DIR}/simlab-build.json)
include(${CMAKE_CURRENT_LIST_DIR}/SimlabJson.cmake)
# The manifest's paths of targets' files and objects are known only at generation, and are written as they are.
if(PROJECT_BINARY_DIR MATCHES "[\"\\\\]")
  message(FATAL_ERROR "simlab: the build folder's path may not hold a quote or a backslash: ${PROJECT_BINARY_DIR}")
endif()
set(SIMLAB_SAMPLE_CLASS_DIR ${PROJECT_BINARY_DIR}/sample-class)

# The compiler of student files, chosen by measurement (bench/self_check.cpp prints the figures): clang++ with a
# precompiled header whose templates are instantiated once, in the header (-fpch-instantiate-templates), compiles a
# lab's file in about 0.15 s at -O0, where GCC spends 1.65 s loading its 202 MB header before the file's first line.
# The physics runs inside Simbody's optimized libraries, so -O0 costs the tests little. GCC is the fallback
# (SIMLAB_STUDENT_COMPILER=gcc, or no clang++): the same tests and scores, slower feedback. Whichever it is, the
# lab programs a student builds compile their file with the same command as the grader, with the same warnings.
set(SIMLAB_STUDENT_COMPILER "auto" CACHE STRING "Compiler of student files: auto (clang++ where found), clang or gcc")
set_property(CACHE SIMLAB_STUDENT_COMPILER PROPERTY STRINGS auto clang gcc)
find_program(SIMLAB_CLANGXX NAMES clang++-14 clang++)
if(SIMLAB_STUDENT_COMPILER STREQUAL "clang" AND NOT SIMLAB_CLANGXX)
  message(FATAL_ERROR "SIMLAB_STUDENT_COMPILER=clang, but no clang++ was found (scripts/install-deps installs it)")
endif()
if(SIMLAB_CLANGXX AND NOT SIMLAB_STUDENT_COMPILER STREQUAL "gcc")
  set(SIMLAB_STUDENT_CXX ${SIMLAB_CLANGXX})
  set(SIMLAB_STUDENT_CXX_ID Clang)
  set(optimization -O0)
else()
  set(SIMLAB_STUDENT_CXX ${CMAKE_CXX_COMPILER})
  set(SIMLAB_STUDENT_CXX_ID GNU)
  set(optimization -O1)  # GCC's compile time hardly changes with the level; its code at -O1 runs faster
endif()
# The linker of probes and lab programs: lld where found (0.16 s a probe against GNU ld's 0.5 s).
find_program(SIMLAB_LLD NAMES ld.lld-14 ld.lld)
set(SIMLAB_LINKER_FLAGS "")
if(SIMLAB_LLD)
  set(SIMLAB_LINKER_FLAGS -fuse-ld=lld)
  add_link_options(${SIMLAB_LINKER_FLAGS})  # simlab's own programs too
endif()
if(SIMLAB_LLD)
  message(STATUS "simlab: student files compiled by ${SIMLAB_STUDENT_CXX} (${optimization}), linked by ${SIMLAB_LLD}")
else()
  message(STATUS "simlab: student files compiled by ${SIMLAB_STUDENT_CXX} (${optimization}), linked by ${CMAKE_LINKER}")
endif()

# Flags for student code. A function that falls off its end without returning a value is an error, not a crash
# waiting to happen. Student code is compiled with hidden visibility: what it defines stays inside the program and
# cannot take the place of a shared library's function (simlab checks that nothing it defines is exported in one's
# stead). It is position-independent as a shared object's code must be: a probe is one, which the probe's host
# loads as the test's own user (a thread_local would not link there otherwise).
set(SIMLAB_SUBMISSION_FLAGS
    -std=c++17 ${optimization} -g0 -fPIC -pthread -fvisibility=hidden -fvisibility-inlines-hidden
    -Wall -Wextra -Wno-unused-parameter -Wno-deprecated-declarations -Werror=return-type)
if(SIMLAB_STUDENT_CXX_ID STREQUAL "GNU")
  list(APPEND SIMLAB_SUBMISSION_FLAGS -Winvalid-pch)
else()
  # A starter's event handler keeps the members its TODOs will use: not a warning, as with GCC. A header the
  # precompiled one was made from whose time changed but whose bytes did not (a package upgrade) leaves it valid.
  list(APPEND SIMLAB_SUBMISSION_FLAGS -Wno-unused-private-field -fpch-validate-input-files-content)
endif()
set(SIMLAB_SUBMISSION_INCLUDES -isystem ${Simbody_INCLUDE_DIR})
set(SIMLAB_SUBMISSION_COMMAND ${SIMLAB_STUDENT_CXX} ${SIMLAB_SUBMISSION_FLAGS} ${SIMLAB_SUBMISSION_INCLUDES})
set(SIMLAB_CONTRACT_DIR ${PROJECT_BINARY_DIR}/contract)

# The precompiled headers of student files, one per assignment (simlab_contract below): Simbody, the standard
# library and the support headers (simlab/pch.h), the assignment's contract, and the templates its files
# instantiate (the assignment's PRECOMPILED header), each built once with exactly the flags above. With clang the
# templates are instantiated in the header (-fpch-instantiate-templates), so a student's compile after an edit does
# none of it again: the apple's reference file compiles in about 0.25 s against its lab's header, 0.35 s against one
# of Simbody alone (bench-self-check's floor shows it). GCC's .gch lies beside its header, which -include finds;
# clang's .pch is named by -include-pch.
configure_file(${SIMLAB_SOURCE_DIR}/assignments/support/include/simlab/pch.h ${SIMLAB_PCH_HEADER} COPYONLY)
if(SIMLAB_STUDENT_CXX_ID STREQUAL "Clang")
  set(SIMLAB_PCH_FLAGS -fpch-instantiate-templates)
else()
  set(SIMLAB_PCH_FLAGS "")
endif()

# The course's own code precompiles its heaviest headers once (Simbody's, the JSON library's and the standard
# library's) and every target that includes Simbody reuses them: one for libraries (-fPIC) and one for programs
# (-fPIE), since a precompiled header serves only code compiled with the same flags. simlab_use_pch(<target>) picks
# the one for the target; each is built only where a target uses it.
# The JSON library is the grader's: the lab programs alone (-DSIMLAB_GRADER=OFF) build without it.
set(SIMLAB_COURSE_PCH_HEADERS <algorithm> <cmath> <functional> <map> <memory> <sstream> <string> <vector>)
set(simlab_course_pch_libraries ${Simbody_LIBRARIES})
if(TARGET nlohmann_json::nlohmann_json)
  list(APPEND SIMLAB_COURSE_PCH_HEADERS <nlohmann/json.hpp>)
  list(APPEND simlab_course_pch_libraries nlohmann_json::nlohmann_json)
endif()
list(APPEND SIMLAB_COURSE_PCH_HEADERS <Simbody.h>)
file(WRITE ${PROJECT_BINARY_DIR}/pch/course_pch_host.cpp "// the course's precompiled header is built with this\n")
foreach(kind nopic pic)
  add_library(simlab_course_pch_${kind} OBJECT ${PROJECT_BINARY_DIR}/pch/course_pch_host.cpp)
  target_link_libraries(simlab_course_pch_${kind} PRIVATE ${simlab_course_pch_libraries})
  target_precompile_headers(simlab_course_pch_${kind} PRIVATE ${SIMLAB_COURSE_PCH_HEADERS})
  set_target_properties(simlab_course_pch_${kind} PROPERTIES EXCLUDE_FROM_ALL TRUE)
endforeach()
set_target_properties(simlab_course_pch_pic PROPERTIES POSITION_INDEPENDENT_CODE ON)
set_target_properties(simlab_course_pch_nopic PROPERTIES POSITION_INDEPENDENT_CODE OFF)  # Debian's default: -fPIE
function(simlab_use_pch)
  foreach(target IN LISTS ARGN)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE")
      set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE OFF)
      target_precompile_headers(${target} REUSE_FROM simlab_course_pch_nopic)
    else()
      set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
      target_precompile_headers(${target} REUSE_FROM simlab_course_pch_pic)
    endif()
  endforeach()
endfunction()

# simlab_contract(<id> <header> [<precompiled>]): the folder a student file of assignment <id> may include from,
# in the build tree: <id>/<header> and simlab/*.h (the support headers); and the assignment's precompiled header,
# built from simlab/pch.h and <precompiled> (which includes the contract; the contract alone without one). Sets
# SIMLAB_CONTRACT_INCLUDE in the caller, and the global properties SIMLAB_COMPILE_<id> (the command that compiles
# the assignment's student files: append -I<contract> -c SOURCE -o OBJECT) and SIMLAB_PCH_DEPENDS_<id>.
function(simlab_contract id header)
  set(dir ${SIMLAB_CONTRACT_DIR}/${id})
  get_filename_component(contract_name ${header} NAME)  # a student's file includes "<id>/<name>"
  configure_file(${CMAKE_CURRENT_SOURCE_DIR}/${header} ${dir}/${id}/${contract_name} COPYONLY)
  file(GLOB support_headers CONFIGURE_DEPENDS ${SIMLAB_SOURCE_DIR}/assignments/support/include/simlab/*.h)
  foreach(file IN LISTS support_headers)
    get_filename_component(name ${file} NAME)
    if(NOT name STREQUAL "pch.h")
      configure_file(${file} ${dir}/simlab/${name} COPYONLY)
    endif()
  endforeach()
  set(SIMLAB_CONTRACT_INCLUDE ${dir} PARENT_SCOPE)

  set(pch_header ${SIMLAB_PCH_DIR}/${id}.h)
  set(text "// ${id}'s precompiled header, written by cmake/Simlab.cmake.\n#include \"simlab_pch.h\"\n")
  if(ARGV2)
    configure_file(${CMAKE_CURRENT_SOURCE_DIR}/${ARGV2} ${SIMLAB_PCH_DIR}/${id}-uses.h COPYONLY)
    string(APPEND text "#include \"${id}-uses.h\"\n")
  else()
    string(APPEND text "#include \"${id}/${contract_name}\"\n")
  endif()
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/precompiled-header.h "${text}")
  configure_file(${CMAKE_CURRENT_BINARY_DIR}/precompiled-header.h ${pch_header} COPYONLY)  # rewritten only on a change
  if(SIMLAB_STUDENT_CXX_ID STREQUAL "Clang")
    set(pch ${pch_header}.pch)
    set(use -include-pch ${pch})
  else()
    set(pch ${pch_header}.gch)
    set(use -include ${pch_header})
  endif()
  # Its inputs by content (cmake/PchInputs.cmake), looked at on every build: the header is made again when a
  # system header's bytes change, even where the package gave it a time older than the header's.
  set(inputs_command ${CMAKE_COMMAND} -DDEPFILE=${pch}.d -DSTAMP=${pch}.inputs
                     -P ${SIMLAB_CMAKE_DIR}/PchInputs.cmake)
  add_custom_target(simlab_pch_inputs_${id} COMMAND ${inputs_command} BYPRODUCTS ${pch}.inputs VERBATIM)
  add_custom_command(
    OUTPUT ${pch}
    COMMAND ${SIMLAB_SUBMISSION_COMMAND} ${SIMLAB_PCH_FLAGS} -I${dir} -x c++-header ${pch_header} -o ${pch}
            -MD -MF ${pch}.d
    COMMAND ${inputs_command}
    COMMAND ${CMAKE_COMMAND} -E touch_nocreate ${pch}  # not older than the record of its inputs
    DEPFILE ${pch}.d
    DEPENDS ${pch_header} ${pch}.inputs ${SIMLAB_CMAKE_DIR}/PchInputs.cmake
    COMMENT "Precompiling the headers of ${id}'s student files"
    VERBATIM)
  add_custom_target(simlab_pch_${id} ALL DEPENDS ${pch})
  add_dependencies(simlab_pch_${id} simlab_pch_inputs_${id})
  set_property(GLOBAL PROPERTY SIMLAB_COMPILE_${id} ${SIMLAB_SUBMISSION_COMMAND} ${use})
  set_property(GLOBAL PROPERTY SIMLAB_PCH_HEADER_${id} ${pch_header})
  set_property(GLOBAL PROPERTY SIMLAB_PCH_DEPENDS_${id} simlab_pch_${id} ${pch})
endfunction()

# simlab_compile_submission(<object> <source> <id> [<flag>...]): compile one student file of assignment <id>
# (simlab_contract first) with its command, and the flags after it.
function(simlab_compile_submission object source id)
  get_property(command GLOBAL PROPERTY SIMLAB_COMPILE_${id})
  get_property(depends GLOBAL PROPERTY SIMLAB_PCH_DEPENDS_${id})
  add_custom_command(
    OUTPUT ${object}
    COMMAND ${command} ${ARGN} -I${SIMLAB_CONTRACT_DIR}/${id} -c ${source} -o ${object} -MD -MF ${object}.d
    DEPFILE ${object}.d
    DEPENDS ${source} ${depends}
    COMMENT "Compiling student file ${source}"
    VERBATIM)
endfunction()

# simlab_course_objects(<var> <target> <files...>): in <var>, the objects of <target> (an object library of the
# current folder) compiled from <files>, as a generator expression.
function(simlab_course_objects var target)
  set(names "")
  foreach(file IN LISTS ARGN)
    get_filename_component(path ${file} ABSOLUTE BASE_DIR ${CMAKE_CURRENT_SOURCE_DIR})
    file(RELATIVE_PATH name ${CMAKE_CURRENT_SOURCE_DIR} ${path})
    string(REPLACE "../" "__/" name ${name})  # CMake's name for a source above the folder
    string(REGEX REPLACE "([.+])" "\\\\\\1" name ${name})
    list(APPEND names ${name})
  endforeach()
  list(JOIN names "|" regex)
  set(${var} "$<FILTER:$<TARGET_OBJECTS:${target}>,INCLUDE,\\.dir/(${regex})\\.o$>" PARENT_SCOPE)
endfunction()

# simlab_add_assignment(<id>
#   TITLE <text>             what `simlab` calls it
#   SOURCE <file name>       the one file a student writes
#   STARTER <file>           what students start from (default: the course tree's starter/<id>/<SOURCE>)
#   SOLUTION <file>          the reference solution (default: the course tree's solutions/<id>/<SOURCE>); a
#                            folder of a lab without one (a student bundle's) has none
#   WORKED_EXAMPLE           the solution is handed out with the student bundle as a worked example: no secret
#   EXAMPLE <name>           the worked example's name: its programs' (<name>, <name>-study) and the one
#                            `simlab project new --from <name>` starts from; optional
#   PROJECTS                 each student makes a project of their own from the starter (`simlab project new`):
#                            each project's trade question is its own, and the lab's study is the worked example's
#   LONG_RUN                 its study follows the reference over a long time (`simlab study long-run`)
#   CORPUS <folder>          its sample submissions with their scores (default: corpus/ in its folder)
#   PROGRAM <name>           the runnable lab program (course main + student file)
#   CONTRACT <header>        the header the student implements, the only one of the assignment they may include
#   PRECOMPILED <header>     the end of the assignment's precompiled header: includes the contract, and names the
#                            templates its student files instantiate (see simlab_contract); optional
#   MAIN <files...>          the course side of the program
#   PROBE <files...>         what the grader can observe of the contract (simlab/probe.h)
#   TESTS <files...>         visible grader tests (Catch2), run in the judge
#   HIDDEN_TESTS <files...>  hidden grader tests; absent from the student bundle, so optional
#   RUBRIC <file>            points and thresholds, one [[test]] per Catch2 test case
#   STUDY <files...>         the work-precision study of the reference solution (simlab/study.h); optional
#   TRADE <file>             the trade question's scene and front (simlab/trade_question.h), in the judge as text
#                            (trade_question.inc); optional
#   HIDDEN_TRADE <file>)     its hidden variants (trade_hidden.inc); absent from the student bundle, so optional
function(simlab_add_assignment id)
  cmake_parse_arguments(A "WORKED_EXAMPLE;PROJECTS;LONG_RUN"
                        "TITLE;SOURCE;STARTER;SOLUTION;PROGRAM;RUBRIC;CONTRACT;PRECOMPILED;TRADE;HIDDEN_TRADE;EXAMPLE;CORPUS"
                        "MAIN;PROBE;TESTS;HIDDEN_TESTS;STUDY" ${ARGN})
  foreach(required TITLE SOURCE PROGRAM RUBRIC CONTRACT MAIN PROBE TESTS)
    if(NOT A_${required})
      message(FATAL_ERROR "simlab_add_assignment(${id}): ${required} is required")
    endif()
  endforeach()
  set(dir ${CMAKE_CURRENT_SOURCE_DIR})
  set(starter ${SIMLAB_SOURCE_DIR}/starter/${id}/${A_SOURCE})
  set(solution ${SIMLAB_SOURCE_DIR}/solutions/${id}/${A_SOURCE})
  if(A_STARTER)
    set(starter ${dir}/${A_STARTER})
  endif()
  if(A_SOLUTION)
    set(solution ${dir}/${A_SOLUTION})
  endif()
  if(NOT EXISTS ${starter})
    message(FATAL_ERROR "simlab_add_assignment(${id}): no starter file ${starter}")
  endif()

  set(tests ${A_TESTS})
  set(hidden_built false)
  if(NOT A_HIDDEN_TESTS)
    set(hidden_built true)  # nothing hidden to miss
  endif()
  set(hidden_paths "")
  foreach(file IN LISTS A_HIDDEN_TESTS)
    list(APPEND hidden_paths ${dir}/${file})
    if(EXISTS ${dir}/${file})
      list(APPEND tests ${file})
      set(hidden_built true)
    endif()
  endforeach()
  if(A_HIDDEN_TRADE)
    list(APPEND hidden_paths ${dir}/${A_HIDDEN_TRADE})
  endif()
  # The trade question's data files, as text the tests include.
  set(trade_dir ${CMAKE_CURRENT_BINARY_DIR}/trade)
  set(trade_texts "")
  foreach(kind question hidden)
    set(file ${A_TRADE})
    if(kind STREQUAL "hidden")
      set(file ${A_HIDDEN_TRADE})
    endif()
    if(file AND EXISTS ${dir}/${file})
      add_custom_command(
        OUTPUT ${trade_dir}/trade_${kind}.inc
        COMMAND ${CMAKE_COMMAND} -DIN=${dir}/${file} -DOUT=${trade_dir}/trade_${kind}.inc
                -P ${SIMLAB_CMAKE_DIR}/EmbedText.cmake
        DEPENDS ${dir}/${file} ${SIMLAB_CMAKE_DIR}/EmbedText.cmake
        VERBATIM)
      list(APPEND trade_texts ${trade_dir}/trade_${kind}.inc)
    endif()
  endforeach()

  simlab_contract(${id} ${A_CONTRACT} ${A_PRECOMPILED})
  set(contract ${SIMLAB_CONTRACT_INCLUDE})
  get_property(compile GLOBAL PROPERTY SIMLAB_COMPILE_${id})
  get_property(pch_depends GLOBAL PROPERTY SIMLAB_PCH_DEPENDS_${id})

  # The course's side includes its lab's files as "<id>/program/exact.h": from the folder that holds the lab's, or,
  # where the folder is named otherwise (a copy of examples/pendulum in my_lab/), from one of the build's where
  # <id> leads to it.
  get_filename_component(labs_dir ${dir} DIRECTORY)
  get_filename_component(folder_name ${dir} NAME)
  if(NOT folder_name STREQUAL id)
    set(labs_dir ${CMAKE_CURRENT_BINARY_DIR}/lab-include)
    file(MAKE_DIRECTORY ${labs_dir})
    file(CREATE_LINK ${dir} ${labs_dir}/${id} SYMBOLIC)
  endif()

  # A course source that more than one side names (MAIN, PROBE, TESTS, STUDY: biosim's stepping loop, declaration
  # checks and schematic) is compiled once, in <id>_course, as every side's own sources are (position-independent,
  # with the course's precompiled header), and each side that names it takes its object from there: <side>_own
  # are the side's own sources, <side>_course its objects of <id>_course. A side that names only such sources
  # compiles them itself.
  set(sides MAIN PROBE TESTS STUDY)
  set(A_TESTS ${tests})  # the hidden ones among them
  set(seen "")
  set(shared "")
  foreach(side IN LISTS sides)
    set(files ${A_${side}})
    list(REMOVE_DUPLICATES files)
    foreach(file IN LISTS files)
      if(file IN_LIST seen AND NOT file IN_LIST shared)
        list(APPEND shared ${file})
      endif()
      list(APPEND seen ${file})
    endforeach()
  endforeach()
  foreach(side IN LISTS sides)
    set(${side}_own ${A_${side}})
    set(${side}_course "")
    set(named ${A_${side}})
    if(shared)
      list(REMOVE_ITEM ${side}_own ${shared})
    endif()
    if(NOT ${side}_own)
      set(${side}_own ${A_${side}})
    elseif(NOT "${named}" STREQUAL "${${side}_own}")
      list(REMOVE_ITEM named ${${side}_own})
      simlab_course_objects(${side}_course ${id}_course ${named})
    endif()
  endforeach()
  if(shared)
    add_library(${id}_course OBJECT ${shared})
    target_link_libraries(${id}_course PRIVATE simlab_support ${Simbody_LIBRARIES})
    simlab_use_pch(${id}_course)
    target_include_directories(${id}_course PRIVATE ${labs_dir})
  endif()

  add_library(${id}_program_main OBJECT ${MAIN_own})
  target_link_libraries(${id}_program_main PRIVATE simlab_program simlab_support ${Simbody_LIBRARIES})
  simlab_use_pch(${id}_program_main)
  target_include_directories(${id}_program_main PRIVATE ${labs_dir})
  set(program_objects $<TARGET_OBJECTS:${id}_program_main> ${MAIN_course})

  set_property(GLOBAL APPEND PROPERTY SIMLAB_LAB_PROGRAMS "${id} ${A_PROGRAM} ${A_SOURCE}")  # simlab_write_editor_labs
  # The lab program, built from the student file in this tree (the starter unless told otherwise) ...
  set(SIMLAB_${id}_SOURCE ${starter} CACHE FILEPATH "Student file the ${A_PROGRAM} program is built from")
  set(object ${CMAKE_CURRENT_BINARY_DIR}/${A_PROGRAM}_student.o)
  # With line tables and variables for a debugger (VS Code's launch configuration): the graded object is not this one.
  simlab_compile_submission(${object} ${SIMLAB_${id}_SOURCE} ${id} -g)
  add_executable(${A_PROGRAM} ${program_objects} ${object})
  target_link_libraries(${A_PROGRAM} PRIVATE simlab_program simlab_support ${Simbody_LIBRARIES})
  # For editors, the student file as a translation unit of compile_commands.json with the folders it includes from
  # (clangd and VS Code's C/C++ read it there; the custom command above is not listed). Never built.
  add_library(${id}_student_file OBJECT EXCLUDE_FROM_ALL ${SIMLAB_${id}_SOURCE})
  target_include_directories(${id}_student_file PRIVATE ${SIMLAB_CONTRACT_DIR}/${id})
  target_include_directories(${id}_student_file SYSTEM PRIVATE ${Simbody_INCLUDE_DIR})
  target_compile_options(${id}_student_file PRIVATE -Wno-error -Wno-unused-parameter -Wno-deprecated-declarations)
  # ... and from the reference solution, where the tree has one (the student bundle does not).
  set(reference_program "")
  if(EXISTS ${solution})
    set(object ${CMAKE_CURRENT_BINARY_DIR}/${A_PROGRAM}_reference.o)
    simlab_compile_submission(${object} ${solution} ${id})
    add_executable(${A_PROGRAM}-reference ${program_objects} ${object})
    target_link_libraries(${A_PROGRAM}-reference PRIVATE simlab_program simlab_support ${Simbody_LIBRARIES})
    if(A_EXAMPLE)
      set_target_properties(${A_PROGRAM}-reference PROPERTIES OUTPUT_NAME ${A_EXAMPLE})
    endif()
    set(reference_program $<TARGET_FILE:${A_PROGRAM}-reference>)
  else()
    set(solution "")
  endif()
  if(NOT SIMLAB_GRADER)
    return()
  endif()

  # The work-precision study (`simlab study trade`), run on the reference solution where the tree has one.
  set(study_program "")
  set(study_objects "")
  if(A_STUDY)
    add_library(${id}_study_main OBJECT ${STUDY_own})
    target_link_libraries(${id}_study_main PRIVATE simlab_study simlab_protocol simlab_support ${Simbody_LIBRARIES})
    simlab_use_pch(${id}_study_main)
    target_include_directories(${id}_study_main PRIVATE ${labs_dir})
    simlab_study_target(${id}_study_main)
    set(study_objects $<TARGET_OBJECTS:${id}_study_main> ${STUDY_course})
    if(solution)
      add_executable(${A_PROGRAM}-study ${study_objects} ${CMAKE_CURRENT_BINARY_DIR}/${A_PROGRAM}_reference.o)
      target_link_libraries(${A_PROGRAM}-study PRIVATE simlab_study simlab_program simlab_support ${Simbody_LIBRARIES})
      simlab_study_target(${A_PROGRAM}-study)
      if(A_EXAMPLE)
        set_target_properties(${A_PROGRAM}-study PROPERTIES OUTPUT_NAME ${A_EXAMPLE}-study)
      endif()
      set(study_program $<TARGET_FILE:${A_PROGRAM}-study>)
    endif()
  endif()

  # The grader's side. Each test runs as two processes: the judge, built here once, holds the tests (hidden ones
  # included) and decides every verdict; the probe, linked per submission from the course's objects below and the
  # student's object, answers the judge's requests for observations. The tests are an object library so that
  # every Catch2 TEST_CASE registration stays in the link (an archive would drop them).
  add_library(${id}_grader_tests OBJECT ${TESTS_own} ${trade_texts})
  target_include_directories(${id}_grader_tests PRIVATE ${trade_dir})
  target_link_libraries(${id}_grader_tests PRIVATE simlab_harness simlab_support Catch2::Catch2 ${Simbody_LIBRARIES})
  add_executable(${id}-judge $<TARGET_OBJECTS:${id}_grader_tests> ${TESTS_course}
                            $<TARGET_OBJECTS:simlab_sanitizer_defaults>)
  target_link_libraries(${id}-judge PRIVATE simlab_harness simlab_observe_remote simlab_rubric simlab_support
                                            Catch2::Catch2WithMain ${Simbody_LIBRARIES})
  set_target_properties(${id}-judge PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/judges)
  add_library(${id}_probe OBJECT ${PROBE_own})
  target_link_libraries(${id}_probe PRIVATE simlab_probe simlab_support ${Simbody_LIBRARIES})
  set_target_properties(${id}_probe PROPERTIES POSITION_INDEPENDENT_CODE ON)
  simlab_use_pch(${id}_grader_tests ${id}_probe)
  target_include_directories(${id}_grader_tests PRIVATE ${labs_dir})
  target_include_directories(${id}_probe PRIVATE ${labs_dir})
  # Everything the manifest entry below names is built with it, so that `--target <id>_grader` alone makes a
  # tree that grades, links a floor and builds the lab program from a submission; `--target <id>_grading`, one
  # that grades (the lab program's objects left out: the sanitizer's tree, tests/sanitize).
  add_custom_target(${id}_grading DEPENDS ${id}-judge ${id}_probe ${pch_depends})
  add_dependencies(${id}_grading ${id}_grader_tests)
  if(shared)
    add_dependencies(${id}_grading ${id}_course)
  endif()
  if(NOT SIMLAB_KIT)  # simlab's own targets: built here, or installed ready (a lab built out of the tree)
    add_dependencies(${id}_grading simlab_probe_main simlab_probe simlab_support_objects simlab_sanitizer_defaults
                     simlab_harness simlab_observe_local simlab_rubric simlab_plot simlab_support simlab-probe-host)
  endif()
  add_custom_target(${id}_grader ALL DEPENDS ${id}_program_main)
  add_dependencies(${id}_grader ${id}_grading)
  if(NOT SIMLAB_KIT)
    add_dependencies(${id}_grader simlab_program)
  endif()

  # The probe's course side: linked before the student's object, whole, so that the student can add to it but
  # never replace any of it. The probe is a shared object that the probe's host loads (simlab-probe-host).
  set(probe_objects $<TARGET_OBJECTS:simlab_probe_main> $<TARGET_OBJECTS:simlab_probe>
                    $<TARGET_OBJECTS:${id}_probe> ${PROBE_course} $<TARGET_OBJECTS:simlab_support_objects>)
  # The benchmark's floor: the tests and the probe in one program, the student's code called directly. A course
  # source both sides name (biosim's declaration.cpp) is linked once.
  set(floor_course "")
  set(named ${A_PROBE} ${A_TESTS})
  list(REMOVE_DUPLICATES named)
  list(REMOVE_ITEM named ${TESTS_own} ${PROBE_own})
  if(named)
    simlab_course_objects(floor_course ${id}_course ${named})
  endif()
  # How the precompiled header is made (an installed simlab makes it again where it is installed).
  get_property(pch_header GLOBAL PROPERTY SIMLAB_PCH_HEADER_${id})
  set(json "{}")
  simlab_json_set_string(json id "${id}")
  simlab_json_set_string(json title "${A_TITLE}")
  simlab_json_set_string(json source "${A_SOURCE}")
  simlab_json_set_string(json program "${A_PROGRAM}")
  simlab_json_set_string(json program_path "$<TARGET_FILE:${A_PROGRAM}>")
  simlab_json_set_string(json reference_program_path "${reference_program}")
  simlab_json_set_string(json study_program_path "${study_program}")
  simlab_json_set_string(json dir "${dir}")
  simlab_json_set_string(json rubric "${dir}/${A_RUBRIC}")
  simlab_json_set_string(json contract_include "${contract}")
  simlab_json_set_string(json precompiled_header "${pch_header}")
  simlab_json_set_string(json starter "${starter}")
  simlab_json_set_string(json solution "${solution}")
  foreach(flag WORKED_EXAMPLE PROJECTS LONG_RUN)
    string(TOLOWER ${flag} key)
    if(key STREQUAL "worked_example")
      set(key solution_shipped)
    endif()
    if(A_${flag})
      string(JSON json SET "${json}" ${key} true)
    else()
      string(JSON json SET "${json}" ${key} false)
    endif()
  endforeach()
  simlab_json_set_string(json example "${A_EXAMPLE}")
  set(corpus ${dir}/corpus)
  if(A_CORPUS)
    get_filename_component(corpus ${A_CORPUS} ABSOLUTE BASE_DIR ${dir})
  endif()
  simlab_json_set_string(json corpus "${corpus}")
  simlab_json_set_string(json judge "$<TARGET_FILE:${id}-judge>")
  string(JSON json SET "${json}" hidden_tests_built ${hidden_built})
  simlab_json_set_list(json compile ${compile})
  simlab_json_set_list(json precompile_flags ${SIMLAB_PCH_FLAGS})
  simlab_json_set_list(json hidden_tests ${hidden_paths})
  simlab_json_set_generated_list(json probe_objects ${probe_objects})
  simlab_json_set_generated_list(json floor_objects
    $<TARGET_OBJECTS:${id}_grader_tests> $<TARGET_OBJECTS:simlab_harness> $<TARGET_OBJECTS:simlab_observe_local>
    $<TARGET_OBJECTS:simlab_probe> $<TARGET_OBJECTS:${id}_probe> ${floor_course}
    $<TARGET_OBJECTS:simlab_support_objects>)
  simlab_json_set_generated_list(json program_objects ${program_objects})
  simlab_json_set_generated_list(json study_objects ${study_objects})
  simlab_json_set_string(json build_dir "${CMAKE_CURRENT_BINARY_DIR}")
  set_property(GLOBAL APPEND PROPERTY SIMLAB_ASSIGNMENTS ${id})
  set_property(GLOBAL PROPERTY SIMLAB_ASSIGNMENT_${id} "${json}")
endfunction()

# simlab_study_target(<target>): a part of the work-precision studies. `simlab_studies` builds them all; without
# SIMLAB_BUILD_STUDIES they are left out of `all` and `simlab study` builds them when it first needs them.
function(simlab_study_target target)
  if(NOT TARGET simlab_studies)
    add_custom_target(simlab_studies)
  endif()
  add_dependencies(simlab_studies ${target})
  if(NOT SIMLAB_BUILD_STUDIES)
    set_target_properties(${target} PROPERTIES EXCLUDE_FROM_ALL TRUE)
  endif()
endfunction()

# simlab_write_editor_labs(): <build>/editor/labs, a line "<id> <program> <student file's name>" for each lab: what
# the editor's tasks (scripts/editor-task) check, build and run for a file open in starter/<id>/.
function(simlab_write_editor_labs)
  get_property(labs GLOBAL PROPERTY SIMLAB_LAB_PROGRAMS)
  list(JOIN labs "\n" text)
  file(WRITE ${PROJECT_BINARY_DIR}/editor/labs "${text}\n")
endfunction()

# simlab_write_manifest(): the build manifest the simlab engine reads to compile and link student code.
function(simlab_write_manifest)
  set(manifest "{}")
  simlab_json_set_string(manifest version "${PROJECT_VERSION}")
  simlab_json_set_string(manifest source_dir "${PROJECT_SOURCE_DIR}")
  simlab_json_set_string(manifest build_dir "${PROJECT_BINARY_DIR}")
  simlab_json_set_string(manifest cmake "${CMAKE_COMMAND}")
  simlab_json_set_string(manifest studies_target simlab_studies)
  simlab_json_set_string(manifest sample_class "${SIMLAB_SAMPLE_CLASS_DIR}")
  simlab_json_set_string(manifest catch2_include "$<TARGET_PROPERTY:Catch2::Catch2,INTERFACE_INCLUDE_DIRECTORIES>")
  simlab_json_set_string(manifest probe_host "$<TARGET_FILE:simlab-probe-host>")
  simlab_json_set_list(manifest compile ${SIMLAB_SUBMISSION_COMMAND})
  # A sanitizer build's course objects need the sanitizers' runtimes wherever they are linked: in the probes too.
  set(sanitizer_link "")
  if(SIMLAB_SANITIZE)
    set(sanitizer_link -fsanitize=address -fsanitize=undefined)
  endif()
  simlab_json_set_list(manifest link ${CMAKE_CXX_COMPILER} -pthread -fno-lto -fno-use-linker-plugin
                       ${SIMLAB_LINKER_FLAGS} ${sanitizer_link})
  # Link order: the course's objects, the student's object, then libraries from most to least dependent.
  simlab_json_set_generated_list(manifest probe_libraries
    $<TARGET_FILE:SimTKsimbody> $<TARGET_FILE:SimTKmath> $<TARGET_FILE:SimTKcommon>)
  # A probe is a shared object that simlab-probe-host loads as the test's own user (grader/isolation/host). It
  # exports its entry point alone: a function the student defines can never take the place of a library's, whoever
  # calls it; and it links only if every symbol it needs is there (-z defs), as a program would.
  file(WRITE ${PROJECT_BINARY_DIR}/probe-exports.map "{ global: simlab_probe_entry; local: *; };\n")
  # A sanitizer build's probe leaves the sanitizers' runtime to the host, which holds it (clang links it into the
  # program, not into each shared object): there it may not insist on every symbol at link time.
  set(defs -Wl,-z,defs)
  if(SIMLAB_SANITIZE)
    set(defs "")
  endif()
  simlab_json_set_list(manifest probe_link -shared ${defs}
                       -Wl,--version-script=${PROJECT_BINARY_DIR}/probe-exports.map)
  simlab_json_set_generated_list(manifest floor_libraries
    $<TARGET_FILE:simlab_plot> $<TARGET_FILE:simlab_rubric> $<TARGET_FILE:Catch2::Catch2WithMain> $<TARGET_FILE:tomlplusplus::tomlplusplus>
    $<TARGET_FILE:SimTKsimbody> $<TARGET_FILE:SimTKmath> $<TARGET_FILE:SimTKcommon>)
  simlab_json_set_generated_list(manifest program_libraries
    $<TARGET_FILE:simlab_program> $<TARGET_FILE:simlab_plot> $<TARGET_FILE:simlab_support>
    $<TARGET_FILE:SimTKsimbody> $<TARGET_FILE:SimTKmath> $<TARGET_FILE:SimTKcommon>)
  simlab_json_set_generated_list(manifest study_libraries
    $<TARGET_FILE:simlab_study> $<TARGET_FILE:simlab_program> $<TARGET_FILE:simlab_plot> $<TARGET_FILE:simlab_support>
    $<TARGET_FILE:SimTKsimbody> $<TARGET_FILE:SimTKmath> $<TARGET_FILE:SimTKcommon>)
  simlab_kit(manifest)
  simlab_json_assignments(manifest)
  simlab_json_generated(manifest "${manifest}")
  file(GENERATE OUTPUT ${SIMLAB_MANIFEST} CONTENT "${manifest}\n")
endfunction()

# simlab_json_assignments(<var>): member `assignments` of the JSON object in <var>, every simlab_add_assignment's.
function(simlab_json_assignments var)
  string(JSON json SET "${${var}}" assignments "[]")
  get_property(ids GLOBAL PROPERTY SIMLAB_ASSIGNMENTS)
  set(index 0)
  foreach(id IN LISTS ids)
    get_property(entry GLOBAL PROPERTY SIMLAB_ASSIGNMENT_${id})
    string(JSON json SET "${json}" assignments ${index} "${entry}")
    math(EXPR index "${index} + 1")
  endforeach()
  set(${var} "${json}" PARENT_SCOPE)
endfunction()

# simlab_kit(<var>): member `kit` of the manifest in <var>: what a lab built out of the tree builds against, its
# course side, tests and probe (simlabConfig.cmake makes imported targets of it with `simlab project
# cmake-config`). The headers of the support library and of the grader's modules a lab's code includes, this
# folder of CMake scripts, and each library simlab_add_assignment() names, with what it links after it.
function(simlab_kit var)
  set(kit "{}")
  set(grader ${PROJECT_SOURCE_DIR}/grader)
  simlab_json_set_list(kit include ${SIMLAB_SOURCE_DIR}/assignments/support/include ${grader}/rubric/include
                       ${grader}/protocol/include ${grader}/probe/include ${grader}/harness/include)
  simlab_json_set_string(kit cmake_dir "${SIMLAB_CMAKE_DIR}")
  string(JSON kit SET "${kit}" targets "[]")
  set(index 0)
  # name kind links...
  foreach(spec
      "simlab_support STATIC Simbody Boost::headers"
      "simlab_plot STATIC simlab_support"
      "simlab_program STATIC simlab_support simlab_plot"
      "simlab_study STATIC simlab_support simlab_program nlohmann_json::nlohmann_json"
      "simlab_rubric STATIC tomlplusplus::tomlplusplus"
      "simlab_protocol INTERFACE nlohmann_json::nlohmann_json"
      "simlab_support_objects OBJECT Simbody Boost::headers"
      "simlab_sanitizer_defaults OBJECT"
      "simlab_probe OBJECT simlab_protocol simlab_support"
      "simlab_probe_main OBJECT simlab_probe"
      "simlab_harness OBJECT simlab_rubric simlab_protocol simlab_support simlab_plot Catch2::Catch2"
      "simlab_observe_remote OBJECT simlab_harness"
      "simlab_observe_local OBJECT simlab_harness simlab_probe")
    string(REPLACE " " ";" spec "${spec}")
    list(POP_FRONT spec name kind)
    set(target "{}")
    simlab_json_set_string(target name ${name})
    simlab_json_set_string(target kind ${kind})
    simlab_json_set_list(target links ${spec})
    if(kind STREQUAL "OBJECT")
      simlab_json_set_generated_list(target files $<TARGET_OBJECTS:${name}>)
    elseif(kind STREQUAL "STATIC")
      simlab_json_set_generated_list(target files $<TARGET_FILE:${name}>)
    else()
      simlab_json_set_list(target files)
    endif()
    string(JSON kit SET "${kit}" targets ${index} "${target}")
    math(EXPR index "${index} + 1")
  endforeach()
  string(JSON json SET "${${var}}" kit "${kit}")
  set(${var} "${json}" PARENT_SCOPE)
  # `--target simlab_kit` builds what a lab builds against (a package's setup of a lab of one's own builds it alone).
  add_custom_target(simlab_kit)
  add_dependencies(simlab_kit simlab simlab-probe-host simlab_support simlab_plot simlab_program simlab_study
                   simlab_rubric simlab_support_objects simlab_sanitizer_defaults simlab_probe simlab_probe_main
                   simlab_harness simlab_observe_remote simlab_observe_local)
endfunction()

# simlab_write_lab_manifest(<file>): what a lab built out of the tree adds to simlab's manifest: its assignments.
function(simlab_write_lab_manifest file)
  set(manifest "{}")
  simlab_json_set_string(manifest version "${simlab_VERSION}")
  simlab_json_assignments(manifest)
  simlab_json_generated(manifest "${manifest}")
  file(GENERATE OUTPUT ${file} CONTENT "${manifest}\n")
endfunction()
