# ctest's python_installed: install BUILD_DIR into PREFIX (emptied first) and
# run CHECK with PYTHON against PREFIX/PACKAGE_DIR only.
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX} OUTPUT_QUIET RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD_DIR} --prefix ${PREFIX} failed (${code})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=PYTHONPATH PYTHONNOUSERSITE=1
                        ${PYTHON} ${CHECK} ${PREFIX} ${PREFIX}/${PACKAGE_DIR} ${SCENE} RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "the installed module failed its check (${code})")
endif()
