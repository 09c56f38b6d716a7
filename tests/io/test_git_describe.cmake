# cmake -DWORK=DIR -DSOURCE=DIR -DGIT=path/to/git -P test_git_describe.cmake
# cmake/GitDescribe.cmake writes "unknown" for a tree that is not the top of a git checkout (here: a fresh folder,
# which is either outside every repository or inside the build tree of one), and a non-empty description for
# the source tree when that is a git checkout.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/tree")
execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${WORK}/tree -DOUTPUT=${WORK}/outside.h -DGIT=${GIT}
                        -P ${SOURCE}/cmake/GitDescribe.cmake RESULT_VARIABLE rc)
file(READ "${WORK}/outside.h" outside)
if(NOT rc EQUAL 0 OR NOT outside MATCHES "#define RADWALK_GIT_DESCRIBE \"unknown\"")
  message(FATAL_ERROR "outside a git checkout: expected \"unknown\", got:\n${outside}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${SOURCE} -DOUTPUT=${WORK}/source.h -DGIT=${GIT}
                        -P ${SOURCE}/cmake/GitDescribe.cmake RESULT_VARIABLE rc)
file(READ "${WORK}/source.h" described)
if(NOT rc EQUAL 0 OR NOT described MATCHES "#define RADWALK_GIT_DESCRIBE \"[^\"]+\"")
  message(FATAL_ERROR "the source tree: expected a description, got:\n${described}")
endif()
if(GIT AND EXISTS "${SOURCE}/.git" AND described MATCHES "\"unknown\"")
  message(FATAL_ERROR "the source tree is a git checkout but was described as unknown")
endif()
