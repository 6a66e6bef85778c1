# `zenith cluster` with no --cluster, run from a folder without configs/: the
# built-in default (the 4-node local dome, its scene and viewports compiled into
# the binary) is written to the cache and played; the stitched frame is the
# 1024 x 1024 dome master. Called with ZENITH and WORK_DIR. Its cache is
# WORK_DIR's, shared with cli.validate_eclipse, which ctest runs first
# (DEPENDS): the paper-size tables of earth-advanced are the same, computed
# once (about 25 s alone on 2 cores with llvmpipe, longer beside other tests).
include("${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake")
set(dir "${WORK_DIR}/cluster-default")
set(cache "${WORK_DIR}/cache")
file(REMOVE_RECURSE "${dir}/run")
file(MAKE_DIRECTORY "${dir}/run")
# A port of its own: another suite on the machine (another checkout) may run
# this test at the same time.
run_cluster_on_a_free_port(
  COMMAND ${CMAKE_COMMAND} -E env ZENITH_CACHE_DIR=${cache} ${ZENITH} cluster --frames 2 --out "${dir}/run/out"
  WORKING_DIRECTORY "${dir}/run" TIMEOUT 900)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "zenith cluster (built-in default) failed (${status}):\n${out}\n${err}")
endif()
expect_mentions("${err}" "using the built-in copy ${cache}/embedded-configs/" "the log (built-in config used?)")
expect_png_size("${dir}/run/out/stitched/frame-000001.png" 1024 1024 "the stitched frame")
