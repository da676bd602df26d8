# API reference (Doxygen) of the installed headers: target `doc` and, with tests enabled, the
# ctest test `doc_undocumented`. Both exist only when doxygen is found
# (Debian: `bash scripts/setup.sh --docs` installs it).
find_package(Doxygen QUIET)
if(NOT DOXYGEN_FOUND)
  message(STATUS "GPHR: doxygen not found, no `doc` target and no doc_undocumented test")
  return()
endif()

set(GPHR_DOC_INPUT "")
foreach(_p IN LISTS GPHR_PACKAGE_NAMES)
  string(APPEND GPHR_DOC_INPUT " ${PROJECT_SOURCE_DIR}/packages/${_p}/include")
endforeach()
file(GLOB_RECURSE _gphr_doc_headers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/packages/*/include/gphr/*.hpp)

# One configuration for the target, one for the test, so the two never write the same files.
set(GPHR_DOC_OUTPUT ${CMAKE_BINARY_DIR}/doc)
configure_file(${PROJECT_SOURCE_DIR}/doc/Doxyfile.in ${GPHR_DOC_OUTPUT}/Doxyfile @ONLY)
set(GPHR_DOC_OUTPUT ${CMAKE_BINARY_DIR}/doc-check)
configure_file(${PROJECT_SOURCE_DIR}/doc/Doxyfile.in ${GPHR_DOC_OUTPUT}/Doxyfile @ONLY)

# The target prints doxygen's warnings (it does not fail on them; the test does).
add_custom_target(doc
  COMMAND ${CMAKE_COMMAND} -DDOXYGEN=${DOXYGEN_EXECUTABLE} -DDOXYFILE=${CMAKE_BINARY_DIR}/doc/Doxyfile
          -DLOG=${CMAKE_BINARY_DIR}/doc/doxygen-warnings.log -DSTRICT=OFF
          -P ${PROJECT_SOURCE_DIR}/cmake/GPHRDocCheck.cmake
  DEPENDS ${_gphr_doc_headers} ${PROJECT_SOURCE_DIR}/doc/Doxyfile.in
  WORKING_DIRECTORY ${CMAKE_BINARY_DIR}/doc
  COMMENT "API reference -> ${CMAKE_BINARY_DIR}/doc/html/index.html"
  VERBATIM)

if(GPHR_ENABLE_TESTS)
  add_test(NAME doc_undocumented
    COMMAND ${CMAKE_COMMAND} -DDOXYGEN=${DOXYGEN_EXECUTABLE} -DDOXYFILE=${CMAKE_BINARY_DIR}/doc-check/Doxyfile
            -DLOG=${CMAKE_BINARY_DIR}/doc-check/doxygen-warnings.log -DSTRICT=ON
            -P ${PROJECT_SOURCE_DIR}/cmake/GPHRDocCheck.cmake
    WORKING_DIRECTORY ${CMAKE_BINARY_DIR}/doc-check)
  set_tests_properties(doc_undocumented PROPERTIES TIMEOUT 120 LABELS "doc;np1")
endif()
