# Checks that every C++ source of the project is formatted by .clang-format:
# `clang-format --dry-run --Werror` over the project's folders.
# Run by ctest as style.clang_format; by hand:
#   cmake -DCLANG_FORMAT=/usr/bin/clang-format -DSOURCE_DIR=$PWD -P scripts/check-format.cmake
# Fix what it reports with scripts/format (clang-format -i on the same files).
#
# The style file is read by clang-format 14 (Debian 12's, installed by
# scripts/bootstrap); other major versions format some constructs differently,
# so with another version the check says so and is skipped (ctest:
# SKIP_REGULAR_EXPRESSION) rather than failing on code that is formatted.
if(NOT CLANG_FORMAT)
  message(FATAL_ERROR "clang-format not found: scripts/bootstrap installs it (Debian package clang-format)")
endif()
execute_process(COMMAND "${CLANG_FORMAT}" --version OUTPUT_VARIABLE version)
if(NOT version MATCHES "version 14\\.")
  message("style check skipped: ${CLANG_FORMAT} is not clang-format 14 (${version})")
  return()
endif()
set(folders apps astro atmosphere bench cluster core image offline render scene show stress tests warp)
set(files "")
foreach(folder IN LISTS folders)
  file(GLOB_RECURSE found LIST_DIRECTORIES false "${SOURCE_DIR}/${folder}/*.cpp" "${SOURCE_DIR}/${folder}/*.h")
  list(APPEND files ${found})
endforeach()
list(LENGTH files count)
if(count LESS 100)
  message(FATAL_ERROR "only ${count} C++ files under ${SOURCE_DIR}: is SOURCE_DIR the repository root?")
endif()
# In batches, to keep each command line short.
set(unformatted "")
set(batch "")
list(APPEND files "")  # flushes the last batch
foreach(f IN LISTS files)
  if(f)
    list(APPEND batch "${f}")
    list(LENGTH batch n)
  endif()
  if((NOT f AND batch) OR n GREATER_EQUAL 80)
    execute_process(COMMAND "${CLANG_FORMAT}" --dry-run --Werror --style=file ${batch}
                    RESULT_VARIABLE rc ERROR_VARIABLE messages OUTPUT_QUIET)
    if(NOT rc EQUAL 0)
      string(REGEX MATCHALL "[^\n]*: error: code should be clang-formatted" lines "${messages}")
      foreach(line IN LISTS lines)
        string(REGEX REPLACE ":[0-9]+:[0-9]+: error: code should be clang-formatted" "" file "${line}")
        file(RELATIVE_PATH rel "${SOURCE_DIR}" "${file}")
        list(APPEND unformatted "${rel}")
      endforeach()
      if(NOT lines)
        message(FATAL_ERROR "clang-format failed (exit ${rc}):\n${messages}")
      endif()
    endif()
    set(batch "")
    set(n 0)
  endif()
endforeach()
list(REMOVE_DUPLICATES unformatted)
if(unformatted)
  list(LENGTH unformatted bad)
  list(JOIN unformatted "\n  " listing)
  message(FATAL_ERROR "${bad} of ${count} C++ files are not formatted by .clang-format (run scripts/format):\n  ${listing}")
endif()
message("${count} C++ files formatted by .clang-format")
