# Every libcgal-demo file a test, bench or binding names must be listed in
# scripts/fetch-test-data.sh: under CI=true a test whose file was not
# fetched fails on a clean clone although it passes in a developer's tree
# with the whole data set linked (this happened three times).
# Usage: cmake -DSOURCE=<source dir> -P test_data_listed.cmake
file(READ "${SOURCE}/scripts/fetch-test-data.sh" fetch)
file(GLOB_RECURSE sources
  "${SOURCE}/tests/*.cpp" "${SOURCE}/tests/*.h" "${SOURCE}/tests/*.txt" "${SOURCE}/tests/*.cmake"
  "${SOURCE}/bench/*.cpp" "${SOURCE}/bench/*.txt"
  "${SOURCE}/python/*.py" "${SOURCE}/web/test/*.mjs" "${SOURCE}/scripts/*.sh")
set(missing "")
set(checked 0)
foreach(f IN LISTS sources)
  if(f MATCHES "test_data_listed.cmake$" OR f MATCHES "fetch-test-data.sh$")
    continue()
  endif()
  file(READ "${f}" text)
  string(REGEX MATCHALL "data/(meshes|points_3)/[A-Za-z0-9_.-]+\\.(off|ply|xyz|obj|stl)" names "${text}")
  list(REMOVE_DUPLICATES names)
  foreach(name IN LISTS names)
    math(EXPR checked "${checked} + 1")
    string(FIND "${fetch}" "  ${name}" at)
    if(at EQUAL -1)
      file(RELATIVE_PATH rel "${SOURCE}" "${f}")
      list(APPEND missing "${rel}: ${name}")
    endif()
  endforeach()
endforeach()
if(checked EQUAL 0)
  message(FATAL_ERROR "no test-data names found: the pattern or the globs are wrong")
endif()
if(missing)
  list(JOIN missing "\n  " lines)
  message(FATAL_ERROR "not fetched by scripts/fetch-test-data.sh (add them to its list):\n  ${lines}")
endif()
message(STATUS "${checked} test-data names, all listed in scripts/fetch-test-data.sh")
