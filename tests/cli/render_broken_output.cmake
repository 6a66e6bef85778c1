# One broken output must not stop another: `zenith render --viewport
# FILE#good` renders `good` while another output of FILE has a broken warp;
# asking for the broken output, or for every output, gives its error naming
# the config, the key, the warp file, the line and the field.
include("${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake")
set(cache "${WORK_DIR}/cache")  # shared with cli.render: tables computed once
set(out "${WORK_DIR}/render-broken-output")
file(REMOVE_RECURSE "${out}")
file(MAKE_DIRECTORY "${out}")

# Two Paul Bourke meshes, 2 x 2 nodes "x y u v intensity", rows from the bottom:
# the identity, and the same with a field that is not a number on line 4.
file(WRITE "${out}/good.data" "2\n2 2\n-1 -1 0 0 1\n1 -1 1 0 1\n-1 1 0 1 1\n1 1 1 1 1\n")
file(WRITE "${out}/bad.data" "2\n2 2\n-1 -1 0 0 1\n1 -1 abc 0 1\n-1 1 0 1 1\n1 1 1 1 1\n")
file(WRITE "${out}/show.json" [=[{"zenith_viewports": 1, "name": "show", "outputs": [
  {"name": "good", "size": [40, 24], "projection": {"type": "fisheye"},
   "warp": {"file": "good.data", "format": "bourke"}},
  {"name": "bad", "size": [40, 24], "projection": {"type": "fisheye"},
   "warp": {"file": "bad.data", "format": "bourke"}}]}
]=])
set(scene --scene "${SOURCE_DIR}/configs/scenes/earth-sunset.json" --tables small --cache "${cache}")

execute_process(COMMAND ${ZENITH} render ${scene} --viewport "${out}/show.json#good" --out "${out}/good.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${out}/good.png")
  message(FATAL_ERROR "rendering the good output failed (${rc}): ${stdout}\n${err}")
endif()
expect_png_size("${out}/good.png" 40 24 "good.png")  # from the viewport config

set(reason "show.json: /outputs/1/warp/file: cannot use the warp: ${out}/bad.data:4: field 'u' = 'abc' is not a number")
function(expect_broken what)
  execute_process(COMMAND ${ZENITH} render ${scene} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  string(FIND "${o}${e}" "${reason}" pos)
  if(rc EQUAL 0 OR pos EQUAL -1)
    message(FATAL_ERROR "${what}: expected a failure mentioning\n  ${reason}\ngot (${rc}):\n${o}\n${e}")
  endif()
endfunction()
expect_broken("the broken output" --viewport "${out}/show.json#bad" --out "${out}/bad.png")
expect_broken("every output" --viewport "${out}/show.json" --out "${out}/all/")
if(EXISTS "${out}/bad.png" OR EXISTS "${out}/all")
  message(FATAL_ERROR "a refused render left files behind")
endif()
file(REMOVE_RECURSE "${out}")
