# ctest: install the package into a fresh prefix, build examples/track_rgbd against it with
# find_package(lumaslam CONFIG), and run it on a synthetic sequence. Passes when the example
# tracks, prints its ATE, and found the vocabulary installed beside the library.
# With PYTHON, the installed Python module must import from the prefix too.
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DCLI=... [-DPYTHON=...] -P ...
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(installed lib/liblumaslam.so include/lumaslam/system.h bin/lumaslam
                  lib/cmake/lumaslam/lumaslamConfig.cmake share/lumaslam/configs)
  if(NOT EXISTS ${prefix}/${installed})
    message(FATAL_ERROR "cmake --install did not install ${installed}")
  endif()
endforeach()
file(GLOB installed_headers RELATIVE ${prefix}/include/lumaslam ${prefix}/include/lumaslam/*)
message(STATUS "installed headers: ${installed_headers}")

run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/track_rgbd -B ${WORK_DIR}/build
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${CLI} synth --preset xyz-rgbd --frames 60 --seed 2 ${WORK_DIR}/seq)
# Not from the source tree: the vocabulary must be found beside the installed library.
run(${CMAKE_COMMAND} -E env --unset=LUMASLAM_VOCABULARY
    ${WORK_DIR}/build/track_rgbd ${WORK_DIR}/seq/settings.yaml tum:${WORK_DIR}/seq)
message(STATUS "${output}")
if(NOT output MATCHES "tracked [0-9]+ of 60 frames" OR NOT output MATCHES "ATE 0\\.00")
  message(FATAL_ERROR "the example did not track the sequence within 1 cm:\n${output}")
endif()
if(NOT output MATCHES "${prefix}/share/lumaslam/[^ ]+\\.bin: vocabulary")
  message(FATAL_ERROR "the example did not load the installed vocabulary:\n${output}")
endif()
if(PYTHON)  # the installed Python module finds the installed library (RPATH $ORIGIN/../..)
  run(${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/lib/python3/dist-packages
      ${PYTHON} -c "print(__import__('lumaslam').__file__)")
  if(NOT output MATCHES "^${prefix}/lib/python3/dist-packages/lumaslam")
    message(FATAL_ERROR "python imported lumaslam from elsewhere: ${output}")
  endif()
endif()
file(REMOVE_RECURSE ${WORK_DIR})
