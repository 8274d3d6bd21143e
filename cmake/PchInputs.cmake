# cmake -DDEPFILE=<header.pch.d> -DSTAMP=<header.pch.inputs> -P PchInputs.cmake
#
# What the precompiled header for student files was made from, by content: a line "<sha256> <path>" for each file
# its dependency file lists. Written only when it changes, so that a rule depending on STAMP reruns exactly when a
# header's bytes changed. A package upgrade often gives a system header a new time and the same bytes (which the
# compiler accepts: -fpch-validate-input-files-content) and sometimes new bytes (which it must not, and which make,
# comparing times, would miss when the packaged time is older than the header's build). simlab reads STAMP too,
# and stops before grading with a header whose inputs changed since (build/build.cpp).
if(NOT EXISTS "${DEPFILE}")
  if(NOT EXISTS "${STAMP}")
    file(WRITE "${STAMP}" "")
  endif()
  return()
endif()
file(READ "${DEPFILE}" rule)
# "target: a b \<newline> c ...": escaped spaces kept, the rest split into a list.
string(REPLACE "\\ " "<space>" rule "${rule}")
string(REGEX REPLACE "\\\\\r?\n" " " rule "${rule}")
string(REGEX REPLACE "[ \t\r\n]+" ";" tokens "${rule}")
set(lines "")
foreach(token IN LISTS tokens)
  if(token STREQUAL "" OR token MATCHES ":$")
    continue()
  endif()
  string(REPLACE "<space>" " " path "${token}")
  if(EXISTS "${path}" AND NOT IS_DIRECTORY "${path}")
    file(SHA256 "${path}" hash)
    string(APPEND lines "${hash} ${path}\n")
  endif()
endforeach()
set(old "")
if(EXISTS "${STAMP}")
  file(READ "${STAMP}" old)
endif()
if(NOT old STREQUAL lines)
  file(WRITE "${STAMP}" "${lines}")
endif()
