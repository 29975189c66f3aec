# Fails when tests/heavy_tests.cmake names a test that does not exist (renamed or removed):
# ctest itself ignores such a name, and the test it meant would run under the sanitizers again.
# Run by ctest as HeavyTestList.NamesTestsThatExist: cmake -DBUILD_DIR=... -DLIST=... -P this.
cmake_minimum_required(VERSION 3.25)
execute_process(COMMAND "${CMAKE_CTEST_COMMAND}" -N --test-dir "${BUILD_DIR}"
  OUTPUT_VARIABLE listing RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "ctest -N in ${BUILD_DIR} failed (${status})")
endif()
string(REGEX MATCHALL "Test +#[0-9]+: [^\n]+" entries "${listing}")
set(tests "")
foreach(entry IN LISTS entries)
  string(REGEX REPLACE "Test +#[0-9]+: " "" name "${entry}")
  list(APPEND tests "${name}")
endforeach()

file(STRINGS "${LIST}" lines REGEX "^  [A-Za-z0-9_/]+[.][A-Za-z0-9_/]+$")
set(count 0)
foreach(line IN LISTS lines)
  string(STRIP "${line}" name)
  math(EXPR count "${count} + 1")
  if(NOT name IN_LIST tests)
    message(FATAL_ERROR "${LIST}: '${name}' is not a test (renamed or removed?)")
  endif()
endforeach()
if(count LESS 10)
  message(FATAL_ERROR "${LIST}: read only ${count} names; the list's format changed?")
endif()
message(STATUS "${count} heavy tests, all of them tests")
