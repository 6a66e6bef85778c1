# `zenith export-calibration`: one output of a generated viewport
# config exported into a folder; the command prints every file it wrote, the
# exported config loads back (zenith export-calibration on it again), and an
# unknown output or an unwritable folder is refused naming the name or folder.
set(out "${WORK_DIR}/export-calibration")
file(REMOVE_RECURSE "${out}")
file(MAKE_DIRECTORY "${out}")

# A Paul Bourke mesh, 2 x 2 nodes "x y u v intensity", rows from the bottom: the identity.
file(WRITE "${out}/mirror.data" "2\n2 2\n-1 -1 0 0 1\n1 -1 1 0 1\n-1 1 0 1 1\n1 1 1 1 1\n")
file(WRITE "${out}/show.json" [=[{"zenith_viewports": 1, "name": "show", "outputs": [
  {"name": "mirror", "size": [40, 24], "projection": {"type": "fisheye"},
   "warp": {"file": "mirror.data", "format": "bourke"}, "black_level": 0.02},
  {"name": "flat", "size": [16, 9], "projection": {"type": "planar", "fov_deg": 60}}]}
]=])

execute_process(COMMAND ${ZENITH} export-calibration --viewport "${out}/show.json#mirror" --out "${out}/hw"
                RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "export-calibration failed (${rc}): ${stdout}\n${err}")
endif()
foreach(f mirror.warp.pfm mirror.alpha-linear.png mirror.alpha-gamma2.2.png mirror.beta-linear.png
          mirror.beta-gamma2.2.png mirror.mpcdi viewport-pfm.json viewport-mpcdi.json calibration.json)
  string(FIND "${stdout}" "written ${out}/hw/${f}: " pos)
  if(pos EQUAL -1 OR NOT EXISTS "${out}/hw/${f}")
    message(FATAL_ERROR "export-calibration did not write or print ${f}:\n${stdout}")
  endif()
endforeach()
file(READ "${out}/hw/mirror.alpha-linear.png" ihdr OFFSET 16 LIMIT 10 HEX)
if(NOT ihdr STREQUAL "00000028000000181000")  # 40 x 24, 16 bit, grey
  message(FATAL_ERROR "mirror.alpha-linear.png is not a 40x24 16-bit grey PNG: IHDR ${ihdr}")
endif()
if(EXISTS "${out}/hw/flat.warp.pfm")
  message(FATAL_ERROR "#mirror exported another output too")
endif()

# The exported configs load: export them again.
foreach(kind pfm mpcdi)
  execute_process(COMMAND ${ZENITH} export-calibration --viewport "${out}/hw/viewport-${kind}.json" --out "${out}/again-${kind}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  if(NOT rc EQUAL 0 OR NOT EXISTS "${out}/again-${kind}/mirror.mpcdi")
    message(FATAL_ERROR "the exported viewport-${kind}.json does not load (${rc}): ${o}\n${e}")
  endif()
endforeach()

# The sl profile: a planar output as a pinhole projector; the
# exported config gives no projection and loads (exported again).
execute_process(COMMAND ${ZENITH} export-calibration --viewport "${out}/show.json#flat" --out "${out}/sl"
                        --mpcdi-profile sl
                RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
string(FIND "${stdout}" "written ${out}/sl/flat.mpcdi: MPCDI sl profile, region 'flat' 16 x 9 px: mpcdi.xml (frustum" pos)
if(NOT rc EQUAL 0 OR pos EQUAL -1)
  message(FATAL_ERROR "export-calibration --mpcdi-profile sl failed or did not print the sl archive (${rc}):\n${stdout}\n${err}")
endif()
file(READ "${out}/sl/viewport-mpcdi.json" sl_config)
string(FIND "${sl_config}" "\"projection\"" pos)
if(NOT pos EQUAL -1)
  message(FATAL_ERROR "the sl viewport-mpcdi.json gives a projection (the region's frustum should):\n${sl_config}")
endif()
execute_process(COMMAND ${ZENITH} export-calibration --viewport "${out}/sl/viewport-mpcdi.json" --out "${out}/sl-again"
                        --mpcdi-profile sl
                RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
if(NOT rc EQUAL 0 OR NOT EXISTS "${out}/sl-again/flat.mpcdi")
  message(FATAL_ERROR "the exported sl viewport-mpcdi.json does not load (${rc}): ${o}\n${e}")
endif()

function(expect_refused what reason)
  execute_process(COMMAND ${ZENITH} export-calibration ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  string(FIND "${o}${e}" "${reason}" pos)
  if(rc EQUAL 0 OR pos EQUAL -1)
    message(FATAL_ERROR "${what}: expected a failure mentioning\n  ${reason}\ngot (${rc}):\n${o}\n${e}")
  endif()
endfunction()
expect_refused("an unknown output" "${out}/show.json: no output named 'nope' (outputs: mirror, flat)"
               --viewport "${out}/show.json#nope" --out "${out}/nope")
expect_refused("a folder under a file" "${out}/show.json/hw: cannot create the export folder"
               --viewport "${out}/show.json" --out "${out}/show.json/hw")
expect_refused("a fisheye as sl" "output 'mirror': the MPCDI sl profile describes a pinhole projector"
               --viewport "${out}/show.json#mirror" --out "${out}/sl-mirror" --mpcdi-profile sl)
expect_refused("an unknown profile" "--mpcdi-profile"
               --viewport "${out}/show.json#flat" --out "${out}/a3" --mpcdi-profile a3)
file(REMOVE_RECURSE "${out}")
