# Writes bapd/version.hpp (run at build time by the bapd_version_header target):
#   cmake -DSOURCE_DIR=... -DVERSION=0.3.0 -DOUTPUT=.../bapd/version.hpp -P version.cmake
# The git description is "" outside a git checkout (a release tarball) or without git.
set(BAPD_GIT_DESCRIBE "")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty --tags
                  WORKING_DIRECTORY ${SOURCE_DIR} OUTPUT_VARIABLE describe ERROR_QUIET
                  RESULT_VARIABLE failed OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT failed)
    set(BAPD_GIT_DESCRIBE "${describe}")
  endif()
endif()
set(BAPD_VERSION "${VERSION}")
# configure_file leaves OUTPUT untouched when its text is unchanged: nothing recompiles.
configure_file(${SOURCE_DIR}/src/version.hpp.in ${OUTPUT} @ONLY)
