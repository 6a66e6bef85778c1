# The checks the command-line tests (tests/cli/*.cmake, run with cmake -P) make
# again and again; each of them includes this file first.

# Fails unless `png` is a PNG of `width` x `height` pixels, as its IHDR chunk
# states them (bytes 16 to 23 of the file: width, then height, each 4 bytes
# big-endian); `what` names the image in the message.
function(expect_png_size png width height what)
  file(READ "${png}" ihdr OFFSET 16 LIMIT 8 HEX)
  set(expected "")
  foreach(side ${width} ${height})
    math(EXPR hex "${side}" OUTPUT_FORMAT HEXADECIMAL)  # "0x4b0"
    string(SUBSTRING "${hex}" 2 -1 digits)
    string(LENGTH "${digits}" count)
    math(EXPR padding "8 - ${count}")
    string(REPEAT "0" ${padding} zeros)
    string(APPEND expected "${zeros}${digits}")
  endforeach()
  if(NOT ihdr STREQUAL expected)
    message(FATAL_ERROR "${what} is not ${width} x ${height}: IHDR ${ihdr}")
  endif()
endfunction()

# Fails unless `zenith ARGN` fails with a message (on stdout or stderr) that
# mentions `needle`.
function(expect_zenith_refuses needle)
  execute_process(COMMAND ${ZENITH} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  string(FIND "${o}${e}" "${needle}" pos)
  if(rc EQUAL 0 OR pos EQUAL -1)
    message(FATAL_ERROR "${ARGN}: expected a failure mentioning '${needle}', got (${rc}):\n${o}\n${e}")
  endif()
endfunction()

# Fails unless `text` contains `needle`; `what` names the text in the message
# ("the summary", "the report").
function(expect_mentions text needle what)
  string(FIND "${text}" "${needle}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "${what} does not mention '${needle}':\n${text}")
  endif()
endfunction()

# Fails unless every file named after `dir` and `writer` exists in `dir`;
# `writer` names what should have written them.
function(expect_files dir writer)
  foreach(f IN LISTS ARGN)
    if(NOT EXISTS "${dir}/${f}")
      message(FATAL_ERROR "${writer} did not write ${f}")
    endif()
  endforeach()
endfunction()

# Where gnuplot is installed, fails unless every file named after `dir` is a
# PNG in `dir` (by its 8-byte signature); without gnuplot the charts are not
# drawn and nothing is checked.
function(expect_gnuplot_pngs dir)
  find_program(GNUPLOT gnuplot)
  if(NOT GNUPLOT)
    return()
  endif()
  foreach(png IN LISTS ARGN)
    file(READ "${dir}/${png}" png_head LIMIT 8 HEX)
    if(NOT png_head STREQUAL "89504e470d0a1a0a")
      message(FATAL_ERROR "${png} is missing or not a PNG although gnuplot is installed")
    endif()
  endforeach()
endfunction()

# Runs `zenith cluster` (COMMAND, its whole command line but --port) with a
# master port of its own: other tests on this machine (the cluster tests'
# masters, any connection's ephemeral port) may hold any fixed one, so a port
# the master finds taken means another try on another, five at most. Sets
# status, out and err in the caller, as execute_process would.
function(run_cluster_on_a_free_port)
  cmake_parse_arguments(RUN "" "WORKING_DIRECTORY;TIMEOUT" "COMMAND" ${ARGN})
  if(NOT RUN_WORKING_DIRECTORY)
    set(RUN_WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}")
  endif()
  foreach(attempt RANGE 1 5)
    string(RANDOM LENGTH 4 ALPHABET 0123456789 digits)
    math(EXPR port "30000 + ${digits} % 20000")
    execute_process(
      COMMAND ${RUN_COMMAND} --port ${port}
      WORKING_DIRECTORY "${RUN_WORKING_DIRECTORY}"
      RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT ${RUN_TIMEOUT})
    string(FIND "${err}" "Address already in use" taken)
    if(taken EQUAL -1)
      break()
    endif()
  endforeach()
  set(status "${status}" PARENT_SCOPE)
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()
