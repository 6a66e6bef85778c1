# `zenith precompute` and `zenith sample` end to end, with a private cache directory.
set(cache "${WORK_DIR}/cli-cache")
file(REMOVE_RECURSE "${cache}")

# `zenith sample ARGN` must fail with `needle` in its error output.
function(expect_sample_refused needle)
  execute_process(COMMAND ${ZENITH} sample ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(FIND "${err}" "${needle}" pos)
  if(rc EQUAL 0 OR pos EQUAL -1)
    message(FATAL_ERROR "sample ${ARGN} not refused with '${needle}' (${rc}):\n${out}\n${err}")
  endif()
endfunction()

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

# The sky's colour (--colour): the earth-advanced preset at 16 wavelengths, 380-755 nm; the blue zenith with the
# sun 30 degrees from it lies between 10 000 and 20 000 K (13 400 K with these tables, 12 500 K with the paper
# tables and the sun 61 degrees up, docs/rendering.md "Eclipses").
file(READ "${SOURCE_DIR}/configs/atmospheres/earth-advanced.json" earth)
string(JSON earth SET "${earth}" wavelengths_nm "[380, 405, 430, 455, 480, 505, 530, 555, 580, 605, 630, 655, 680, 705, 730, 755]")
file(WRITE "${WORK_DIR}/earth-16.json" "${earth}")
execute_process(COMMAND ${ZENITH} sample --atmosphere "${WORK_DIR}/earth-16.json" --tables small --orders 2 --cache "${cache}"
                        --sun-zenith-deg 30 --grid 1x1 --colour
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH ",Y_cd_m2,x,y,CCT_K,Duv,T_eff_K\n0,0,[^\n]*,([0-9.]+),(-?[0-9.e-]+),([0-9.]+)\n" row "${out}")
if(NOT rc EQUAL 0 OR NOT row OR CMAKE_MATCH_1 LESS 10000 OR CMAKE_MATCH_1 GREATER 20000 OR CMAKE_MATCH_3 LESS 9000
   OR CMAKE_MATCH_3 GREATER 20000)
  message(FATAL_ERROR "sample --colour: no zenith CCT and effective temperature within 10 000 (9 000)-20 000 K "
                      "(${rc}):\n${out}\n${err}")
endif()
# --colour-band-nm reaches the fit: 720-800 nm holds two of the 16 wavelengths (730, 755), too few for a
# temperature; a band whose ends are reversed is refused before any table is read.
foreach(band_and_needle "720,800|wavelengths_nm: --colour-band-nm 720,800 holds 2 of the wavelengths" "665,525|--colour-band-nm 665,525: the band's first")
  string(REPLACE "|" ";" band_and_needle "${band_and_needle}")
  list(GET band_and_needle 0 band)
  list(GET band_and_needle 1 needle)
  execute_process(COMMAND ${ZENITH} sample --atmosphere "${WORK_DIR}/earth-16.json" --tables small --orders 2
                          --cache "${cache}" --sun-zenith-deg 30 --grid 1x1 --colour --colour-band-nm ${band}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(FIND "${err}" "${needle}" pos)
  if(rc EQUAL 0 OR pos EQUAL -1)
    message(FATAL_ERROR "sample --colour-band-nm ${band} not refused with '${needle}' (${rc}):\n${out}\n${err}")
  endif()
endforeach()
# Three wavelengths make no colour; a transmittance has none.
expect_sample_refused("wavelengths_nm: --colour: a spectrum's colour needs at least 16 wavelengths"
                      --atmosphere mars --tables small --cpu --orders 2 --cache "${cache}" --colour)
expect_sample_refused("does not apply to --quantity transmittance"
                      --atmosphere "${WORK_DIR}/earth-16.json" --quantity transmittance --colour --cache "${cache}")
# --polarized is the path tracer's: the tables (scalar) refuse it, the reference method takes it.
expect_sample_refused("--polarized is the reference solver's vector radiative transfer; it needs --method reference"
                      --atmosphere mars --cache "${cache}" --grid 1x1 --polarized)
execute_process(COMMAND ${ZENITH} sample --atmosphere mars --method reference --samples 2000 --grid 1x1 --polarized
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "\n0,0,[0-9.e-]+,")
  message(FATAL_ERROR "sample --method reference --polarized failed (${rc}):\n${out}\n${err}")
endif()
# --stokes is the path tracer's polarization: scalar transfer refuses it; in vector transfer each row gains
# Q, U, the degree P with its standard error and the angle chi per wavelength, the degree within [0, 1].
expect_sample_refused("--stokes is the polarization of the sky's radiance in the reference solver's vector transfer; it needs --method reference --polarized"
                      --atmosphere mars --method reference --samples 200 --grid 1x1 --stokes)
execute_process(COMMAND ${ZENITH} sample --atmosphere mars --method reference --samples 2000 --grid 1x1 --polarized
                        --stokes --sun-zenith-deg 60
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES ",Q_rel_[0-9]+nm_per_sr,.*,U_rel_.*,P_[0-9]+nm,.*,se_P_.*,chi_[0-9]+nm_deg,")
  message(FATAL_ERROR "sample --polarized --stokes: no polarization columns (${rc}):\n${out}\n${err}")
endif()
string(REGEX MATCH "^[^\n]*" header "${out}")
string(REGEX MATCH "\n0,0,[^\n]*" row "${out}")
string(STRIP "${row}" row)
string(REPLACE "," ";" names "${header}")
string(REPLACE "," ";" cells "${row}")
set(degree "")
list(LENGTH names column_count)
math(EXPR last_column "${column_count} - 1")
foreach(column RANGE 0 ${last_column})
  list(GET names ${column} name)
  if(name MATCHES "^P_[0-9]+nm$")
    list(GET cells ${column} degree)
    set(degree_column ${column})
    break()
  endif()
endforeach()
if(NOT degree MATCHES "^0\\.[0-9]+$" AND NOT degree MATCHES "^[0-9.]+e-[0-9]+$")
  message(FATAL_ERROR "sample --stokes: the zenith's degree of polarization '${degree}' is not within [0, 1):\n${out}")
endif()
# --aerosol-depolarizes bounds the aerosols' share of vector transfer: refused in scalar transfer; with
# --polarized the Martian dust then sends its light on unpolarized, and the zenith's degree falls.
expect_sample_refused("--aerosol-depolarizes bounds the aerosols' share of the reference solver's vector transfer; it needs --method reference --polarized"
                      --atmosphere mars --method reference --samples 200 --grid 1x1 --aerosol-depolarizes)
execute_process(COMMAND ${ZENITH} sample --atmosphere mars --method reference --samples 2000 --grid 1x1 --polarized
                        --stokes --sun-zenith-deg 60 --aerosol-depolarizes
                RESULT_VARIABLE rc OUTPUT_VARIABLE depolarized_out ERROR_VARIABLE err)
string(REGEX MATCH "\n0,0,[^\n]*" depolarized_row "${depolarized_out}")
string(STRIP "${depolarized_row}" depolarized_row)
string(REPLACE "," ";" depolarized_cells "${depolarized_row}")
list(GET depolarized_cells ${degree_column} depolarized_degree)
if(NOT rc EQUAL 0 OR NOT depolarized_degree LESS degree)
  message(FATAL_ERROR "sample --aerosol-depolarizes: the zenith's degree ${depolarized_degree} is not below "
                      "${degree} (${rc}):\n${depolarized_out}\n${err}")
endif()
# --reference-orders splits the path tracer's light by order: the tables refuse it, a first order above the
# last is refused naming both.
expect_sample_refused("--reference-orders splits the reference solver's light by order; it needs --method reference"
                      --atmosphere mars --cache "${cache}" --grid 1x1 --reference-orders 2,2)
expect_sample_refused("--reference-orders 3,2: the first order must be at least 1 and not above the last"
                      --atmosphere mars --method reference --samples 200 --grid 1x1 --reference-orders 3,2)

# --shadow-passes and --scalar-shadow shape the Moon's shadow over the tables: without an eclipse they are
# refused, and passes out of [1, 4] are refused naming the option.
expect_sample_refused("--shadow-passes and --scalar-shadow shape the Moon's shadow over the tables; they need --method lut and --eclipse-at"
                      --atmosphere mars --cache "${cache}" --grid 1x1 --shadow-passes 1)
expect_sample_refused("--shadow-passes"
                      --atmosphere mars --cache "${cache}" --grid 1x1 --shadow-passes 5)

# A malformed directions file is rejected naming the file and the line.
file(WRITE "${WORK_DIR}/bad-directions.csv" "0,0\n200,0\n")
expect_sample_refused("line 2"
                      --atmosphere mars --cache "${cache}" --directions "${WORK_DIR}/bad-directions.csv")
file(REMOVE_RECURSE "${cache}")
