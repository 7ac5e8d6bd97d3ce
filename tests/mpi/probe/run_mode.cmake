# include(run_mode.cmake), then run_mode(<name> <out dir> <command...>): runs the command with
# --out <out dir> (240 s at most); a non-zero exit fails the test with the run's output.
function(run_mode name out)
  execute_process(COMMAND ${ARGN} --out ${out} RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr
                  TIMEOUT 240)
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "${name} run: exit code ${rc}\n${stdout}${stderr}")
  endif()
endfunction()
