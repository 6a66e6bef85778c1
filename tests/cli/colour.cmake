# `zenith colour` end to end: Planck curves give back their temperatures, the band picks which part of a
# spectrum is fitted, and a malformed file is refused naming the file, the line and the column.

# Planck's law B(λ, T) ∝ λ⁻⁵ / (exp(c₂ / λT) − 1) at 16 wavelengths, 380–755 nm, for 9 100 K and 20 000 K,
# and a spectrum that is the 6 000 K curve up to 580 nm and the 12 000 K curve from 605 nm (scaled by 7, which
# the fit's free scale ignores). Written from the closed form (c₂ = 1.438776877e7 nm K, × 1e15; CMake has no
# exp()).
set(spectrum "# Planck curves (closed form), for tests/cli/colour.cmake
wavelength_nm,planck_9100,planck_20000,split_6000_12000
380,1.99954499,22.3766457,0.229767844
405,1.88858028,18.6999756,0.246877003
430,1.76572564,15.7166342,0.25846065
455,1.63862488,13.2842348,0.265059738
480,1.51249037,11.290579,0.26737114
505,1.39070324,9.64758065,0.266135071
530,1.27531519,8.28609418,0.262064552
555,1.16744126,7.15173142,0.25580621
580,1.06755488,6.20156756,0.247922557
605,0.975703063,5.40158268,13.8052976
630,0.891660099,4.72468789,12.3592288
655,0.815035112,4.14920631,11.0867959
680,0.745346044,3.65770368,9.96567616
705,0.682069519,3.23608647,8.97633966
730,0.624673655,2.87290409,8.10179071
755,0.572638944,2.55880709,7.32728911
")
file(WRITE "${WORK_DIR}/colour-planck.csv" "${spectrum}")

function(colour_rows band out_var)
  execute_process(COMMAND ${ZENITH} colour --spectrum "${WORK_DIR}/colour-planck.csv" ${band}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "zenith colour ${band} failed (${rc}): ${err}")
  endif()
  set(${out_var} "${out}" PARENT_SCOPE)
endfunction()

# T_eff_K is the last cell of a column's row.
function(expect_effective_temperature out column low high)
  string(REGEX MATCH "\n${column},[^\n]*,([0-9]+)\n" row "${out}")
  if(NOT row OR CMAKE_MATCH_1 LESS low OR CMAKE_MATCH_1 GREATER high)
    message(FATAL_ERROR "zenith colour: ${column}'s effective temperature not within ${low}-${high} K:\n${out}")
  endif()
endfunction()

colour_rows("" out)
string(FIND "${out}" "column,x,y,CCT_K,Duv,T_eff_K\n" pos)
if(NOT pos EQUAL 0)
  message(FATAL_ERROR "zenith colour: unexpected header:\n${out}")
endif()
expect_effective_temperature("${out}" planck_9100 9095 9105)
expect_effective_temperature("${out}" planck_20000 19980 20020)
# The correlated colour temperature of a Planck curve is its temperature, to the 25-nm sampling's few %.
string(REGEX MATCH "\nplanck_9100,0\\.[0-9]+,0\\.[0-9]+,([0-9]+)," row "${out}")
if(NOT row OR CMAKE_MATCH_1 LESS 8800 OR CMAKE_MATCH_1 GREATER 9400)
  message(FATAL_ERROR "zenith colour: the 9 100 K curve's CCT is not within 8 800-9 400 K:\n${out}")
endif()
# The band decides which half of the split spectrum is fitted.
colour_rows("--band-nm;380,580" out)
expect_effective_temperature("${out}" split_6000_12000 5995 6005)
colour_rows("--band-nm;605,755" out)
expect_effective_temperature("${out}" split_6000_12000 11990 12010)

# Bad input: each refused, naming where.
function(expect_refused name text needle)
  file(WRITE "${WORK_DIR}/colour-${name}.csv" "${text}")
  execute_process(COMMAND ${ZENITH} colour --spectrum "${WORK_DIR}/colour-${name}.csv" ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(FIND "${err}" "${needle}" pos)
  if(rc EQUAL 0 OR pos EQUAL -1)
    message(FATAL_ERROR "zenith colour (${name}) not refused with '${needle}' (${rc}):\n${out}\n${err}")
  endif()
endfunction()
expect_refused(header "nm,a\n500,1\n" "colour-header.csv: header: expected 'wavelength_nm'")
expect_refused(order "wavelength_nm,a\n500,1\n400,2\n" "colour-order.csv, line 3, column wavelength_nm: the wavelengths must increase")
expect_refused(number "wavelength_nm,a\n500,1\n600,x\n" "colour-number.csv, line 3, column a:")
expect_refused(negative "wavelength_nm,a\n500,1\n600,-2\n" "colour-negative.csv, line 3, column a:")
expect_refused(band "${spectrum}" "column planck_9100: effective blackbody temperature" --band-nm 700,720)
expect_refused(reversed "${spectrum}" "--band-nm 600,500: the band's first wavelength must be below its last"
               --band-nm 600,500)
