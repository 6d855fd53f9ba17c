# The installed CMake package: find_package(vgroove) gives vgroove::common, ::optics, ::sim,
# ::analytic, ::support, ::validation and ::scene, with their dependencies found again.
include(CMakePackageConfigHelpers)
set(VGROOVE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/vgroove)
install(EXPORT vgrooveTargets NAMESPACE vgroove:: DESTINATION ${VGROOVE_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/vgrooveConfig.cmake.in
  ${CMAKE_BINARY_DIR}/vgrooveConfig.cmake INSTALL_DESTINATION ${VGROOVE_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/vgrooveConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/vgrooveConfig.cmake ${CMAKE_BINARY_DIR}/vgrooveConfigVersion.cmake
        DESTINATION ${VGROOVE_CMAKE_DIR})
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/CITATION.cff
        DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/vgroove)
# The JSON Schemas of the files vgroove reads and writes (docs/schemas/), for editors and
# validators: share/vgroove/schemas.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/schemas/ DESTINATION ${CMAKE_INSTALL_DATADIR}/vgroove/schemas
        FILES_MATCHING PATTERN "*.schema.json")
