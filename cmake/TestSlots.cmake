# How ctest shares the machine's cores among the tests.
#
# scripts/test runs `ctest --parallel <2 × cores>`: a core is two slots. A test
# takes both slots of a core (PROCESSORS 2), as it took a core when the suite
# ran one test per core. A test that spends most of its time waiting on the
# wall clock (a show paced in real time, a node's restart, a silence limit to
# run out) is marked `PROCESSORS ${ZENITH_TEST_WAITING_SLOTS}` where it is
# declared, with its measured share of a core beside it: two such tests share a
# core. So the cores are never asked for more than the suite asked them for
# before, and the waiting no longer leaves one idle.
set(ZENITH_TEST_CORE_SLOTS 2)
set(ZENITH_TEST_WAITING_SLOTS 1)

# Gives every test of the current directory that names no PROCESSORS a core's
# slots. Tests discovered from a GoogleTest executable are set where they are
# declared (zenith_add_gtest), since they exist only once ctest reads them.
function(zenith_tests_take_a_core)
  get_property(tests DIRECTORY PROPERTY TESTS)
  foreach(test IN LISTS tests)
    get_test_property(${test} PROCESSORS slots)
    if(NOT slots)
      set_tests_properties(${test} PROPERTIES PROCESSORS ${ZENITH_TEST_CORE_SLOTS})
    endif()
  endforeach()
endfunction()

# Call at the top of a CMakeLists.txt that adds tests: its tests get their
# slots once the whole file has been read.
macro(zenith_test_directory)
  cmake_language(DEFER CALL zenith_tests_take_a_core)
endmacro()
