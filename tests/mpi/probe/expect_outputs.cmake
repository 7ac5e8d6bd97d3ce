# cmake -DCOMMAND="cmd;args" -DOUT=<dir> -DFILES="a.png;b/c.pvsm" -P expect_outputs.cmake
# Runs COMMAND with --out OUT (exit 0 required) and checks that every one of FILES (relative to
# OUT) was written and is not empty: a distributed run's pictures and ParaView state.
include(${CMAKE_CURRENT_LIST_DIR}/run_mode.cmake)
file(REMOVE_RECURSE ${OUT})
run_mode(distributed ${OUT} ${COMMAND})
foreach(f ${FILES})
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "not written: ${OUT}/${f}")
  endif()
  file(SIZE ${OUT}/${f} bytes)
  if(bytes EQUAL 0)
    message(FATAL_ERROR "empty: ${OUT}/${f}")
  endif()
endforeach()
message(STATUS "written: ${FILES}")
