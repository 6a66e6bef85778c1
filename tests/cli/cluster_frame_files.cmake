# Live shows write no frame files unless asked: `zenith cluster`
# without --out leaves none (presented.log still records every presented
# frame); with --record-frames DIR exactly one file per output and presented
# frame, named by the frames presented.log lists. Headless nodes. Called with
# ZENITH, SOURCE_DIR and WORK_DIR.
include("${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake")
set(dir "${WORK_DIR}/cluster-frame-files")
file(REMOVE_RECURSE "${dir}")
file(MAKE_DIRECTORY "${dir}/live")
set(config "${SOURCE_DIR}/tests/data/clusters/windowed-halves.json")

# Without --out: the config's output directory (out/windowed, relative to the
# working directory) gets the logs only.
run_cluster_on_a_free_port(
  COMMAND ${ZENITH} cluster --frames 3 --cluster "${config}" --cache "${dir}/cache"
  WORKING_DIRECTORY "${dir}/live" TIMEOUT 600)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "zenith cluster without --out failed (${status}):\n${out}\n${err}")
endif()
file(GLOB_RECURSE frames "${dir}/live/*.png" "${dir}/live/*.exr" "${dir}/live/*.partial")
if(frames)
  message(FATAL_ERROR "a live show without --out wrote frame files: ${frames}")
endif()
foreach(node left right)
  set(log "${dir}/live/out/windowed/${node}/presented.log")
  if(NOT EXISTS "${log}")
    message(FATAL_ERROR "node ${node} wrote no presented.log (${log}):\n${err}")
  endif()
  file(STRINGS "${log}" lines)
  list(LENGTH lines count)
  if(NOT count EQUAL 3)
    message(FATAL_ERROR "node ${node} presented ${count} frames, expected 3:\n${lines}")
  endif()
endforeach()

# With --record-frames DIR: one file per output and presented frame, no more.
run_cluster_on_a_free_port(
  COMMAND ${ZENITH} cluster --frames 3 --cluster "${config}" --cache "${dir}/cache" --record-frames "${dir}/recorded"
  WORKING_DIRECTORY "${dir}/live" TIMEOUT 600)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "zenith cluster --record-frames failed (${status}):\n${out}\n${err}")
endif()
foreach(node left right)
  file(STRINGS "${dir}/recorded/${node}/presented.log" lines)
  set(expected "")
  foreach(line IN LISTS lines)
    string(REGEX MATCH "^frame ([0-9]+) " match "${line}")
    math(EXPR frame "${CMAKE_MATCH_1}" OUTPUT_FORMAT DECIMAL)
    string(LENGTH "${frame}" digits)
    math(EXPR pad "6 - ${digits}")
    string(REPEAT "0" ${pad} zeros)
    list(APPEND expected "${dir}/recorded/${node}/${node}/frame-${zeros}${frame}.png")
  endforeach()
  file(GLOB written "${dir}/recorded/${node}/${node}/*")
  list(SORT written)
  list(SORT expected)
  list(LENGTH expected presented)
  if(NOT presented EQUAL 3 OR NOT "${written}" STREQUAL "${expected}")
    message(FATAL_ERROR "node ${node}: files ${written}\nexpected one per presented frame: ${expected}")
  endif()
endforeach()
# The nodes' stitched frame: the recorded tiles make the whole dome master.
if(NOT EXISTS "${dir}/recorded/stitched/frame-000002.png")
  message(FATAL_ERROR "no stitched frame with --record-frames:\n${err}")
endif()
