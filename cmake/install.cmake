# cmake --install: libmosb and libmosb_c, their headers, the mosb program (when built), the CMake
# package (mosbConfig.cmake, exporting mosb::mosb and mosb::mosb_c) and pkg-config files.
include(CMakePackageConfigHelpers)

set(mosb_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/mosb)
install(TARGETS mosb_lib mosb_c EXPORT mosbTargets
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} NAMELINK_COMPONENT Development
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/lib/include/ ${PROJECT_SOURCE_DIR}/format/include/
                  ${PROJECT_BINARY_DIR}/lib/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h" PATTERN "*.hpp")
if(MOSB_BUILD_TOOLS)
  install(TARGETS mosb RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

install(EXPORT mosbTargets NAMESPACE mosb:: DESTINATION ${mosb_cmake_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/mosbConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/mosbConfig.cmake
                              INSTALL_DESTINATION ${mosb_cmake_dir})
# Before 1.0 a minor release may break the API, so 0.2 accepts 0.2.x only.
if(PROJECT_VERSION_MAJOR EQUAL 0)
  set(mosb_compatibility SameMinorVersion)
else()
  set(mosb_compatibility SameMajorVersion)
endif()
write_basic_package_version_file(${PROJECT_BINARY_DIR}/mosbConfigVersion.cmake
                                 COMPATIBILITY ${mosb_compatibility})
install(FILES ${PROJECT_BINARY_DIR}/mosbConfig.cmake ${PROJECT_BINARY_DIR}/mosbConfigVersion.cmake
        DESTINATION ${mosb_cmake_dir})

# pkg-config: a static library's own dependencies must appear in plain `--libs` (most users do not
# pass --static); a shared one hides them.
if(BUILD_SHARED_LIBS)
  set(MOSB_PC_REQUIRES "Requires.private: libxxhash libcrypto libzstd")
  set(MOSB_PC_C_LIBS "")
  set(MOSB_PC_C_LIBS_PRIVATE "Libs.private: -lmosb -lstdc++ -lm")
else()
  set(MOSB_PC_REQUIRES "Requires: libxxhash libcrypto libzstd")
  set(MOSB_PC_C_LIBS " -lmosb -lstdc++ -lm")
  set(MOSB_PC_C_LIBS_PRIVATE "")
endif()
# The files name their prefix relative to where they lie, so a moved prefix (or
# `cmake --install --prefix`) still works.
file(RELATIVE_PATH MOSB_PC_PREFIX_FROM_PCDIR /root/${CMAKE_INSTALL_LIBDIR}/pkgconfig /root)
string(REGEX REPLACE "/$" "" MOSB_PC_PREFIX_FROM_PCDIR "${MOSB_PC_PREFIX_FROM_PCDIR}")
foreach(pc mosb mosb_c)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/${pc}.pc.in ${PROJECT_BINARY_DIR}/${pc}.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/${pc}.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endforeach()
