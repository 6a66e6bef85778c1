# `zenith cluster --windows` on a virtual display (xvfb-run): two nodes render
# halves of a dome master, show every presented frame in a window and write it;
# the stitched last frame is the whole dome. Called with XVFB_RUN, ZENITH,
# SOURCE_DIR and WORK_DIR.
include("${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake")
set(dir "${WORK_DIR}/cluster-windows")
file(REMOVE_RECURSE "${dir}")
file(MAKE_DIRECTORY "${dir}")
run_cluster_on_a_free_port(
  COMMAND ${XVFB_RUN} -a -s "-screen 0 640x480x24 -noreset" ${ZENITH} cluster --windows --frames 3
          --cluster "${SOURCE_DIR}/tests/data/clusters/windowed-halves.json" --out "${dir}/out" --cache "${dir}/cache"
  TIMEOUT 600)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "zenith cluster --windows failed (${status}):\n${out}\n${err}")
endif()
foreach(node left right)
  string(FIND "${err}" "node '${node}': rendering on" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "node ${node} did not report its GL renderer:\n${err}")
  endif()
  foreach(frame 000000 000001 000002)
    if(NOT EXISTS "${dir}/out/${node}/${node}/frame-${frame}.png")
      message(FATAL_ERROR "node ${node} did not write frame ${frame}:\n${err}")
    endif()
  endforeach()
endforeach()
string(REGEX MATCHALL "into 1 window" windows "${err}")
list(LENGTH windows count)
if(NOT count EQUAL 2)
  message(FATAL_ERROR "expected 2 nodes rendering into windows, found ${count}:\n${err}")
endif()
expect_png_size("${dir}/out/stitched/frame-000002.png" 96 96 "the stitched frame")
