# The version of this build for run records (include/sphark/io/build_info.hpp): the git commit
# of the source tree and whether it differs from that commit, the build type and sanitizers,
# written to <build>/generated/sphark/build_info_generated.hpp at configure time and again at
# every build (configure_file touches the header only when a value changed, so an unchanged
# tree recompiles nothing). Outside a git checkout (a tarball), or without git, the commit and
# the modified state are "unknown".
#
#   include(cmake/build_info.cmake)
#   sphark_build_info(sphark)        # the target whose sources include the header
#
# At build time this file runs as a script: cmake -DSOURCE_DIR=.. -DOUTPUT=.. -DBUILD_TYPE=..
# -DVERSION=.. -DSANITIZE=.. -P build_info.cmake

function(sphark_write_build_info source_dir output build_type version sanitize)
  set(SPHARK_GIT_COMMIT "unknown")
  set(SPHARK_GIT_MODIFIED "unknown")
  find_program(SPHARK_GIT_EXECUTABLE git)
  if(SPHARK_GIT_EXECUTABLE)
    execute_process(COMMAND ${SPHARK_GIT_EXECUTABLE} -C ${source_dir} rev-parse --show-toplevel
                    OUTPUT_VARIABLE top RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    get_filename_component(source_real "${source_dir}" REALPATH)
    if(rc EQUAL 0)
      get_filename_component(top "${top}" REALPATH)
    endif()
    # only this project's own checkout counts (a tarball unpacked inside another repository: unknown)
    if(rc EQUAL 0 AND top STREQUAL source_real)
      execute_process(COMMAND ${SPHARK_GIT_EXECUTABLE} -C ${source_dir} rev-parse HEAD
                      OUTPUT_VARIABLE commit RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
      if(rc EQUAL 0)
        set(SPHARK_GIT_COMMIT "${commit}")
        execute_process(COMMAND ${SPHARK_GIT_EXECUTABLE} -C ${source_dir} status --porcelain
                        OUTPUT_VARIABLE changes RESULT_VARIABLE rc ERROR_QUIET)
        if(rc EQUAL 0 AND changes STREQUAL "")
          set(SPHARK_GIT_MODIFIED "no")
        elseif(rc EQUAL 0)
          set(SPHARK_GIT_MODIFIED "yes")
        endif()
      endif()
    endif()
  endif()
  set(SPHARK_BUILD_TYPE "${build_type}")
  set(SPHARK_VERSION "${version}")
  set(SPHARK_SANITIZE "${sanitize}")
  configure_file(${CMAKE_CURRENT_FUNCTION_LIST_DIR}/build_info.hpp.in ${output} @ONLY)
endfunction()

if(CMAKE_SCRIPT_MODE_FILE)
  sphark_write_build_info("${SOURCE_DIR}" "${OUTPUT}" "${BUILD_TYPE}" "${VERSION}" "${SANITIZE}")
  return()
endif()

function(sphark_build_info target)
  set(dir ${PROJECT_BINARY_DIR}/generated)
  set(header ${dir}/sphark/build_info_generated.hpp)
  set(sanitize OFF)
  if(SPHARK_SANITIZE)
    set(sanitize ON)
  endif()
  sphark_write_build_info(${PROJECT_SOURCE_DIR} ${header} "${CMAKE_BUILD_TYPE}" "${PROJECT_VERSION}" ${sanitize})
  add_custom_target(${target}_build_info
    COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DOUTPUT=${header}
            -DBUILD_TYPE=${CMAKE_BUILD_TYPE} -DVERSION=${PROJECT_VERSION} -DSANITIZE=${sanitize}
            -P ${CMAKE_CURRENT_FUNCTION_LIST_FILE}
    BYPRODUCTS ${header} VERBATIM)
  add_dependencies(${target} ${target}_build_info)
  target_include_directories(${target} PRIVATE ${dir})
endfunction()
