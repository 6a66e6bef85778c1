# layers.upward_include_fails (tests/layers/CMakeLists.txt): builds each probe,
# a source compiled with the include directories of one library's own sources
# that includes a header of a module above that library, and passes when every
# one fails to compile because the compiler does not find that header; and
# builds the control, which includes only what its library may, and must compile
# (so a probe's failure is the include's, not the build's).
#
#   cmake -DBUILD_DIR=build -DPROBES="target=header|..." -DCONTROL=target -P upward_include.cmake
cmake_minimum_required(VERSION 3.20)
string(REPLACE "|" ";" PROBES "${PROBES}")

function(build_probe target out_rc out_log)
  execute_process(COMMAND "${CMAKE_COMMAND}" --build "${BUILD_DIR}" --target ${target}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE log)
  set(${out_rc} "${rc}" PARENT_SCOPE)
  set(${out_log} "${log}" PARENT_SCOPE)
endfunction()

build_probe(${CONTROL} rc log)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the control ${CONTROL} does not compile, so the probes prove nothing:\n${log}")
endif()
message("${CONTROL}: compiles")

set(failures 0)
foreach(probe IN LISTS PROBES)
  string(FIND "${probe}" "=" eq)
  string(SUBSTRING "${probe}" 0 ${eq} target)
  math(EXPR eq "${eq} + 1")
  string(SUBSTRING "${probe}" ${eq} -1 header)
  build_probe(${target} rc log)
  string(REPLACE "." "\\." header_re "${header}")
  # GCC: "fatal error: x/y.h: No such file or directory"; Clang: "fatal error: 'x/y.h' file not found".
  if(NOT rc EQUAL 0 AND (log MATCHES "${header_re}: No such file or directory" OR log MATCHES "'${header_re}' file not found"))
    message("${target}: #include \"${header}\" does not compile, as it should")
  else()
    message("${target}: #include \"${header}\" was not refused by the compiler (exit ${rc}):\n${log}")
    math(EXPR failures "${failures} + 1")
  endif()
endforeach()
if(failures GREATER 0)
  message(FATAL_ERROR "${failures} upward include(s) compiled: a library sees a module above it (docs/architecture.md)")
endif()
