# gphr_add_package(NAME <name> SOURCES <files...> DEPENDS <targets...>)
# One library per package (DESIGN.md), headers under packages/<name>/include/gphr/<name>/.
function(gphr_add_package)
  cmake_parse_arguments(P "" "NAME" "SOURCES;DEPENDS" ${ARGN})
  set(_t gphr_${P_NAME})
  add_library(${_t} ${P_SOURCES})
  add_library(GPHR::${P_NAME} ALIAS ${_t})
  target_include_directories(${_t} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:include>)
  target_link_libraries(${_t} PUBLIC ${P_DEPENDS})
  target_compile_options(${_t} PRIVATE -Wall -Wextra ${GPHR_ARCH_FLAGS})
  set_target_properties(${_t} PROPERTIES EXPORT_NAME ${P_NAME})
  set_property(GLOBAL APPEND PROPERTY GPHR_PACKAGES ${_t})
endfunction()

# gphr_time_mpi(<target>): links the PMPI interposer (packages/driver/src/MpiTimeInterposer.cpp)
# into an executable, so that gphr::mpiTimeNow() counts its time inside MPI (StageClock.hpp).
# The executable exports the MPI_* symbols it defines, so that calls from shared libraries
# (Trilinos, HDF5) resolve to them, not to libmpi's. GNU ld already exports the ones that the
# shared libraries on the link line reference; the flag makes sure of the others (a library that
# is only reached through another, e.g. HDF5's MPI-IO). Only executables: the libraries stay free of it.
function(gphr_time_mpi target)
  target_sources(${target} PRIVATE ${PROJECT_SOURCE_DIR}/packages/driver/src/MpiTimeInterposer.cpp)
  target_link_libraries(${target} PRIVATE gphr_core MPI::MPI_C)
  target_link_options(${target} PRIVATE "LINKER:--export-dynamic-symbol=MPI_*")
endfunction()

# gphr_add_test(NAME <name> SOURCES <files...> DEPENDS <targets...> [RANKS n...] [LABELS ...])
# Each test binary has GPHR's gtest main (Tpetra::ScopeGuard + an MPI reduction of the result).
# RANKS lists the MPI rank counts it runs with (default 1); rank counts > 1 run under mpirun.
# The BLAS threads of the unit tests (ctest sets OPENBLAS_NUM_THREADS for them; the end-to-end
# tests take the caller's): 1, so that MPI tests do not oversubscribe the cores. scripts/portability.sh
# configures 2 as well, to show that no test depends on a threaded BLAS's order of summation.
set(GPHR_TEST_BLAS_THREADS 1 CACHE STRING "OPENBLAS_NUM_THREADS of the unit tests")
if(NOT GPHR_TEST_BLAS_THREADS MATCHES "^[1-9][0-9]*$")
  message(FATAL_ERROR "GPHR_TEST_BLAS_THREADS = '${GPHR_TEST_BLAS_THREADS}': allowed, a whole number >= 1")
endif()

function(gphr_add_test)
  cmake_parse_arguments(T "" "NAME;TIMEOUT" "SOURCES;DEPENDS;RANKS;LABELS" ${ARGN})
  if(NOT GPHR_ENABLE_TESTS)
    return()
  endif()
  if(NOT T_RANKS)
    set(T_RANKS 1)
  endif()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_DEPENDS} gphr_testmain GTest::gtest)
  target_compile_options(${T_NAME} PRIVATE -Wall -Wextra ${GPHR_ARCH_FLAGS})
  foreach(_np IN LISTS T_RANKS)
    if(_np EQUAL 1)
      add_test(NAME ${T_NAME} COMMAND ${T_NAME})
      set(_tn ${T_NAME})
    else()
      set(_tn ${T_NAME}_np${_np})
      add_test(NAME ${_tn} COMMAND ${MPIEXEC_EXECUTABLE} ${GPHR_MPIEXEC_FLAGS} ${MPIEXEC_NUMPROC_FLAG} ${_np}
               $<TARGET_FILE:${T_NAME}>)
    endif()
    set_tests_properties(${_tn} PROPERTIES TIMEOUT ${T_TIMEOUT} PROCESSORS ${_np}
      LABELS "${T_LABELS};np${_np}" ENVIRONMENT "OPENBLAS_NUM_THREADS=${GPHR_TEST_BLAS_THREADS};OMP_NUM_THREADS=1")
  endforeach()
endfunction()

# mpirun refuses root without these; more ranks than cores needs oversubscribe (PLATFORM.md).
set(GPHR_MPIEXEC_FLAGS --allow-run-as-root --oversubscribe CACHE STRING "Flags for mpirun in tests")
