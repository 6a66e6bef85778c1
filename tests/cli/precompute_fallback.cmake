# A GPU precompute whose program the driver refuses falls back to the CPU with
# one warning naming the program and the driver (render/lut/table_provider.cpp),
# for `zenith precompute` and for `zenith render` (a show must still start).
# ZENITH_FAIL_SHADER makes one program fail to compile, as a driver would
# refuse it: the zenith command line of the test binary
# ZENITH_WITH_SHADER_FAULTS (tests/cli/zenith_with_shader_faults.cpp).
set(cache "${WORK_DIR}/fallback-cache")
file(REMOVE_RECURSE "${cache}")

function(expect_one_fallback_warning program err)
  string(REPLACE ";" "," err "${err}")  # a CMake list separator inside a match would split it
  string(REGEX MATCHALL "GPU precompute: shader program '${program}' does not build on this driver \\(GL_VENDOR '[^']+', GL_RENDERER '[^']+', GL_VERSION '[^']+'\\)[^\n]*ZENITH_FAIL_SHADER[^\n]*precomputing on the CPU instead"
         warnings "${err}")
  list(LENGTH warnings n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "expected one fallback warning naming ${program} and the driver, got ${n}:\n${err}")
  endif()
endfunction()

execute_process(COMMAND ${CMAKE_COMMAND} -E env ZENITH_FAIL_SHADER=harmonic_density.comp
                        ${ZENITH_WITH_SHADER_FAULTS} precompute --atmosphere mars --tables small --orders 2 --cache "${cache}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "precompute with a refused program failed (${rc}):\n${out}\n${err}")
endif()
expect_one_fallback_warning("harmonic_density.comp" "${err}")
foreach(needle "computed on CPU" "orders used     2" "cached in")
  string(FIND "${out}" "${needle}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "precompute output lacks '${needle}':\n${out}")
  endif()
endforeach()

# A render whose tables are missing: the first program of the precompute is refused.
execute_process(COMMAND ${CMAKE_COMMAND} -E env ZENITH_FAIL_SHADER=transmittance.comp
                        ${ZENITH_WITH_SHADER_FAULTS} render --scene "${SOURCE_DIR}/configs/scenes/earth-sunset.json" --projection planar
                        --size 32x18 --tables small --orders 2 --cache "${cache}" --out "${WORK_DIR}/fallback.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${WORK_DIR}/fallback.png")
  message(FATAL_ERROR "render with a refused precompute program failed (${rc}):\n${out}\n${err}")
endif()
expect_one_fallback_warning("transmittance.comp" "${err}")
file(REMOVE_RECURSE "${cache}")
file(REMOVE "${WORK_DIR}/fallback.png")
