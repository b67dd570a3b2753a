# package.cmake - how programs outside the tree find an installed
# libmpbench: a pkg-config file (libmpbench.pc) and a CMake package
# (find_package(mpbench) -> mpbench::mpbench). Included from
# libmpbench/CMakeLists.txt after the install(TARGETS ... EXPORT) rule.
include(CMakePackageConfigHelpers)

set(MPB_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/mpbench)
install(EXPORT mpbenchTargets NAMESPACE mpbench::
  FILE mpbenchTargets.cmake DESTINATION ${MPB_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/mpbenchConfig.cmake.in
  ${CMAKE_BINARY_DIR}/cmake/mpbenchConfig.cmake
  INSTALL_DESTINATION ${MPB_CMAKE_DIR})
# 0.x: no compatibility promised across minor versions yet.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/mpbenchConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/mpbenchConfig.cmake
              ${CMAKE_BINARY_DIR}/cmake/mpbenchConfigVersion.cmake
  DESTINATION ${MPB_CMAKE_DIR})

# The static library's own dependencies, for `pkg-config --static`. FCL's
# .pc carries -std=c++11 in its cflags, which must not reach a C
# compiler, so FCL goes in as plain linker flags rather than a Requires.
list(TRANSFORM FCL_LIBRARIES PREPEND "-l" OUTPUT_VARIABLE MPB_PC_FCL_LIBS)
string(REPLACE ";" " " MPB_PC_FCL_LIBS "${MPB_PC_FCL_LIBS}")
# The prefix is the one of the install, not of the configure: written when
# installing, so `cmake --install --prefix P` gets a libmpbench.pc for P.
install(CODE "
  set(MPB_PC_PREFIX \"\${CMAKE_INSTALL_PREFIX}\")
  set(MPB_PC_LIBDIR \"${CMAKE_INSTALL_LIBDIR}\")
  set(MPB_PC_INCLUDEDIR \"${CMAKE_INSTALL_INCLUDEDIR}\")
  set(MPB_PC_VERSION \"${PROJECT_VERSION}\")
  set(MPB_PC_FCL_LIBS \"${MPB_PC_FCL_LIBS}\")
  configure_file(\"${CMAKE_CURRENT_LIST_DIR}/libmpbench.pc.in\"
                 \"${CMAKE_BINARY_DIR}/cmake/libmpbench.pc\" @ONLY)")
install(FILES ${CMAKE_BINARY_DIR}/cmake/libmpbench.pc
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
