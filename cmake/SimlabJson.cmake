# JSON made with CMake's own JSON means (string(JSON ... SET ...)), for the build manifest (Simlab.cmake). Every
# string is escaped; a list whose items only generation knows ($<TARGET_OBJECTS:...>, $<TARGET_FILE:...>) is a
# placeholder until simlab_json_generated() puts its generator expression in the text file(GENERATE) writes.

# `text` as a JSON string: quoted, its backslashes, quotes and control characters escaped.
function(simlab_json_quote out text)
  string(REPLACE "\\" "\\\\" text "${text}")
  string(REPLACE "\"" "\\\"" text "${text}")
  string(REPLACE "\n" "\\n" text "${text}")
  string(REPLACE "\r" "\\r" text "${text}")
  string(REPLACE "\t" "\\t" text "${text}")
  set(${out} "\"${text}\"" PARENT_SCOPE)
endfunction()

# Member `key` of the JSON object in the variable named `var` set to the string `text`.
function(simlab_json_set_string var key text)
  simlab_json_quote(quoted "${text}")
  string(JSON json SET "${${var}}" ${key} "${quoted}")
  set(${var} "${json}" PARENT_SCOPE)
endfunction()

# Member `key` set to an array of strings, one per item of the CMake list that follows.
function(simlab_json_set_list var key)
  set(array "[]")
  set(index 0)
  foreach(item IN LISTS ARGN)
    simlab_json_quote(quoted "${item}")
    string(JSON array SET "${array}" ${index} "${quoted}")
    math(EXPR index "${index} + 1")
  endforeach()
  string(JSON json SET "${${var}}" ${key} "${array}")
  set(${var} "${json}" PARENT_SCOPE)
endfunction()

# Member `key` set to an array of the paths that the generator expressions that follow give (a list each, joined).
# Such paths are CMake's own, under the build folder or a package's prefix; Simlab.cmake checks that the build
# folder's path needs no escaping.
function(simlab_json_set_generated_list var key)
  get_property(count GLOBAL PROPERTY SIMLAB_JSON_GENERATED)
  if(NOT count)
    set(count 0)
  endif()
  math(EXPR count "${count} + 1")
  set(expression "[]")
  if(ARGN)
    set(expression "[\"$<JOIN:${ARGN},\",\">\"]")
  endif()
  set_property(GLOBAL PROPERTY SIMLAB_JSON_GENERATED ${count})
  set_property(GLOBAL PROPERTY SIMLAB_JSON_GENERATED_${count} "${expression}")
  simlab_json_set_string(${var} ${key} "@simlab-generated-${count}@")
  set(${var} "${${var}}" PARENT_SCOPE)
endfunction()

# `json` with each generated list's placeholder replaced by its generator expression: the text for file(GENERATE).
function(simlab_json_generated out json)
  get_property(count GLOBAL PROPERTY SIMLAB_JSON_GENERATED)
  if(count)
    foreach(n RANGE 1 ${count})
      get_property(expression GLOBAL PROPERTY SIMLAB_JSON_GENERATED_${n})
      string(REPLACE "\"@simlab-generated-${n}@\"" "${expression}" json "${json}")
    endforeach()
  endif()
  set(${out} "${json}" PARENT_SCOPE)
endfunction()
