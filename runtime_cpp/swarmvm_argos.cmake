# Finding ARGoS 3 and building a swarmvm ARGoS controller, included by a generated project's
# CMakeLists.txt (which the user owns and may extend: more sources, more libraries), and by an
# OpenSwarm project switched to swarmvm's sct.h (`swarmvm compat-switch`, docs/compat.md), which
# finds this file by asking the swarmvm program (`swarmvm cmake-dir` prints its folder; the
# program on PATH, or -DSWARMVM_EXECUTABLE=), never a python3.
#
# ARGoS is found through its ARGoSConfig.cmake (share/argos3/cmake), looked for in this order at
# ARGoS_DIR, ARGOS_PREFIX (cache or environment variable), CMAKE_PREFIX_PATH, the prefix of the
# argos3 program on PATH, the usual prefixes (/usr/local, /usr, /opt); else with pkg-config
# (argos3_simulator), as older ARGoS releases install it. ARGoS's headers (and Lua's, which an
# ARGoS built with Lua includes) are system headers, so -Wall -Wextra -pedantic warn about the
# project's code only.
#
#   swarmvm_argos_controller(<target> <source>...)
#       a MODULE library (the controller ARGoS loads) from the given sources and the swarmvm
#       runtime headers beside this file, linked with ARGoS's simulator and e-puck plugins.
#
#   swarmvm_pack(<target> <supervisor.yaml>...)
#       a target (built by default) that packs each supervisor.yaml into the image beside it
#       (x/supervisor.yaml -> x/supervisor.svm, what SCT("x/supervisor.yaml") reads) with
#       `swarmvm pack`, at build time and again whenever the YAML file changes: a build never
#       leaves a stale image (docs/compat.md, "Never stale"). Relative paths are taken from the
#       current source folder. `swarmvm` is found on PATH, or given as -DSWARMVM_EXECUTABLE=.

set(ARGOS_PREFIX "$ENV{ARGOS_PREFIX}" CACHE PATH "ARGoS install prefix (holds bin/argos3)")
find_program(ARGOS_EXECUTABLE argos3 HINTS "${ARGOS_PREFIX}/bin")
string(REPLACE ":" ";" _env_prefixes "$ENV{CMAKE_PREFIX_PATH}")
set(_argos_hints "${ARGoS_DIR}")
foreach(_prefix ${ARGOS_PREFIX} ${CMAKE_PREFIX_PATH} ${_env_prefixes})
  list(APPEND _argos_hints "${_prefix}/share/argos3/cmake")
endforeach()
if(ARGOS_EXECUTABLE)
  get_filename_component(_argos_bin "${ARGOS_EXECUTABLE}" DIRECTORY)
  list(APPEND _argos_hints "${_argos_bin}/../share/argos3/cmake")
endif()
find_path(ARGOS_CMAKE_DIR ARGoSConfig.cmake
  HINTS ${_argos_hints}
  PATHS /usr/local/share/argos3/cmake /usr/share/argos3/cmake /opt/share/argos3/cmake /opt/local/share/argos3/cmake
  DOC "Folder of ARGoSConfig.cmake")

if(ARGOS_CMAKE_DIR)
  # ARGoSConfig.cmake looks for the headers and libraries under the prefixes CMake searches.
  get_filename_component(_argos_prefix "${ARGOS_CMAKE_DIR}/../../.." ABSOLUTE)
  list(INSERT CMAKE_PREFIX_PATH 0 "${_argos_prefix}")
  find_package(ARGoS REQUIRED CONFIG PATHS "${ARGOS_CMAKE_DIR}" NO_DEFAULT_PATH)
  set(SWARMVM_ARGOS_LIBRARY_DIRS "${ARGOS_LIBRARY_DIR}")
else()
  find_package(PkgConfig)
  if(PKG_CONFIG_FOUND)
    pkg_check_modules(ARGOS argos3_simulator)
  endif()
  if(NOT ARGOS_FOUND)
    message(FATAL_ERROR "ARGoS 3 not found: install it (https://www.argos-sim.info), then pass "
                        "-DARGOS_PREFIX=<prefix> or -DARGoS_DIR=<prefix>/share/argos3/cmake")
  endif()
  set(SWARMVM_ARGOS_LIBRARY_DIRS ${ARGOS_LIBRARY_DIRS})
  # An ARGoS built with Lua includes <lua.h> from its headers.
  find_package(Lua)
  if(LUA_FOUND)
    list(APPEND ARGOS_INCLUDE_DIRS "${LUA_INCLUDE_DIR}")
  endif()
endif()

set(SWARMVM_RUNTIME_DIR "${CMAKE_CURRENT_LIST_DIR}")

function(swarmvm_argos_controller target)
  add_library(${target} MODULE ${ARGN})
  set_target_properties(${target} PROPERTIES CXX_STANDARD 17 CXX_STANDARD_REQUIRED ON CXX_EXTENSIONS OFF)
  target_include_directories(${target} SYSTEM PRIVATE ${ARGOS_INCLUDE_DIRS})
  target_include_directories(${target} PRIVATE "${SWARMVM_RUNTIME_DIR}")
  target_link_directories(${target} PRIVATE ${SWARMVM_ARGOS_LIBRARY_DIRS})
  target_compile_options(${target} PRIVATE -Wall -Wextra -pedantic)
  target_link_libraries(${target} argos3core_simulator argos3plugin_simulator_epuck argos3plugin_simulator_genericrobot)
endfunction()

find_program(SWARMVM_EXECUTABLE swarmvm DOC "The swarmvm program (swarmvm cmake-dir, swarmvm_pack)")

function(swarmvm_pack target)
  if(NOT SWARMVM_EXECUTABLE)
    message(FATAL_ERROR "swarmvm_pack(${target}): the swarmvm program was not found: pip install swarmvm, "
                        "or pass -DSWARMVM_EXECUTABLE=<path of swarmvm>")
  endif()
  set(_images "")
  foreach(_yaml IN LISTS ARGN)
    get_filename_component(_yaml "${_yaml}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    if(NOT _yaml MATCHES "\\.yaml$")
      message(FATAL_ERROR "swarmvm_pack(${target}): ${_yaml} is not a supervisor.yaml")
    endif()
    string(REGEX REPLACE "\\.yaml$" ".svm" _image "${_yaml}")
    add_custom_command(OUTPUT "${_image}"
                       COMMAND "${SWARMVM_EXECUTABLE}" pack "${_yaml}" -o "${_image}"
                       DEPENDS "${_yaml}"
                       COMMENT "swarmvm pack ${_yaml}"
                       VERBATIM)
    list(APPEND _images "${_image}")
  endforeach()
  add_custom_target(${target} ALL DEPENDS ${_images})
endfunction()
