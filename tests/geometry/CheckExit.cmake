# Runs a command and checks its exit code and that its standard error contains a text; used by
# the urbanpvs-cityinfo command-line tests in CMakeLists.txt.
#   cmake -DCOMMAND=prog|arg|arg -DEXPECT_RC=11 [-DEXPECT_STDERR=text] [-DEXPECT_STDOUT=text]
#         [-DREQUIRE_FILE=path] -P CheckExit.cmake
# An empty EXPECT_STDERR is refused: it would match anything; a test of a success names what
# its standard output must say (EXPECT_STDOUT).
# '|' separates the command's arguments. When REQUIRE_FILE is absent it prints "SKIP: ..." (the
# tests set SKIP_REGULAR_EXPRESSION on that) and succeeds.
if(DEFINED REQUIRE_FILE AND NOT EXISTS "${REQUIRE_FILE}")
  message("SKIP: ${REQUIRE_FILE} is absent")
  return()
endif()
string(REPLACE "|" ";" command "${COMMAND}")
execute_process(COMMAND ${command} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT "${rc}" STREQUAL "${EXPECT_RC}")
  message(FATAL_ERROR "exit status ${rc}, expected ${EXPECT_RC}\nstdout:\n${out}\nstderr:\n${err}")
endif()
if(DEFINED EXPECT_STDERR AND "${EXPECT_STDERR}" STREQUAL "")
  message(FATAL_ERROR "EXPECT_STDERR is empty: it matches anything; name the expected text")
endif()
if(DEFINED EXPECT_STDOUT)
  string(FIND "${out}" "${EXPECT_STDOUT}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "standard output lacks \"${EXPECT_STDOUT}\":\n${out}")
  endif()
endif()
if(DEFINED EXPECT_STDERR)
  string(FIND "${err}" "${EXPECT_STDERR}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "standard error lacks \"${EXPECT_STDERR}\":\n${err}")
  endif()
endif()
