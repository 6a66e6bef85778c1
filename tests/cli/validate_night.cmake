# `zenith validate night` end to end with small tables (docs/night-sky.md): every
# check within its published tolerance (the command exits 1 otherwise), the
# report names its sources, the CSV, gnuplot script and PNG charts are written,
# and a bad option is refused.
include("${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake")
set(cache "${WORK_DIR}/cache")  # shared with cli.render and cli.validate_cie: small tables computed once
set(out "${WORK_DIR}/validate-night-out")
file(REMOVE_RECURSE "${out}")

execute_process(COMMAND ${ZENITH} validate night --tables small --cache "${cache}" --out "${out}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
message(STATUS "${stdout}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "validate night failed (${rc}):\n${stdout}\n${err}")
endif()
foreach(needle "NREL SPA example" "Meeus ex. 47.a" "Bennett 1982" "Pickering 2002 air mass"
               "Patat et al. 2006" "Schaefer 1990" " 0 outside their tolerance")
  string(FIND "${stdout}" "${needle}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "the report does not mention '${needle}':\n${stdout}")
  endif()
endforeach()
foreach(f night_twilight.csv night_refraction.csv night.gp)
  if(NOT EXISTS "${out}/${f}")
    message(FATAL_ERROR "validate night did not write ${f}")
  endif()
endforeach()
find_program(GNUPLOT gnuplot)
if(GNUPLOT)
  foreach(png night_twilight.png night_limiting_magnitude.png night_refraction.png)
    file(READ "${out}/${png}" png_head LIMIT 8 HEX)
    if(NOT png_head STREQUAL "89504e470d0a1a0a")
      message(FATAL_ERROR "${png} is missing or not a PNG although gnuplot is installed")
    endif()
  endforeach()
endif()
expect_zenith_refuses("--tables" validate night --tables huge --out "${out}")
