# cmake -DSERIAL="water_drop;args" -DDISTRIBUTED="mpirun;...;water_drop;args" -DOUT=<dir>
#       -DFRAME=<run>/drop_NNNNN -DCOMPARE=<compare_frames> -P compare_runs.cmake
# Runs the example serially into OUT/serial and under mpirun into OUT/distributed (both must
# exit 0), then compares FRAME.vtp of the one with FRAME.pvtp of the other (compare_frames).
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
