# cmake -DIN=<file> -DOUT=<file.inc> -P EmbedText.cmake
#
# A text file as a C++ raw string literal, for a program to hold the file itself: `#include "file.inc"` where a
# string goes.
file(READ "${IN}" text)
if(text MATCHES "\\)simlab-text\"")
  message(FATAL_ERROR "${IN} holds the raw string's end marker")
endif()
file(WRITE "${OUT}.tmp" "R\"simlab-text(${text})simlab-text\"\n")
file(RENAME "${OUT}.tmp" "${OUT}")
