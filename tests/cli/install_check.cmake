# `cmake --install BUILD --prefix PREFIX` (what `make install PREFIX=…` runs) gives a runnable
# `lagrange` with its headers, libraries, docs and examples. Run by ctest with -DBUILD=… -DPREFIX=….
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${PREFIX}
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}): ${err}")
endif()

execute_process(COMMAND ${PREFIX}/bin/lagrange --version
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^lagrange [0-9]+\\.[0-9]+\\.[0-9]+ \\(git [^)]+\\)\n$")
  message(FATAL_ERROR "installed lagrange --version: exit ${rc}, output '${out}${err}'")
endif()

set(doc ${PREFIX}/share/doc/lagrange)
execute_process(COMMAND ${PREFIX}/bin/lagrange check ${doc}/examples/pendulum.yaml
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "model ok")
  message(FATAL_ERROR "installed lagrange check of the installed example: exit ${rc}: ${out}${err}")
endif()

file(GLOB_RECURSE libraries ${PREFIX}/lib*/liblagrange_*.a)
list(LENGTH libraries count)
if(count LESS 7)
  message(FATAL_ERROR "expected the 7 stage libraries under ${PREFIX}/lib, got: ${libraries}")
endif()
foreach(f include/lagrange/model.hpp include/lagrange/simulation.hpp
          share/doc/lagrange/README.md share/doc/lagrange/docs/theory.md
          share/doc/lagrange/docs/model-language.md)
  if(NOT EXISTS ${PREFIX}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
if(PYTHON)  # the Python module: importable from PREFIX/PYTHON_DIR, it runs the installed example
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${PREFIX}/${PYTHON_DIR} ${PYTHON} -c
                          "import lagrange, sys; print(lagrange.__file__); print(lagrange.load(sys.argv[1]).simulate(t_end=1).status)"
                          ${doc}/examples/pendulum.yaml
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out STREQUAL "${PREFIX}/${PYTHON_DIR}/lagrange/__init__.py\ncomplete\n")
    message(FATAL_ERROR "installed Python module: exit ${rc}: ${out}${err}")
  endif()
endif()
file(REMOVE_RECURSE ${PREFIX})
