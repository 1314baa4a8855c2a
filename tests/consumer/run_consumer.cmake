# InstalledPackage.ConsumerBuildsAndRuns: installs TEM's build tree into a scratch prefix, builds
# tests/consumer against it with find_package(TEM) and runs it. Run as
#
#   cmake -DTEM_BUILD_DIR=... -DPREFIX=... -DCONSUMER_SOURCE=... -DCONSUMER_BUILD=...
#         -DSCENE=... [-DGENERATOR=...] [-DCXX_COMPILER=...] -P run_consumer.cmake
#
# Fails (a non-zero exit) at the first step that does, printing that step's output.
foreach(var TEM_BUILD_DIR PREFIX CONSUMER_SOURCE CONSUMER_BUILD SCENE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_consumer.cmake: -D${var}=... is missing")
  endif()
endforeach()

function(run_step name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message("${out}")
    list(JOIN ARGN " " command)
    message(FATAL_ERROR "${name} failed (${rc}): ${command}")
  endif()
  message(STATUS "${name}: ok")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

# A fresh prefix and consumer build each time: nothing left from an earlier install may help.
file(REMOVE_RECURSE "${PREFIX}" "${CONSUMER_BUILD}")

run_step("install" ${CMAKE_COMMAND} --install "${TEM_BUILD_DIR}" --prefix "${PREFIX}")

set(configure_args -S "${CONSUMER_SOURCE}" -B "${CONSUMER_BUILD}" -DCMAKE_BUILD_TYPE=Release
                   "-DCMAKE_PREFIX_PATH=${PREFIX}")
if(GENERATOR)
  list(APPEND configure_args -G "${GENERATOR}")
endif()
if(CXX_COMPILER)
  list(APPEND configure_args "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
endif()
# Warnings in TEM's public headers fail the test.
list(APPEND configure_args -DCMAKE_CXX_FLAGS=-Werror)
run_step("configure consumer" ${CMAKE_COMMAND} ${configure_args})

# find_package must have found the installed package, not TEM's build tree.
file(STRINGS "${CONSUMER_BUILD}/CMakeCache.txt" tem_dir REGEX "^TEM_DIR:")
string(REGEX REPLACE "^TEM_DIR:[A-Z]*=" "" tem_dir "${tem_dir}")
file(REAL_PATH "${PREFIX}" real_prefix)
file(REAL_PATH "${tem_dir}" real_tem_dir)
string(FIND "${real_tem_dir}" "${real_prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "find_package(TEM) found ${tem_dir}, not the package in ${PREFIX}")
endif()
message(STATUS "TEM_DIR: ${tem_dir}")

run_step("build consumer" ${CMAKE_COMMAND} --build "${CONSUMER_BUILD}")

# No LD_LIBRARY_PATH: the consumer's RPATH must lead to the installed libtem.so.
run_step("run consumer" "${CONSUMER_BUILD}/consumer" "${SCENE}")
message("${step_output}")
