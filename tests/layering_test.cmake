# The libraries' layering, checked on the sources' #include lines:
#   format <- decoder <- io <- encoder <- measure <- tools
# a file may include the public headers of its own layer and those below it,
# never above.  `dbss info`, `dbss decode` and `dbss export` (tools/info.cpp,
# info_report.cpp, decode.cpp, export.cpp, open_dbss.cpp, args.cpp) sit on format, decoder and io alone, and
# the reference decoder (spec/reference) includes no dbss header at all: it
# is an independent witness.  Run with -DSOURCE=<source dir>.
cmake_minimum_required(VERSION 3.20)
set(layers format decoder io encoder measure tools)
set(errors "")
function(check_file file allowed)
  file(STRINGS ${file} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]dbss/")
  foreach(line ${lines})
    string(REGEX MATCH "dbss/([a-z_]+)/" _ "${line}")
    set(used ${CMAKE_MATCH_1})
    if(NOT used IN_LIST allowed)
      file(RELATIVE_PATH rel ${SOURCE} ${file})
      set(errors "${errors}\n  ${rel}: includes dbss/${used}/ (may use: ${allowed})" PARENT_SCOPE)
    endif()
  endforeach()
endfunction()

set(allowed "")
foreach(layer ${layers})
  list(APPEND allowed ${layer})
  file(GLOB_RECURSE files ${SOURCE}/${layer}/*.h ${SOURCE}/${layer}/*.cpp)
  foreach(f ${files})
    check_file(${f} "${allowed}")
  endforeach()
endforeach()
foreach(f info.cpp info_report.cpp decode.cpp export.cpp open_dbss.cpp args.cpp)
  check_file(${SOURCE}/tools/${f} "format;decoder;io")
endforeach()
file(GLOB_RECURSE files ${SOURCE}/spec/reference/*.h ${SOURCE}/spec/reference/*.cpp)
foreach(f ${files})
  check_file(${f} "")
endforeach()

if(errors)
  message(FATAL_ERROR "layering broken:${errors}")
endif()
message(STATUS "layering holds: format <- decoder <- io <- encoder <- measure <- tools")
