# Installs urbanpvs::runtime (and the tools) so engines can use find_package(urbanpvs CONFIG).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS urbanpvs_runtime EXPORT urbanpvsTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/runtime/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT urbanpvsTargets NAMESPACE urbanpvs:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/urbanpvs)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/urbanpvsConfig.cmake.in
  ${PROJECT_BINARY_DIR}/urbanpvsConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/urbanpvs)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/urbanpvsConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/urbanpvsConfig.cmake ${PROJECT_BINARY_DIR}/urbanpvsConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/urbanpvs)
