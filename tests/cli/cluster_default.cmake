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
# this test at the same time.
run_cluster_on_a_free_port(
  COMMAND ${CMAKE_COMMAND} -E env ZENITH_CACHE_DIR=${dir}/cache ${ZENITH} cluster --frames 2 --out "${dir}/run/out"
  WORKING_DIRECTORY "${dir}/run" TIMEOUT 900)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "zenith cluster (built-in default) failed (${status}):\n${out}\n${err}")
endif()
expect_mentions("${err}" "using the built-in copy ${dir}/cache/embedded-configs/" "the log (built-in config used?)")
expect_png_size("${dir}/run/out/stitched/frame-000001.png" 1024 1024 "the stitched frame")
