# `zenith render` end to end: a small fisheye and planar frame of a scene to
# EXR + PNG (small tables, private cache), then bad arguments are refused with
# a message naming the argument.
include("${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake")
set(cache "${WORK_DIR}/cache")  # shared with cli.render_window: tables computed once
set(out "${WORK_DIR}/render-out")
file(REMOVE_RECURSE "${out}")

execute_process(COMMAND ${ZENITH} render --scene "${SOURCE_DIR}/configs/scenes/earth-sunset.json" --projection fisheye
                        --size 48x48 --tables small --cache "${cache}" --out "${out}/dome.exr" --out "${out}/dome.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "render failed (${rc}): ${err}")
endif()
foreach(f dome.exr dome.png)
  if(NOT EXISTS "${out}/${f}" OR EXISTS "${out}/${f}.partial")
    message(FATAL_ERROR "render did not leave ${f} (and only it): ${stdout}\n${err}")
  endif()
endforeach()
file(READ "${out}/dome.png" png_head LIMIT 8 HEX)
if(NOT png_head STREQUAL "89504e470d0a1a0a")
  message(FATAL_ERROR "dome.png is not a PNG")
endif()
file(READ "${out}/dome.exr" exr_head LIMIT 4 HEX)
if(NOT exr_head STREQUAL "762f3101")
  message(FATAL_ERROR "dome.exr is not an OpenEXR file")
endif()

execute_process(COMMAND ${ZENITH} render --scene "${SOURCE_DIR}/configs/scenes/mars-sunset.json" --projection planar
                        --fov 70 --size 64x36 --tables small --cache "${cache}" --out "${out}/mars.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${out}/mars.png")
  message(FATAL_ERROR "planar render failed (${rc}): ${err}")
endif()

# One projector of the 6-projector dome, alone, blended (docs/viewports.md).
execute_process(COMMAND ${ZENITH} render --scene "${SOURCE_DIR}/configs/scenes/earth-ground-noon.json"
                        --viewport "${SOURCE_DIR}/configs/viewports/dome-6-projectors.json#p2" --tables small
                        --cache "${cache}" --out "${out}/p2.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${out}/p2.png")
  message(FATAL_ERROR "viewport render failed (${rc}): ${err}")
endif()
expect_png_size("${out}/p2.png" 1920 1200 "p2.png")  # from the viewport config

# An 8192² dome master streams through bands and the PNG writer within CI memory.
execute_process(COMMAND ${ZENITH} render --scene "${SOURCE_DIR}/configs/scenes/earth-ground-noon.json"
                        --projection fisheye --size 8192x8192 --tables small --cache "${cache}"
                        --out "${out}/dome-8k.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${out}/dome-8k.png")
  message(FATAL_ERROR "8K render failed (${rc}): ${err}")
endif()
expect_png_size("${out}/dome-8k.png" 8192 8192 "dome-8k.png")

# Bad input: each refused with a message naming what is wrong.
function(expect_refused needle)
  expect_zenith_refuses("${needle}" render ${ARGN})
endfunction()
set(scene --scene "${SOURCE_DIR}/configs/scenes/earth-sunset.json")
expect_refused("--size" ${scene} --size 12by12 --out "${out}/x.png")
expect_refused("--out" ${scene} --size 8x8 --out "${out}/x.tiff")
expect_refused("--fov" ${scene} --projection planar --fov 200 --size 8x8 --out "${out}/x.png")
expect_refused("--viewport" ${scene} --viewport "${SOURCE_DIR}/configs/viewports/dome-6-projectors.json#p2"
               --size 8x8 --out "${out}/x.png")
expect_refused("p9" ${scene} --viewport "${SOURCE_DIR}/configs/viewports/dome-6-projectors.json#p9" --out "${out}/x.png")
expect_refused("missing.json" --scene "${out}/missing.json" --size 8x8 --out "${out}/x.png")
file(REMOVE_RECURSE "${out}")
