# cmake -DSERIAL="water_drop;args" -DDISTRIBUTED="mpirun;...;water_drop;args" -DOUT=<dir>
#       -DFRAME=<run>/drop_NNNNN -DCOMPARE=<compare_frames> [-DSAME_FILES="view.pvsm;..."]
#       [-DWRITTEN="frames_cleaned.png;..."] -P compare_runs.cmake
# Runs the example serially into OUT/serial and under mpirun into OUT/distributed (both must
# exit 0), then compares FRAME.vtp of the one with FRAME.pvtp of the other (compare_frames), and
# each of SAME_FILES (relative to OUT/<mode>) byte for byte: what is drawn from equal frames
# (ParaView's state file, the charts) must be equal too; a listed file missing from either run
# fails. WRITTEN: files the distributed run must have written, not empty (a particle picture,
# whose points the pieces of a .pvtp draw in another order, is not byte for byte the serial one;
# its pixels were equal when compared once, session 20).
include(${CMAKE_CURRENT_LIST_DIR}/run_mode.cmake)
file(REMOVE_RECURSE ${OUT})
run_mode(serial ${OUT}/serial ${SERIAL})
run_mode(distributed ${OUT}/distributed ${DISTRIBUTED})
execute_process(COMMAND ${COMPARE} ${OUT}/serial/${FRAME}.vtp ${OUT}/distributed/${FRAME}.pvtp RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "${out}${err}")
endif()
message(STATUS "${out}")
foreach(f ${SAME_FILES})
  foreach(mode serial distributed)
    if(NOT EXISTS ${OUT}/${mode}/${f})
      message(FATAL_ERROR "not written: ${OUT}/${mode}/${f}")
    endif()
  endforeach()
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/serial/${f} ${OUT}/distributed/${f} RESULT_VARIABLE same)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "${f} differs between the serial and the distributed run")
  endif()
endforeach()
message(STATUS "the same: ${SAME_FILES}")
foreach(f ${WRITTEN})
  if(NOT EXISTS ${OUT}/distributed/${f})
    message(FATAL_ERROR "not written: ${OUT}/distributed/${f}")
  endif()
  file(SIZE ${OUT}/distributed/${f} bytes)
  if(bytes EQUAL 0)
    message(FATAL_ERROR "empty: ${OUT}/distributed/${f}")
  endif()
endforeach()
