# `zenith show plan` for shows by date and place (docs/shows.md, "Eclipses"):
# one whose sky passes through the total eclipse of 2017-08-21 at NASA's point
# of greatest eclipse names it (maximum within seconds of NASA's 18:25:32
# UTC) and its totality; one a day later has none, which is not an error, and the plan says no
# other is seen from there within its five years of search; and the next lunar
# eclipse seen from there; and the lunar eclipse show holds its eclipse.
include("${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake")
set(dir "${WORK_DIR}/show-plan-eclipse")
file(REMOVE_RECURSE "${dir}")
file(MAKE_DIRECTORY "${dir}")
foreach(case "during;2017-08-21T18:00:00Z" "after;2017-08-22T00:00:00Z")
  list(GET case 0 name)
  list(GET case 1 start)
  file(WRITE "${dir}/${name}.json"
       "{\"zenith_show\": 1, \"name\": \"eclipse-${name}\", "
       "\"scene\": \"${SOURCE_DIR}/configs/scenes/earth-eclipse-2017-totality.json\", \"fps\": 30, "
       "\"time\": {\"start\": \"${start}\", \"time_rate\": 60, \"end_s\": 60}}\n")
endforeach()
# The plan of show NAME into `out`; fails the test if the command does.
function(show_plan name out)
  execute_process(COMMAND ${ZENITH} show plan --show "${dir}/${name}.json" --tables small
                  RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "show plan of ${name}.json failed (${rc}):\n${stdout}\n${err}")
  endif()
  set(${out} "${stdout}" PARENT_SCOPE)
endfunction()

show_plan(during stdout)
# Totality there 2 min 40 s by NASA (its Moon 0.8 km smaller than our 1 737.4 km: ours ~2 s longer).
foreach(needle "holds a total solar eclipse, maximum 2017-08-21 18:25:" "the Sun 63.9° up"
               "contacts 2017-08-21 16:56:0" "totality 2017-08-21 18:24:" "(2 min 4")
  expect_mentions("${stdout}" "${needle}" "the plan")
endforeach()
show_plan(after stdout)
expect_mentions("${stdout}" "eclipse: none at 36.9667°, -87.6667° during the show's sky time" "the plan")
expect_mentions("${stdout}" "none seen from there within 5 years" "the plan")
# The next lunar eclipse seen from there: 2018-01-31, total (NASA: greatest 13:29:50, umbral magnitude 1.316),
# the Moon setting in Kentucky during it.
expect_mentions("${stdout}" "lunar eclipse: the next one seen from there: a total lunar eclipse, maximum 2018-01-31 13:29:"
                "the plan")
# The lunar eclipse show (configs/shows/earth-lunar-eclipse-2029-buenos-aires.json) holds its eclipse: NASA's
# greatest eclipse 03:22:05 UTC, umbral magnitude 1.8452, totality 02:31:18–04:13:01, the Moon high over Buenos Aires.
execute_process(COMMAND ${ZENITH} show plan --show "${SOURCE_DIR}/configs/shows/earth-lunar-eclipse-2029-buenos-aires.json"
                        --tables small
                RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "show plan of the lunar eclipse show failed (${rc}):\n${stdout}\n${err}")
endif()
foreach(needle "lunar eclipse: the show's sky holds a total lunar eclipse, maximum 2029-06-26 03:22:"
               "umbral magnitude 1.84" "the Moon 76." "totality 2029-06-26 02:31:" "– 2029-06-26 04:13:")
  expect_mentions("${stdout}" "${needle}" "the lunar eclipse show's plan")
endforeach()
