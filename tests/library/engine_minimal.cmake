# cmake -P script of the test library.engine_minimal (tests/library/CMakeLists.txt): install, build the
# example against the installed package only, run it. Any failing stage fails the test with its output.
function(run_stage name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}")
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "engine_minimal: ${name} failed (${code}):\n${err}")
  endif()
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
run_stage(install ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(file deformConfig.cmake deformConfigVersion.cmake deformTargets.cmake deformable_body.hpp)
  file(GLOB_RECURSE found ${prefix}/${file})
  if(NOT found)
    message(FATAL_ERROR "engine_minimal: the install has no ${file}")
  endif()
endforeach()
# Only the prefix is searched for deform: the example cannot pick up the build tree.
run_stage(configure ${CMAKE_COMMAND} -S ${EXAMPLE_DIR} -B ${WORK_DIR}/build -DCMAKE_BUILD_TYPE=Release
          -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
          -DCMAKE_CXX_COMPILER=${CXX_COMPILER} "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}")
run_stage(build ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run_stage(run ${WORK_DIR}/build/engine_minimal)
