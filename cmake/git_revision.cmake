# lagrange_git_revision(VAR): `git describe --always --dirty` of the source tree at configure
# time, or "unknown" when git is missing or the sources are not their own git checkout (an
# unpacked archive inside some other repository must not report that repository's revision).
function(lagrange_git_revision var)
  set(revision unknown)
  find_package(Git QUIET)
  if(GIT_FOUND)
    execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --show-toplevel
                    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                    OUTPUT_VARIABLE toplevel OUTPUT_STRIP_TRAILING_WHITESPACE
                    RESULT_VARIABLE toplevel_rc ERROR_QUIET)
    file(REAL_PATH "${PROJECT_SOURCE_DIR}" source_dir)
    if(toplevel_rc EQUAL 0)
      file(REAL_PATH "${toplevel}" toplevel)
    endif()
    if(toplevel_rc EQUAL 0 AND toplevel STREQUAL source_dir)
      execute_process(COMMAND ${GIT_EXECUTABLE} describe --always --dirty
                      WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                      OUTPUT_VARIABLE described OUTPUT_STRIP_TRAILING_WHITESPACE
                      RESULT_VARIABLE described_rc ERROR_QUIET)
      if(described_rc EQUAL 0 AND NOT described STREQUAL "")
        set(revision ${described})
      endif()
    endif()
  endif()
  set(${var} ${revision} PARENT_SCOPE)
endfunction()
