# Runs a libFuzzer target for a bounded time on a fresh seed corpus.
# -DFUZZER=exe -DCORPUS_TOOL=exe -DWORK_DIR=dir [-DMAX_TOTAL_TIME_S=60]
if(NOT MAX_TOTAL_TIME_S)
  set(MAX_TOTAL_TIME_S 60)
endif()
set(seeds "${WORK_DIR}/seeds")
set(corpus "${WORK_DIR}/corpus")      # grows across runs (kept in the build tree)
set(artifacts "${WORK_DIR}/artifacts/")
file(REMOVE_RECURSE "${seeds}")
file(MAKE_DIRECTORY "${corpus}" "${artifacts}")
execute_process(COMMAND "${CORPUS_TOOL}" "${seeds}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "seed corpus generation failed (${rc})")
endif()
execute_process(COMMAND "${FUZZER}" "${corpus}" "${seeds}" -max_total_time=${MAX_TOTAL_TIME_S} -max_len=8192
                        -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 "-artifact_prefix=${artifacts}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${FUZZER} failed (${rc}); the crashing input is in ${artifacts}")
endif()
