# What `cmake --install build --prefix P` adds beside the libraries, headers and
# command (installed where they are defined): the CMake package
# (find_package(superball 0.2 CONFIG)), superball.pc, the manual page and the scenes.
include(CMakePackageConfigHelpers)
set(SUPERBALL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/superball)
set(SUPERBALL_SCENES_INSTALL_DIR ${CMAKE_INSTALL_DATADIR}/superball/scenes)

install(EXPORT superballTargets NAMESPACE superball:: DESTINATION ${SUPERBALL_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/superballConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/superballConfig.cmake
  INSTALL_DESTINATION ${SUPERBALL_CMAKE_DIR} PATH_VARS SUPERBALL_SCENES_INSTALL_DIR)
# 0.x: a minor release may break the API, so 0.2 accepts 0.2.* only.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/superballConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/superballConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/superballConfigVersion.cmake
  DESTINATION ${SUPERBALL_CMAKE_DIR})

# superball.pc and the manual page name the prefix given at install time
# (cmake --install --prefix), so they are completed then, not at configure time.
if(BUILD_SHARED_LIBS)
  set(SUPERBALL_PC_PRIVATE "")
else()
  set(SUPERBALL_PC_PRIVATE "Requires.private: tomlplusplus mpfr gmp")
endif()
set(SUPERBALL_PREFIX "@SUPERBALL_PREFIX@")  # kept for install time
set(staged ${CMAKE_CURRENT_BINARY_DIR}/install-time)
configure_file(${CMAKE_CURRENT_LIST_DIR}/superball.pc.in ${staged}/superball.pc.in @ONLY)
configure_file(${PROJECT_SOURCE_DIR}/cli/superball.1.in ${staged}/superball.1.in @ONLY)
install(CODE "
  set(SUPERBALL_PREFIX \"\${CMAKE_INSTALL_PREFIX}\")
  configure_file(\"${staged}/superball.pc.in\" \"${staged}/superball.pc\" @ONLY)
  configure_file(\"${staged}/superball.1.in\" \"${staged}/superball.1\" @ONLY)
  file(INSTALL \"${staged}/superball.pc\" DESTINATION \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/pkgconfig\")
  file(INSTALL \"${staged}/superball.1\" DESTINATION \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_MANDIR}/man1\")")

install(DIRECTORY ${PROJECT_SOURCE_DIR}/cases/scenes/ DESTINATION ${SUPERBALL_SCENES_INSTALL_DIR} FILES_MATCHING PATTERN "*.toml")
