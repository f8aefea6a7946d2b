# Run at every build (custom target swell_git_commit): writes OUT (from cmake/git_commit.hpp.in)
# with the commit of SRC, rewriting it only when the commit or the dirty state changed, so
# only io/provenance.cpp recompiles after a commit.
#   cmake -DSRC=<source dir> -DOUT=<header> -P cmake/git_commit.cmake
set(SWELL_GIT_COMMIT "unknown")
find_program(GIT_EXECUTABLE git)
if(GIT_EXECUTABLE)
  # The source tree must be the work tree's top (a tarball unpacked inside another checkout
  # is not that checkout's commit).
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SRC} rev-parse --show-toplevel
                  OUTPUT_VARIABLE top RESULT_VARIABLE rc_top ERROR_QUIET
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SRC} rev-parse HEAD
                  OUTPUT_VARIABLE commit RESULT_VARIABLE rc ERROR_QUIET
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  get_filename_component(src_real ${SRC} REALPATH)
  if(rc_top EQUAL 0)
    get_filename_component(top ${top} REALPATH)
  endif()
  if(rc EQUAL 0 AND rc_top EQUAL 0 AND top STREQUAL src_real AND commit MATCHES "^[0-9a-f]+$")
    set(SWELL_GIT_COMMIT "${commit}")
    # Tracked files changed (staged or not); untracked files do not count.
    execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SRC} status --porcelain --untracked-files=no
                    OUTPUT_VARIABLE changes RESULT_VARIABLE rc ERROR_QUIET)
    if(rc EQUAL 0 AND NOT changes STREQUAL "")
      string(APPEND SWELL_GIT_COMMIT "-dirty")
    endif()
  endif()
endif()
get_filename_component(here ${CMAKE_SCRIPT_MODE_FILE} DIRECTORY)
configure_file(${here}/git_commit.hpp.in ${OUT} @ONLY)  # writes only when the text changed
