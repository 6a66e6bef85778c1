# A cluster of 2 nodes × 2 windows paced at 60 Hz on a virtual display
# (xvfb-run): `zenith cluster --windows` for 300 frames; every node
# presents every frame once, in order (presented.log), each node reports how
# it detects late presents and how many it had, the master the counts per
# node, and the swap group the config asks for is detected and logged (Mesa
# has none: the network barrier plus vsync). Called with XVFB_RUN, ZENITH,
# SOURCE_DIR and WORK_DIR.
include("${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake")
set(dir "${WORK_DIR}/cluster-paced-windows")
file(REMOVE_RECURSE "${dir}")
file(MAKE_DIRECTORY "${dir}")
set(frames 300)
run_cluster_on_a_free_port(
  COMMAND ${XVFB_RUN} -a -s "-screen 0 64x64x24 -noreset" ${ZENITH} cluster --windows --frames ${frames}
          --cluster "${SOURCE_DIR}/tests/data/clusters/paced-2x2.json" --cache "${dir}/cache"
  WORKING_DIRECTORY "${dir}" TIMEOUT 600)
file(WRITE "${dir}/cluster.log" "${out}\n${err}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "zenith cluster --windows at 60 Hz failed (${status}):\n${out}\n${err}")
endif()
math(EXPR last "${frames} - 1")
foreach(node n1 n2)
  # Every frame once, in order.
  file(STRINGS "${dir}/out/paced/${node}/presented.log" lines)
  list(LENGTH lines count)
  if(NOT count EQUAL frames)
    message(FATAL_ERROR "node ${node} presented ${count} frames, expected ${frames} (see ${dir}/cluster.log)")
  endif()
  set(expected 0)
  foreach(line IN LISTS lines)
    if(NOT line MATCHES "^frame ${expected} ")
      message(FATAL_ERROR "node ${node}: line ${expected} of presented.log is '${line}', expected frame ${expected}")
    endif()
    math(EXPR expected "${expected} + 1")
  endforeach()
  # Two windows each, the swap group detected and logged, the late presents counted and reported.
  string(REGEX MATCHALL "node '${node}': rendering on [^\n]* into 2 windows" windows "${err}")
  if(NOT windows)
    message(FATAL_ERROR "node ${node} did not render into 2 windows:\n${err}")
  endif()
  if(NOT err MATCHES "node '${node}': (joined swap group 1|swap group 1 not joined: [^\n]*)")
    message(FATAL_ERROR "node ${node} did not say what became of swap group 1:\n${err}")
  endif()
  if(NOT err MATCHES "node '${node}': late presents counted from ")
    message(FATAL_ERROR "node ${node} did not say how it counts late presents:\n${err}")
  endif()
  if(NOT err MATCHES "node '${node}': presented ${frames} frames in its windows, ([0-9]+) late")
    message(FATAL_ERROR "node ${node} did not report its ${frames} presents and the late ones:\n${err}")
  endif()
  message(STATUS "node ${node}: ${CMAKE_MATCH_1} of ${frames} presents late")
endforeach()
# A deterministic start: frame 0 warms the nodes up unpaced; the schedule
# starts at its Present, and the late count leaves it out.
# (the match without its "; ", which would split it as a CMake list)
string(REGEX MATCHALL "master: warm-up frame 0 presented after [0-9.]+ ms" warm "${err}")
string(REGEX MATCHALL "Hz schedule starts now" schedule "${err}")
list(LENGTH schedule schedule_count)
list(LENGTH warm warm_count)
if(NOT warm_count EQUAL 1 OR NOT schedule_count EQUAL 1 OR NOT err MATCHES "after [0-9.]+ ms; the 60 Hz schedule starts now")
  message(FATAL_ERROR "the master did not start the 60 Hz schedule once, at the warm-up frame's Present:\n${err}")
endif()
if(NOT err MATCHES "master: pacing at 60 Hz: ${frames} frames presented, ([0-9]+) more than a period after they were due \\(the warm-up frame 0 not counted\\)")
  message(FATAL_ERROR "the master did not report its late frames:\n${err}")
endif()
message(STATUS "master: ${CMAKE_MATCH_1} of ${last} paced frames late")
# The master's counts per node, from the nodes' RenderDones (the last present comes after the last RenderDone).
if(NOT err MATCHES "master: late presents per node \\(as of its last RenderDone\\): n1 [0-9]+ of ${last}, n2 [0-9]+ of ${last}")
  message(FATAL_ERROR "the master did not report the late presents per node:\n${err}")
endif()
