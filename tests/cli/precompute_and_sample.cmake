# `zenith precompute` and `zenith sample` end to end, with a private cache directory.
set(cache "${WORK_DIR}/cli-cache")
file(REMOVE_RECURSE "${cache}")

execute_process(COMMAND ${ZENITH} precompute --atmosphere mars --tables small --cpu --orders 2 --cache "${cache}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "precompute failed (${rc}): ${err}")
endif()
foreach(needle "lut hash" "computed on CPU" "single scattering" "orders used     2" "cached in")
  string(FIND "${out}" "${needle}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "precompute output lacks '${needle}':\n${out}")
  endif()
endforeach()

# Second run: the same table set comes from the cache.
execute_process(COMMAND ${ZENITH} precompute --atmosphere mars --tables small --cpu --orders 2 --cache "${cache}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(FIND "${out}" "source          cache" pos)
if(NOT rc EQUAL 0 OR pos EQUAL -1)
  message(FATAL_ERROR "second precompute did not use the cache:\n${out}\n${err}")
endif()

# Table-based and reference radiance: CSV with a header and one row per direction.
file(WRITE "${WORK_DIR}/directions.csv" "zenith_deg,azimuth_deg\n0,0\n45,180\n")
foreach(method lut reference)
  execute_process(COMMAND ${ZENITH} sample --atmosphere mars --tables small --cpu --orders 2 --cache "${cache}"
                          --method ${method} --samples 200 --sun-zenith-deg 40 --directions "${WORK_DIR}/directions.csv"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX MATCHALL "\n" lines "${out}")
  list(LENGTH lines n)
  string(FIND "${out}" "zenith_deg,azimuth_deg,L_rel_680nm_per_sr" pos)
  if(NOT rc EQUAL 0 OR NOT n EQUAL 3 OR NOT pos EQUAL 0)
    message(FATAL_ERROR "sample --method ${method} (${rc}):\n${out}\n${err}")
  endif()
endforeach()

# A malformed directions file is rejected naming the file and the line.
file(WRITE "${WORK_DIR}/bad-directions.csv" "0,0\n200,0\n")
execute_process(COMMAND ${ZENITH} sample --atmosphere mars --cache "${cache}" --directions "${WORK_DIR}/bad-directions.csv"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(FIND "${err}" "line 2" pos)
if(rc EQUAL 0 OR pos EQUAL -1)
  message(FATAL_ERROR "bad directions not reported (${rc}): ${err}")
endif()
file(REMOVE_RECURSE "${cache}")
