# Checks that the modules include each other only downward
# (docs/architecture.md). The layers, bottom to top, and what each may include
# besides itself:
#
#   core/        nothing of zenith (config reading, files, embedded resources,
#                parallel loops, SHA-256, units, timing, progress bars)
#   image/       core                       EXR/PNG files, tone mapping, colour
#   atmosphere/  core                       the physics; no GL
#   warp/        core, image                projections, warp meshes, blending, calibration export; no GL
#   astro/       core, atmosphere           star catalogue, ephemerides (ERFA), refraction, night-sky photometry; no GL
#   scene/       core, image, atmosphere, astro   scenes, albedo maps, the sun's disc, frame descriptions; no GL
#   show/        core, image, atmosphere, astro, scene   shows, playback clock, table plans, timecode; no GL, no protocol
#   render/      core … scene (not show)    GL, tables on the GPU, the frame renderer
#   cluster/     a module of modules, each folder one (no loops, no sideways steps):
#     protocol/  core, scene                the wire protocol: messages, framing, handshake, table transfer
#     link/      … warp, scene, protocol    configuration, a connection, a link to the master, takeover state
#     operator/  … show, link               the operator: commands, desk, consoles; the master only through DeskMaster
#     master/    … show, render, link, operator   the master: table schedule, barrier, status
#     node/      … render, link             a render node
#     standby/   … master, link             the standby master
#     launcher/  core, image, warp, link    a local cluster: its child processes, the stitched dome
#   validate/    core … render (not show)   `zenith validate`: CIE, night sky, stress; the reference models only it uses
#   offline/     the above, show, cluster   offline rendering of shows (frames, manifest, outputs)
#   apps/        all of the above           the `zenith` command
#   (bench/ and tests/ may include anything)
#
# and inside render/, the GL wrapper render/gl/ includes only render/gl/.
#
# Reads every .h and .cpp under those directories, takes each
# `#include "module/..."` and prints every include that points up or sideways,
# as file:line, the include and what the file's module may include. Fails if
# there is one. A CMake script, so it runs wherever the build does:
#
#   cmake -DSOURCE_DIR=. -P scripts/check-layers.cmake
#
# CTest runs it as layers.include_graph.
#
# With -DLINK_GRAPH=FILE it checks the libraries' links instead: FILE holds one
# edge a line, "module target linked_module linked_target", as
# tests/layers/CMakeLists.txt writes it for every target of the build. A
# library sees the include roots of what it links (cmake/ModuleIncludes.cmake),
# so a link up the layers would open them: it fails on every edge from a module
# to one it may not include. CTest runs it as layers.link_graph.
cmake_minimum_required(VERSION 3.20)
if(NOT SOURCE_DIR)
  set(SOURCE_DIR "${CMAKE_CURRENT_LIST_DIR}/..")
endif()
get_filename_component(SOURCE_DIR "${SOURCE_DIR}" ABSOLUTE)

set(cluster cluster/protocol cluster/link cluster/operator cluster/master cluster/node cluster/standby cluster/check cluster/launcher)
set(modules core image atmosphere warp astro scene show render ${cluster} validate offline apps)
set(allowed_core "")
set(allowed_image core)
set(allowed_atmosphere core)
set(allowed_warp core image)
set(allowed_astro core atmosphere)
set(allowed_scene core image atmosphere astro)
set(allowed_show core image atmosphere astro scene)
set(allowed_render core image atmosphere warp astro scene)
set(allowed_cluster/protocol core scene)
set(allowed_cluster/link core image atmosphere warp astro scene cluster/protocol)
set(allowed_cluster/operator core image atmosphere warp astro scene show cluster/protocol cluster/link)
set(allowed_cluster/master core image atmosphere warp astro scene show render cluster/protocol cluster/link cluster/operator)
set(allowed_cluster/node core image atmosphere warp astro scene render cluster/protocol cluster/link)
set(allowed_cluster/standby core image atmosphere warp astro scene show render cluster/protocol cluster/link cluster/operator cluster/master)
set(allowed_cluster/check core image atmosphere warp astro scene show render cluster/protocol cluster/link cluster/operator cluster/master)
set(allowed_cluster/launcher core image warp cluster/protocol cluster/link)
set(allowed_validate core image atmosphere warp astro scene render)
set(allowed_offline core image atmosphere warp astro scene show render ${cluster})
set(allowed_apps core image atmosphere warp astro scene show render ${cluster} validate offline)

if(LINK_GRAPH)
  file(STRINGS "${LINK_GRAPH}" edges)
  set(violations 0)
  list(LENGTH edges count)
  foreach(edge IN LISTS edges)
    string(REPLACE " " ";" edge "${edge}")
    list(GET edge 0 module)
    list(GET edge 1 target)
    list(GET edge 2 linked_module)
    list(GET edge 3 linked_target)
    if(module IN_LIST modules AND NOT linked_module STREQUAL module AND NOT linked_module IN_LIST allowed_${module})
      string(REPLACE ";" ", " may "${allowed_${module}}")
      if(may STREQUAL "")
        set(may "nothing of zenith")
      endif()
      message("${target} (${module}/) links ${linked_target} (${linked_module}/)  (${module}/ may include ${may})")
      math(EXPR violations "${violations} + 1")
    endif()
  endforeach()
  message("check-layers: ${count} links, ${violations} upward or sideways")
  if(violations GREATER 0)
    message(FATAL_ERROR "check-layers: the link graph does not follow the layers (docs/architecture.md)")
  endif()
  return()
endif()

# Prints the include `line` at `source`:`number` and `why` it breaks the
# layers, and counts it in `violations`.
function(report_include source number line why)
  file(RELATIVE_PATH relative "${SOURCE_DIR}" "${source}")
  string(STRIP "${line}" include)
  message("${relative}:${number}: ${include}  (${why})")
  math(EXPR count "${violations} + 1")
  set(violations ${count} PARENT_SCOPE)
endfunction()

set(violations 0)
set(files 0)
foreach(module IN LISTS modules)
  file(GLOB_RECURSE sources "${SOURCE_DIR}/${module}/*.h" "${SOURCE_DIR}/${module}/*.cpp")
  list(SORT sources)
  foreach(source IN LISTS sources)
    math(EXPR files "${files} + 1")
    file(STRINGS "${source}" lines)
    set(number 0)
    foreach(line IN LISTS lines)
      math(EXPR number "${number} + 1")
      if(line MATCHES "^[ \t]*#[ \t]*include[ \t]+\"([a-z_]+)/(([a-z_]+)/)?")
        set(target "${CMAKE_MATCH_1}")
        if(target STREQUAL "cluster" AND CMAKE_MATCH_3)  # a module of modules: cluster/master, …
          set(target "cluster/${CMAKE_MATCH_3}")
        endif()
        if(NOT target STREQUAL module AND target IN_LIST modules AND NOT target IN_LIST allowed_${module})
          string(REPLACE ";" ", " may "${allowed_${module}}")
          if(may STREQUAL "")
            set(may "nothing of zenith")
          endif()
          report_include("${source}" ${number} "${line}" "${module}/ may include ${may}")
        endif()
      endif()
    endforeach()
  endforeach()
endforeach()

# Folders inside a module that may include less of their module than the
# module may: "folder:allowed prefix;…". The generic GL wrapper render/gl/
# takes plain #defines and knows no engine constant (render/shader_bindings.h,
# the frame's tiles), so it includes nothing of render/ outside render/gl/;
# the engine's program factory is render/shader_programs.h.
set(folder_rules "render/gl:render/gl/")
foreach(rule IN LISTS folder_rules)
  string(REPLACE ":" ";" rule "${rule}")
  list(GET rule 0 folder)
  list(GET rule 1 allowed_prefix)
  string(REGEX REPLACE "/.*" "" folder_module "${folder}")
  file(GLOB_RECURSE sources "${SOURCE_DIR}/${folder}/*.h" "${SOURCE_DIR}/${folder}/*.cpp")
  list(SORT sources)
  foreach(source IN LISTS sources)
    file(STRINGS "${source}" lines)
    set(number 0)
    foreach(line IN LISTS lines)
      math(EXPR number "${number} + 1")
      if(line MATCHES "^[ \t]*#[ \t]*include[ \t]+\"(${folder_module}/[^\"]*)\"")
        set(included "${CMAKE_MATCH_1}")
        string(FIND "${included}" "${allowed_prefix}" at)
        if(NOT at EQUAL 0)
          report_include("${source}" ${number} "${line}" "${folder}/ may include only ${allowed_prefix} of ${folder_module}/")
        endif()
      endif()
    endforeach()
  endforeach()
endforeach()

message("check-layers: ${files} files, ${violations} upward or sideways include(s)")
if(violations GREATER 0)
  message(FATAL_ERROR "check-layers: the include graph does not follow the layers (docs/architecture.md)")
endif()
