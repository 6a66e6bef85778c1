# `zenith show render` end to end (docs/shows.md, "Offline rendering"), on a
# 6-frame show with two table sets (tests/data/shows/offline-sunset.json),
# 48x48 fisheye frames, small tables in a private cache:
#   1. two renders into two folders give byte-identical files;
#   2. a resume re-renders exactly a deleted and a corrupted frame;
#   3. an interrupted render (--to 2, plus a file written but never recorded)
#      completes with only the missing frames;
#   4. a changed frame rate re-renders exactly the frames whose state changed,
#      a dropped format nothing;
#   5. a viewport config's outputs get a folder each;
#   6. bad arguments are refused with a message naming the argument;
#   7. the pipeline (writer threads, frames in flight) writes the simple path's
#      bytes (--threads 0) in every format, with a frame-name pattern;
#   8. a render killed with SIGKILL mid-show leaves only whole frames under
#      their names and resumes to the same bytes;
#   9. a file that cannot be written stops the render with an error naming it,
#      and the frames before it stay valid.
include("${CMAKE_CURRENT_LIST_DIR}/cli_checks.cmake")
set(cache "${WORK_DIR}/cache")  # shared with cli.render: tables computed once
set(root "${WORK_DIR}/show-render-out")
set(show "${SOURCE_DIR}/tests/data/shows/offline-sunset.json")
file(REMOVE_RECURSE "${root}")
set(dome --projection fisheye --size 48x48 --tables small --cache "${cache}")

# Runs `zenith show render --show SHOW ARGN`; fails unless it succeeds and its
# stdout contains `summary`.
function(render_show summary)
  execute_process(COMMAND ${ZENITH} show render --show "${show}" ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  string(FIND "${o}" "${summary}" pos)
  if(NOT rc EQUAL 0 OR pos EQUAL -1)
    message(FATAL_ERROR "show render ${ARGN}: expected success and '${summary}', got (${rc}):\n${o}\n${e}")
  endif()
  set(last_stdout "${o}" PARENT_SCOPE)
  set(last_stderr "${e}" PARENT_SCOPE)
endfunction()

# Fails unless folders `a` and `b` hold the same bytes in each file ARGN (paths relative to both).
function(expect_same_files a b)
  foreach(f ${ARGN})
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${a}/${f}" "${b}/${f}" RESULT_VARIABLE differ)
    if(NOT differ EQUAL 0)
      message(FATAL_ERROR "${a}/${f} and ${b}/${f} differ (or one is missing)")
    endif()
  endforeach()
endfunction()

# Fails unless folders `a` and `b` hold the same PNG and EXR of frames `first`..`last` of the fisheye output.
function(expect_identical a b output first last)
  fisheye_files(pngs png ${first} ${last})
  fisheye_files(exrs exr ${first} ${last})
  expect_same_files("${a}" "${b}" ${pngs} ${exrs})
endfunction()

# Sets `out` to the fisheye files of frames `first`..`last` with extension `ext` (default names).
function(fisheye_files out ext first last)
  set(files "")
  foreach(frame RANGE ${first} ${last})
    string(LENGTH "${frame}" digits)
    math(EXPR pad "6 - ${digits}")
    string(REPEAT "0" ${pad} zeros)
    list(APPEND files "fisheye/fisheye.${zeros}${frame}.${ext}")
  endforeach()
  set(${out} "${files}" PARENT_SCOPE)
endfunction()

# 1. Deterministic: the same frames twice, byte for byte (contact sheet included).
render_show("rendered 6, skipped 0 of 6 frames" ${dome} --format png,exr --out "${root}/a")
string(FIND "${last_stdout}" "2 lookup-table sets for 6 frames at 2 fps" pos)
if(pos EQUAL -1)
  message(FATAL_ERROR "show render did not print the table plan first:\n${last_stdout}")
endif()
# The start-up breakdown, at info level, once the first frame is on its way (its one table set).
string(REGEX MATCH "start-up [0-9.]+ s to the first frame: GL context [0-9.]+ s, tables precomputed [0-9.]+ s, tables loaded and uploaded [0-9.]+ s \\(1 set\\), programs [0-9.]+ s \\([1-9][0-9]* built, [0-9]+ from stored binaries\\)" startup "${last_stdout}${last_stderr}")
if(NOT startup)
  message(FATAL_ERROR "show render did not log where its start went:\n${last_stdout}\n${last_stderr}")
endif()
# The renderer's programs built one at a time (--serial-compile) give the same
# bytes; a one-frame render allocates one readback slot of the five it may hold.
render_show("rendered 1, skipped 0 of 1 frames" ${dome} --format png,exr --to 0 --serial-compile --threads 3
            --frames-in-flight 5 --out "${root}/serial")
expect_identical("${root}/a" "${root}/serial" fisheye 0 0)
foreach(line "one at a time (serial" "pipeline: 1 of at most 5 readback slots allocated")
  string(FIND "${last_stdout}${last_stderr}" "${line}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "show render --serial-compile --frames-in-flight 5: no '${line}' in:\n${last_stdout}\n${last_stderr}")
  endif()
endforeach()
# (b through the simple path, one frame at a time on one thread: the same bytes as a's pipeline)
render_show("rendered 6, skipped 0 of 6 frames" ${dome} --format png,exr --threads 0 --out "${root}/b")
expect_identical("${root}/a" "${root}/b" fisheye 0 5)
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${root}/a/contact-sheet.png" "${root}/b/contact-sheet.png"
                RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "the two contact sheets differ")
endif()
# 6 frames of 48x48 cells, round(sqrt(6)) = 2 columns, 3 rows, 4 px gaps: 108 x 160.
expect_png_size("${root}/a/contact-sheet.png" 108 160 "contact-sheet.png")
foreach(f manifest.json.partial fisheye/fisheye.000000.png.partial)
  if(EXISTS "${root}/a/${f}")
    message(FATAL_ERROR "${f} left behind")
  endif()
endforeach()

# Nothing to do when everything is verified.
render_show("rendered 0, skipped 6 of 6 frames" ${dome} --format png,exr --out "${root}/a")

# 2. Resume: one frame's file deleted, another's bytes corrupted (same size):
#    exactly those two frames are rendered again, and come back identical.
file(REMOVE "${root}/a/fisheye/fisheye.000002.png")
file(SIZE "${root}/a/fisheye/fisheye.000004.exr" exr_size)
string(REPEAT "x" ${exr_size} garbage)
file(WRITE "${root}/a/fisheye/fisheye.000004.exr" "${garbage}")
render_show("rendered 2, skipped 4 of 6 frames" ${dome} --format png,exr --out "${root}/a")
foreach(needle "frame 2: rendering again: fisheye/fisheye.000002.png: missing"
               "frame 4: rendering again: fisheye/fisheye.000004.exr: changed on disk")
  string(FIND "${last_stderr}" "${needle}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "the resume did not report '${needle}':\n${last_stderr}")
  endif()
endforeach()
expect_identical("${root}/a" "${root}/b" fisheye 0 5)

# 3. Interrupted: frames 0-2 only, then a frame written but never recorded in
#    the manifest (killed before the update): the full run renders 3, 4 and 5.
render_show("rendered 3, skipped 0 of 3 frames" ${dome} --format png,exr --to 2 --contact-sheet none --out "${root}/c")
if(EXISTS "${root}/c/contact-sheet.png" OR EXISTS "${root}/c/fisheye/fisheye.000003.png")
  message(FATAL_ERROR "--to 2 --contact-sheet none wrote more than frames 0-2")
endif()
file(COPY "${root}/b/fisheye/fisheye.000003.png" DESTINATION "${root}/c/fisheye")
render_show("rendered 3, skipped 3 of 6 frames" ${dome} --format png,exr --out "${root}/c")
expect_identical("${root}/c" "${root}/b" fisheye 0 5)

# 4. Another frame rate: at 4 fps frame 0 is the same state (show time 0), the
#    other ten are new; dropping the EXR invalidates no frame.
render_show("rendered 10, skipped 1 of 11 frames" ${dome} --format png,exr --fps 4 --contact-sheet none
            --out "${root}/c")
render_show("rendered 0, skipped 11 of 11 frames" ${dome} --format png --fps 4 --contact-sheet none --out "${root}/c")
render_show("rendered 0, skipped 6 of 6 frames" ${dome} --format png --out "${root}/b")

# 5. A viewport config: each output in its folder; the two halves of one dome master are put back
#    together on the sheet.
file(WRITE "${root}/halves.json" [=[{
  "zenith_viewports": 1,
  "name": "halves",
  "outputs": [
    {"name": "left", "size": [24, 48],
     "projection": {"type": "fisheye", "fov_deg": 180, "centre_x_px": 24, "centre_y_px": 24, "radius_px": 24}},
    {"name": "right", "size": [24, 48],
     "projection": {"type": "fisheye", "fov_deg": 180, "centre_x_px": 0, "centre_y_px": 24, "radius_px": 24}}
  ]
}]=])
render_show("rendered 2, skipped 0 of 2 frames" --viewport "${root}/halves.json" --tables small --cache "${cache}"
            --from 4 --to 5 --out "${root}/v")
foreach(f left/left.000004.png left/left.000005.png right/right.000004.png right/right.000005.png contact-sheet.png)
  if(NOT EXISTS "${root}/v/${f}")
    message(FATAL_ERROR "viewport render did not write ${f}")
  endif()
endforeach()
# 2 frames, each cell the whole 48 x 48 dome (not 24 + 4 + 24 side by side): 1 column, 2 rows: 56 x 108.
expect_png_size("${root}/v/contact-sheet.png" 56 108 "the viewport contact sheet")

# 6. Bad input: each refused with a message naming what is wrong.
function(expect_refused needle)
  expect_zenith_refuses("${needle}" show render ${ARGN})
endfunction()
set(s --show "${show}")
set(x "${root}/refused")
expect_refused("--out is required" ${s} ${dome})
expect_refused("p9" ${s} --viewport "${SOURCE_DIR}/configs/viewports/dome-6-projectors.json#p9" --out "${x}")
expect_refused("--fps 0: must be in (0, 1000]" ${s} ${dome} --fps 0 --out "${x}")
expect_refused("--fps 5000: must be in (0, 1000]" ${s} ${dome} --fps 5000 --out "${x}")
expect_refused("--fps" ${s} ${dome} --fps fast --out "${x}")
expect_refused("--from 4 --to 2" ${s} ${dome} --from 4 --to 2 --out "${x}")
expect_refused("the show's last frame" ${s} ${dome} --to 6 --out "${x}")
expect_refused("--format 'gif'" ${s} ${dome} --format gif --out "${x}")
expect_refused("--frame-name 'f.png'" ${s} ${dome} --frame-name f.png --out "${x}")
expect_refused("--png-compression 'slow'" ${s} ${dome} --png-compression slow --out "${x}")
expect_refused("--threads 300" ${s} ${dome} --threads 300 --out "${x}")
expect_refused("--size" ${s} --projection fisheye --out "${x}")
expect_refused("give one of --cluster FILE" ${s} --size 48x48 --out "${x}")
expect_refused("--viewport" ${s} --viewport "${root}/halves.json" --size 48x48 --out "${x}")
expect_refused("missing.json" --show "${root}/missing.json" ${dome} --out "${x}")
expect_refused("--show is required" ${dome} --out "${x}")
# --video without ffmpeg on PATH: refused before anything is rendered.
execute_process(COMMAND ${CMAKE_COMMAND} -E env PATH=/nonexistent ${ZENITH} show render ${s} ${dome} --video "${x}/v.mp4"
                        --out "${x}" RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
if(rc EQUAL 0 OR NOT "${e}" MATCHES "--video .*v.mp4: ffmpeg is not installed")
  message(FATAL_ERROR "--video without ffmpeg: expected a refusal naming ffmpeg, got (${rc}):\n${o}\n${e}")
endif()
if(EXISTS "${x}")
  message(FATAL_ERROR "a refused render created ${x}")
endif()

# 7. Pipeline = simple path in every format (16-bit PNG, TIFF, float EXR), named by a pattern.
set(all_formats --format png16,tiff,exr --exr-type float --frame-name "sky.%04d.png" --start-number 1 --contact-sheet none)
render_show("rendered 6, skipped 0 of 6 frames" ${dome} ${all_formats} --threads 3 --frames-in-flight 4 --out "${root}/p")
render_show("rendered 6, skipped 0 of 6 frames" ${dome} ${all_formats} --threads 0 --out "${root}/s")
set(pattern_files "")
foreach(n RANGE 1 6)
  list(APPEND pattern_files fisheye/sky.000${n}.png fisheye/sky.000${n}.tif fisheye/sky.000${n}.exr)
endforeach()
expect_same_files("${root}/p" "${root}/s" ${pattern_files})  # the pipeline's files = the simple path's

# 8. kill -9 mid-show: 121 frames at 48 fps; killed once the manifest (rewritten every 2 s) lists
#    frames and 8 are on disk. Every file under a frame's name is whole (equal to the reference's
#    bytes), and the resume skips the listed frames and completes the rest identically.
set(long ${dome} --fps 48 --contact-sheet none)
render_show("rendered 121, skipped 0 of 121 frames" ${long} --threads 0 --out "${root}/ref")
execute_process(
  COMMAND sh -c "\"$0\" show render --show \"$1\" $2 --threads 2 --frames-in-flight 4 --out \"$3\" >\"$3.log\" 2>&1 &
                 pid=$!; n=0
                 while { [ $(ls \"$3/fisheye\" 2>/dev/null | grep -c 'png$') -lt 8 ] ||
                         ! grep -q state_digest \"$3/manifest.json\" 2>/dev/null; } && [ $n -lt 6000 ]; do
                   sleep 0.01; n=$((n+1)); done
                 kill -9 $pid; wait $pid; echo \"exit $?\""
          "${ZENITH}" "${show}" "--projection fisheye --size 48x48 --tables small --cache ${cache} --fps 48 --contact-sheet none"
          "${root}/k"
  OUTPUT_VARIABLE killed)
if(NOT killed MATCHES "exit 137")
  message(WARNING "the render finished before it could be killed (${killed}): the resume below checks nothing new")
endif()
file(GLOB on_disk RELATIVE "${root}/k/fisheye" "${root}/k/fisheye/*.png")
list(LENGTH on_disk count)
if(count LESS 8)
  message(FATAL_ERROR "killed render: ${count} frames on disk, expected at least 8")
endif()
list(TRANSFORM on_disk PREPEND "fisheye/")
expect_same_files("${root}/k" "${root}/ref" ${on_disk})  # none torn
render_show("of 121 frames" ${long} --out "${root}/k")
if(NOT last_stdout MATCHES "rendered ([0-9]+), skipped ([0-9]+) of 121 frames" OR CMAKE_MATCH_2 EQUAL 0)
  message(FATAL_ERROR "the resume after kill -9 skipped no frame:\n${last_stdout}")
endif()
fisheye_files(all_frames png 0 120)
expect_same_files("${root}/k" "${root}/ref" ${all_frames})  # the resumed render = the uninterrupted one

# 9. A file that cannot be written (a folder stands where frame 3's file goes): the render stops
#    naming it; frames 0-2 stay valid, and once the obstacle is gone only frames 3-5 are rendered.
file(MAKE_DIRECTORY "${root}/w/fisheye/fisheye.000003.png.partial")
execute_process(COMMAND ${ZENITH} show render --show "${show}" ${dome} --contact-sheet none --out "${root}/w"
                RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
if(rc EQUAL 0 OR NOT "${e}" MATCHES "fisheye.000003.png")
  message(FATAL_ERROR "an unwritable frame file: expected a failure naming fisheye.000003.png, got (${rc}):\n${o}\n${e}")
endif()
file(REMOVE_RECURSE "${root}/w/fisheye/fisheye.000003.png.partial")
render_show("rendered 3, skipped 3 of 6 frames" ${dome} --contact-sheet none --out "${root}/w")
fisheye_files(six png 0 5)
expect_same_files("${root}/w" "${root}/a" ${six})

file(REMOVE_RECURSE "${root}")
