# Per-module include roots (docs/architecture.md, "Include roots").
#
# Sources include each other as "<module>/<path>" ("core/json_reader.h",
# "atmosphere/lut/table.h"). Instead of the repository root, every library
# exports an include root of its own module only: a folder of the build tree,
#   ${PROJECT_BINARY_DIR}/include/<module>/
# holding one symbolic link, <module> → ${PROJECT_SOURCE_DIR}/<module>. A
# library's sources therefore see their own module and the modules of the
# libraries they link (whose roots come with them as usage requirements), and an
# include of a module above them fails to compile ("No such file or directory").
# tests/ and bench/ get a root of their own the same way ("tests/warp/...") and
# see what they link.
#
# cluster/ is a module of modules: each of its folders (cluster/protocol,
# cluster/link, cluster/master, …) is a module of its own with a root of its
# own (${PROJECT_BINARY_DIR}/include/cluster_master/cluster/master → …), so
# that the master's library cannot see node/ and the other way round.
#
#   zenith_module_of_dir(<dir> <out-var>)           the module of a source folder
#   zenith_module_include_root(<module> <out-var>)  the root of <module>, created if needed
#   zenith_module_library(<target> [<module>])      <target> exports the root of <module>
#       (default: the module whose folder holds the calling CMakeLists.txt):
#       PUBLIC, or INTERFACE for an interface library, PRIVATE for an executable.

# The folders whose sub-folders are modules (scripts/check-layers.cmake knows them too).
set(ZENITH_MODULES_OF_MODULES cluster)

function(zenith_module_of_dir dir out)
  file(RELATIVE_PATH relative "${PROJECT_SOURCE_DIR}" "${dir}")
  string(REGEX REPLACE "/.*" "" module "${relative}")
  if(module IN_LIST ZENITH_MODULES_OF_MODULES AND relative MATCHES "^${module}/([a-z_]+)")
    set(module "${module}/${CMAKE_MATCH_1}")
  endif()
  set(${out} "${module}" PARENT_SCOPE)
endfunction()

function(zenith_module_include_root module out)
  string(REPLACE "/" "_" root_name "${module}")
  set(root "${PROJECT_BINARY_DIR}/include/${root_name}")
  set(link "${root}/${module}")
  set(target "${PROJECT_SOURCE_DIR}/${module}")
  if(NOT IS_DIRECTORY "${target}")
    message(FATAL_ERROR "zenith_module_include_root: no module folder ${target}")
  endif()
  set(current "")
  if(IS_SYMLINK "${link}")
    file(READ_SYMLINK "${link}" current)
  endif()
  if(NOT current STREQUAL target)  # first configure, or the source tree moved
    get_filename_component(parent "${link}" DIRECTORY)
    file(MAKE_DIRECTORY "${parent}")
    file(REMOVE "${link}")
    file(CREATE_LINK "${target}" "${link}" SYMBOLIC RESULT failed)
    if(failed)
      message(FATAL_ERROR "zenith_module_include_root: cannot link ${link} → ${target}: ${failed}")
    endif()
  endif()
  set(${out} "${root}" PARENT_SCOPE)
endfunction()

function(zenith_module_library target)
  if(ARGC GREATER 1)
    set(module "${ARGV1}")
  else()
    zenith_module_of_dir("${CMAKE_CURRENT_SOURCE_DIR}" module)
  endif()
  zenith_module_include_root("${module}" root)
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    target_include_directories(${target} INTERFACE "${root}")
  elseif(type STREQUAL "EXECUTABLE")
    target_include_directories(${target} PRIVATE "${root}")
  else()
    target_include_directories(${target} PUBLIC "${root}")
  endif()
endfunction()
