# SHUDDER_BUILD_VERSION: what `shudder --version` and `shudder.__version__` print — the project
# version, plus `git describe` of the source tree when it is a git checkout and git is present at
# configure time (a release tarball has no .git: the project version alone). Kept apart from
# SHUDDER_VERSION (stored in every output file) so that a new commit recompiles only the two
# files that print it, and outputs do not change with the checkout.
set(SHUDDER_BUILD_VERSION "${PROJECT_VERSION}")
find_package(Git QUIET)
if(GIT_FOUND AND EXISTS "${PROJECT_SOURCE_DIR}/.git")
  execute_process(COMMAND "${GIT_EXECUTABLE}" describe --always --tags --dirty
                  WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}"
                  OUTPUT_VARIABLE shudder_git_describe
                  RESULT_VARIABLE shudder_git_result
                  OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(shudder_git_result EQUAL 0 AND NOT shudder_git_describe STREQUAL "")
    set(SHUDDER_BUILD_VERSION "${PROJECT_VERSION} (git ${shudder_git_describe})")
  endif()
endif()
message(STATUS "shudder version: ${SHUDDER_BUILD_VERSION}")
