# The render node's systemd unit (configs/systemd/zenith-node@.service,
# docs/cluster.md "A node as a service"): systemd-analyze verify finds no
# unknown key, no bad section and an ExecStart it can run (this build's
# zenith in place of /usr/local/bin/zenith), and the command line it runs is
# one `zenith node` accepts. Skipped (77) without systemd-analyze.
find_program(SYSTEMD_ANALYZE systemd-analyze)
if(NOT SYSTEMD_ANALYZE)
  message("systemd-analyze not found: skipped")
  cmake_language(EXIT 77)
endif()
set(dir "${WORK_DIR}/systemd-unit")
file(REMOVE_RECURSE "${dir}")
file(MAKE_DIRECTORY "${dir}")
file(READ "${SOURCE_DIR}/configs/systemd/zenith-node@.service" unit)
string(REPLACE "/usr/local/bin/zenith" "${ZENITH}" unit "${unit}")
file(WRITE "${dir}/zenith-node@render-1.service" "${unit}")
execute_process(COMMAND ${SYSTEMD_ANALYZE} verify "${dir}/zenith-node@render-1.service"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT "${out}${err}" STREQUAL "")
  message(FATAL_ERROR "systemd-analyze verify (${rc}):\n${out}${err}")
endif()
# The options of its ExecStart are the node's: --help of `zenith node` lists each.
string(REGEX MATCH "ExecStart=[^\n]*" exec "${unit}")
execute_process(COMMAND ${ZENITH} node --help OUTPUT_VARIABLE help ERROR_VARIABLE help_err)
string(REGEX MATCHALL "--[a-z-]+" options "${exec}")
foreach(option IN LISTS options)
  string(FIND "${help}" "${option}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the unit's ExecStart uses ${option}, which `zenith node` does not have:\n${help}")
  endif()
endforeach()
file(REMOVE_RECURSE "${dir}")
