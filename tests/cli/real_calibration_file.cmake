# A real calibration file from another tool (tests/data/warp/README.md) loaded
# through its viewport config and rendered: `zenith render --viewport
# REAL_FILE.viewport.json#p1` must write the output's frame, at the size the
# config gives, with no warp refused. The Evans & Sutherland archives' color="TBD"
# is reported once, naming the file and the value.
include("${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake")
set(cache "${WORK_DIR}/cache")  # shared with cli.render: tables computed once
set(out "${WORK_DIR}/real-file-${REAL_FILE}")
file(REMOVE_RECURSE "${out}")
set(config "${SOURCE_DIR}/tests/data/warp/${REAL_FILE}.viewport.json")

execute_process(COMMAND ${ZENITH} render --scene "${SOURCE_DIR}/configs/scenes/earth-ground-noon.json"
                        --viewport "${config}#p1" --tables small --cache "${cache}" --out "${out}/p1.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${out}/p1.png")
  message(FATAL_ERROR "${REAL_FILE}: render failed (${rc}):\n${stdout}\n${err}")
endif()
string(FIND "${stdout}${err}" "cannot use the warp" refused)
if(NOT refused EQUAL -1)
  message(FATAL_ERROR "${REAL_FILE}: a warp was refused:\n${stdout}\n${err}")
endif()

file(READ "${config}" config_text)
string(JSON width GET "${config_text}" outputs 0 size 0)
string(JSON height GET "${config_text}" outputs 0 size 1)
expect_png_size("${out}/p1.png" ${width} ${height} "${REAL_FILE} p1.png")

if(REAL_FILE MATCHES "^es-")
  string(REGEX MATCHALL "attribute 'color' = 'TBD'" tbd "${stdout}${err}")
  list(LENGTH tbd count)
  if(NOT count EQUAL 1)
    message(FATAL_ERROR "${REAL_FILE}: expected one warning about color=\"TBD\", got ${count}:\n${stdout}\n${err}")
  endif()
  expect_mentions("${stdout}${err}" ".mpcdi:mpcdi" "the TBD warning")
endif()
file(REMOVE_RECURSE "${out}")
