# Finds Debian's Trilinos 13.2, MPI, parallel HDF5 and GoogleTest; a missing piece stops
# configuration with the Debian package to install (see PLATFORM.md for why each is needed).
set(GPHR_TRILINOS_COMPONENTS Teuchos Tpetra KokkosKernels Belos Anasazi NOX Ifpack2 Thyra Stratimikos)
set(GPHR_DEBIAN_HINT "run scripts/setup.sh (or apt-get install the list in README.md)")

find_package(MPI COMPONENTS C CXX)
if(NOT MPI_FOUND)
  message(FATAL_ERROR "GPHR: MPI not found. Install the Debian packages libopenmpi-dev openmpi-bin (${GPHR_DEBIAN_HINT}).")
endif()

# Without COMPONENTS, TrilinosConfig looks for MueLu and fails (PLATFORM.md).
find_package(Trilinos QUIET COMPONENTS ${GPHR_TRILINOS_COMPONENTS})
if(NOT Trilinos_FOUND)
  message(FATAL_ERROR "GPHR: Trilinos (${GPHR_TRILINOS_COMPONENTS}) not found. Install the Debian packages "
    "libtrilinos-teuchos-dev libtrilinos-tpetra-dev libtrilinos-kokkos-dev libtrilinos-kokkos-kernels-dev "
    "libtrilinos-belos-dev libtrilinos-anasazi-dev libtrilinos-nox-dev libtrilinos-ifpack2-dev "
    "and the companions listed in README.md (their CMake configs include each other) (${GPHR_DEBIAN_HINT}).")
endif()
foreach(_lib IN ITEMS tpetra belostpetra ifpack2 teuchosparameterlist teuchosnumerics kokkoscore)
  if(NOT TARGET trilinos_${_lib} AND NOT TARGET ${_lib})
    message(FATAL_ERROR "GPHR: Trilinos target for '${_lib}' missing; install its libtrilinos-*-dev package (${GPHR_DEBIAN_HINT}).")
  endif()
endforeach()

set(HDF5_PREFER_PARALLEL TRUE)
find_package(HDF5 QUIET COMPONENTS C)
if(NOT HDF5_FOUND OR NOT HDF5_IS_PARALLEL)
  message(FATAL_ERROR "GPHR: parallel HDF5 not found. Install the Debian package libhdf5-openmpi-dev (${GPHR_DEBIAN_HINT}).")
endif()

if(GPHR_ENABLE_TESTS)
  find_package(GTest QUIET)
  if(NOT GTest_FOUND)
    message(FATAL_ERROR "GPHR: GoogleTest not found. Install the Debian package libgtest-dev (${GPHR_DEBIAN_HINT}).")
  endif()
endif()

# HDF5 as a plain interface target with the resolved paths: an installed GPHR then needs no
# FindHDF5 (which try-compiles C) in a consumer's project, which may enable CXX only.
add_library(gphr_hdf5 INTERFACE)
target_include_directories(gphr_hdf5 SYSTEM INTERFACE ${HDF5_C_INCLUDE_DIRS})
target_link_libraries(gphr_hdf5 INTERFACE ${HDF5_C_LIBRARIES})
target_compile_definitions(gphr_hdf5 INTERFACE ${HDF5_C_DEFINITIONS} ${HDF5_DEFINITIONS})

# Trilinos' imported targets carry no include dirs and no MPI flags (PLATFORM.md).
add_library(gphr_trilinos INTERFACE)
target_include_directories(gphr_trilinos SYSTEM INTERFACE ${Trilinos_INCLUDE_DIRS} ${Trilinos_TPL_INCLUDE_DIRS})
target_link_libraries(gphr_trilinos INTERFACE ${Trilinos_LIBRARIES} MPI::MPI_CXX)
