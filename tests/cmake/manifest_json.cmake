# The build manifest's JSON (cmake/SimlabJson.cmake): a lab whose title holds a quote, a backslash, a newline and a
# semicolon is written as valid JSON that reads back the same, beside a list only generation knows.
#   cmake -DSOURCE_DIR=<simlab's source folder> -P manifest_json.cmake
include(${SOURCE_DIR}/cmake/SimlabJson.cmake)

set(title "The \"apple\" lab\\n, a C:\\path\\ and a tab\there;\nsecond line")
set(lab "{}")
simlab_json_set_string(lab id apple)
simlab_json_set_string(lab title "${title}")
simlab_json_set_list(lab compile clang++ "-DNAME=\"x\"" "-I/a b\\c")
simlab_json_set_generated_list(lab probe_objects $<TARGET_OBJECTS:probe> $<TARGET_OBJECTS:support>)
set(manifest "{}")
string(JSON manifest SET "${manifest}" assignments "[]")
string(JSON manifest SET "${manifest}" assignments 0 "${lab}")
simlab_json_generated(text "${manifest}")

function(expect what actual expected)
  if(NOT actual STREQUAL expected)
    message(FATAL_ERROR "${what}: got [${actual}], expected [${expected}]")
  endif()
endfunction()

# Before generation the generated list is a generator expression that joins its paths into a JSON array.
string(FIND "${text}" "[\"$<JOIN:$<TARGET_OBJECTS:probe>;$<TARGET_OBJECTS:support>,\",\">\"]" at)
if(at EQUAL -1)
  message(FATAL_ERROR "the generated list is not in the manifest's text:\n${text}")
endif()
# As generation would leave it, for these two objects.
string(REPLACE "$<JOIN:$<TARGET_OBJECTS:probe>;$<TARGET_OBJECTS:support>,\",\">" "/b/probe.o\",\"/b/support.o"
       generated "${text}")
string(JSON read ERROR_VARIABLE error GET "${generated}" assignments 0 title)
expect("the title" "${read}" "${title}")
string(JSON read GET "${generated}" assignments 0 compile 1)
expect("a flag with quotes" "${read}" "-DNAME=\"x\"")
string(JSON read GET "${generated}" assignments 0 compile 2)
expect("a flag with a backslash" "${read}" "-I/a b\\c")
string(JSON read GET "${generated}" assignments 0 probe_objects 1)
expect("a generated path" "${read}" "/b/support.o")
string(JSON count LENGTH "${generated}" assignments 0)
expect("the lab's members" "${count}" 4)
