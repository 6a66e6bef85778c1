# `zenith cluster` with no --cluster, run from a folder without configs/: the
# built-in default (the 4-node local dome, its scene and viewports compiled into
# the binary) is written to the cache and played; the stitched frame is the
# 1024 x 1024 dome master. Called with ZENITH and WORK_DIR. The first run
# precomputes the paper-size tables of earth-advanced into WORK_DIR's cache
# (about 1.5 minutes on 2 cores with llvmpipe); later runs take seconds.
include("${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake")
set(dir "${WORK_DIR}/cluster-default")
file(REMOVE_RECURSE "${dir}/run")
file(MAKE_DIRECTORY "${dir}/run")
# A port of its own: another suite on the machine (another checkout) may run
# this test at the same time, so a taken port means another try on another one.
foreach(attempt RANGE 1 5)
  string(RANDOM LENGTH 4 ALPHABET 0123456789 digits)
  math(EXPR port "30000 + ${digits} % 20000")
  execute_process(
    COMMAND ${CMAKE_COMMAND} -E env ZENITH_CACHE_DIR=${dir}/cache
            ${ZENITH} cluster --frames 2 --port ${port} --out "${dir}/run/out"
    WORKING_DIRECTORY "${dir}/run"
    RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 900)
  string(FIND "${err}" "Address already in use" taken)
  if(taken EQUAL -1)
    break()
  endif()
endforeach()
if(NOT status EQUAL 0)
  message(FATAL_ERROR "zenith cluster (built-in default) failed (${status}):\n${out}\n${err}")
endif()
expect_mentions("${err}" "using the built-in copy ${dir}/cache/embedded-configs/" "the log (built-in config used?)")
expect_png_size("${dir}/run/out/stitched/frame-000001.png" 1024 1024 "the stitched frame")
