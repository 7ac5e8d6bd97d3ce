# cmake -DREFERENCE="cmd;args" -DFIRST="cmd;args" -DRESTART="cmd;args" -DOUT=<dir> -DRUN=<run>
#       -DFRAME=drop_NNNNN -DREF_EXT=vtp|pvtp -DEXT=vtp|pvtp -DCOMPARE=<compare_frames> -P restart_runs.cmake
# A checkpoint restarted on another number of ranks (docs/scaling.md, "Checkpoints of distributed
# runs"): REFERENCE runs to the end into OUT/reference; FIRST runs to the checkpoint into OUT/first
# (with --checkpoint-every); RESTART continues from OUT/first/RUN/checkpoint.bin to the end into
# OUT/restarted (all must exit 0). The restarted run's FRAME must equal the reference's bit for bit
# (compare_frames: every point and array per global id).
include(${CMAKE_CURRENT_LIST_DIR}/run_mode.cmake)
file(REMOVE_RECURSE ${OUT})
run_mode(reference ${OUT}/reference ${REFERENCE})
run_mode(first ${OUT}/first ${FIRST})
run_mode(restarted ${OUT}/restarted ${RESTART} --restart ${OUT}/first/${RUN}/checkpoint.bin)
execute_process(COMMAND ${COMPARE} ${OUT}/reference/${RUN}/${FRAME}.${REF_EXT} ${OUT}/restarted/${RUN}/${FRAME}.${EXT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc STREQUAL "0")
  message(FATAL_ERROR "${out}${err}")
endif()
message(STATUS "${out}")
