# cmake --install puts headers, libraries and GPHRConfig.cmake so that a Trilinos application
# writes find_package(GPHR REQUIRED) and links GPHR::gphr.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The libraries and their headers; the application (gphr_driver) is installed as the gphr
# executable only: nothing a user links or includes names it.
get_property(_gphr_pkgs GLOBAL PROPERTY GPHR_PACKAGES)
list(REMOVE_ITEM _gphr_pkgs gphr_driver)
foreach(_t IN LISTS _gphr_pkgs)
  get_target_property(_src ${_t} SOURCE_DIR)
  install(DIRECTORY ${_src}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
set_target_properties(gphr_trilinos PROPERTIES EXPORT_NAME trilinos_deps)
set_target_properties(gphr_hdf5 PROPERTIES EXPORT_NAME hdf5_deps)
install(TARGETS gphr gphr_trilinos gphr_hdf5 ${_gphr_pkgs} EXPORT GPHRTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET gphr_cli)
  install(TARGETS gphr_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(EXPORT GPHRTargets NAMESPACE GPHR:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/GPHR)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/GPHRConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/GPHRConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/GPHR)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/GPHRConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/GPHRConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/GPHRConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/GPHR)
