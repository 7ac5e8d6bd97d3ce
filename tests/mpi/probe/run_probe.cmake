# cmake -DCOMMAND="mpirun;...;failure_probe;mode" -DEXIT=<code> -DMATCH=<regex> [-DNOMATCH=<regex>]
#   -P run_probe.cmake
# Runs the command; fails unless it exits with EXIT and its output matches MATCH (and not NOMATCH).
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
set(all "${out}${err}")
if(NOT rc STREQUAL "${EXIT}")
  message(FATAL_ERROR "exit code ${rc}, expected ${EXIT}\n${all}")
endif()
if(NOT all MATCHES "${MATCH}")
  message(FATAL_ERROR "output does not match '${MATCH}':\n${all}")
endif()
if(DEFINED NOMATCH AND all MATCHES "${NOMATCH}")
  message(FATAL_ERROR "output matches '${NOMATCH}':\n${all}")
endif()
message(STATUS "exit ${rc}; output matches '${MATCH}'")
