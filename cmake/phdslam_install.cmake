# Installation as a CMake package: `cmake --install BUILD --prefix PREFIX` puts the libraries in
# PREFIX/lib, the headers in PREFIX/include/phdslam (paths as in the repository, e.g.
# "src/filters/estimator.h"), the phdslam program in PREFIX/bin, the MRPT baselines' plugin
# libphdslam_mrpt_baselines.so in PREFIX/lib (reference/mrpt/CMakeLists.txt; the program opens it
# from ../lib when an MRPT estimator is constructed) and phdslamConfig.cmake with the
# exported targets (phdslam::<library>) in PREFIX/lib/cmake/phdslam, so that another project can
#   find_package(phdslam REQUIRED)
#   target_link_libraries(my_program PRIVATE phdslam::phdslam_validation)
# (examples/cpp_estimator/ is such a project).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PHDSLAM_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/phdslam")
set(PHDSLAM_INSTALL_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}/phdslam")

# phdslam_install(TARGET...): adds libraries (or programs) to the installed package. A new
# library needs one such call (or its name in the list of the top-level CMakeLists.txt); its
# headers are installed with their folder. Targets that were not built (optional baselines)
# are skipped.
function(phdslam_install)
  foreach(target IN LISTS ARGN)
    if(TARGET ${target})
      install(TARGETS ${target} EXPORT phdslamTargets
              ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
              LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
              RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
      set_property(GLOBAL APPEND PROPERTY PHDSLAM_INSTALLED_TARGETS ${target})
    endif()
  endforeach()
endfunction()

# The headers of every library folder, the export set and the package configuration; called
# once, after every phdslam_install().
function(phdslam_install_package)
  # A library that an installed one links but that is not installed itself would break the
  # export with a terse message; name it and the fix instead.
  get_property(installed GLOBAL PROPERTY PHDSLAM_INSTALLED_TARGETS)
  foreach(target IN LISTS installed)
    get_target_property(links ${target} LINK_LIBRARIES)
    get_target_property(interface_links ${target} INTERFACE_LINK_LIBRARIES)
    foreach(link IN LISTS links interface_links)
      if(link MATCHES "^phdslam_" AND TARGET ${link} AND NOT link IN_LIST installed)
        message(FATAL_ERROR "phdslam: ${target} links ${link}, which is not installed: add "
                            "${link} to the phdslam_install(...) list of CMakeLists.txt")
      endif()
    endforeach()
  endforeach()
  install(DIRECTORY src datasets validation oracle reference
          DESTINATION ${PHDSLAM_INSTALL_INCLUDEDIR}
          FILES_MATCHING PATTERN "*.h")
  install(EXPORT phdslamTargets NAMESPACE phdslam:: DESTINATION ${PHDSLAM_INSTALL_CMAKEDIR})
  # What the installed libraries were built with decides which dependencies the config finds.
  set(PHDSLAM_PACKAGE_WITH_CERES OFF)
  set(PHDSLAM_PACKAGE_WITH_MRPT OFF)
  if(TARGET phdslam_reference_ceres)
    set(PHDSLAM_PACKAGE_WITH_CERES ON)
  endif()
  if(TARGET phdslam_reference_mrpt)
    set(PHDSLAM_PACKAGE_WITH_MRPT ON)
  endif()
  configure_package_config_file(
    ${PROJECT_SOURCE_DIR}/cmake/phdslamConfig.cmake.in
    ${PROJECT_BINARY_DIR}/phdslamConfig.cmake
    INSTALL_DESTINATION ${PHDSLAM_INSTALL_CMAKEDIR})
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/phdslamConfigVersion.cmake
                                   COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/phdslamConfig.cmake
                ${PROJECT_BINARY_DIR}/phdslamConfigVersion.cmake
          DESTINATION ${PHDSLAM_INSTALL_CMAKEDIR})
endfunction()
