# cmake --install: the components' libraries and public headers (lib/*/include, format/include,
# the generated version.hpp; never lib/core/internal), libmosb.so with the C ABI, the mosb program
# (when built), the CMake package (mosbConfig.cmake: mosb::core, ::pack, ::store, ::solutions,
# ::stats, ::run, ::pull, the umbrella mosb::mosb, the C ABI mosb::c and mosb::c_static) and pkg-config files.
include(CMakePackageConfigHelpers)

set(mosb_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/mosb)
set(mosb_components core pack store solutions stats run)
if(TARGET mosb_pull)  # built when libcurl is there (lib/pull/CMakeLists.txt)
  list(APPEND mosb_components pull)
endif()
list(TRANSFORM mosb_components PREPEND mosb_ OUTPUT_VARIABLE mosb_component_targets)
install(TARGETS ${mosb_component_targets} mosb_cxx mosb_c_shared mosb_c mosb_c_compat
        EXPORT mosbTargets
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} NAMELINK_COMPONENT Development
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(component ${mosb_components} c)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/lib/${component}/include/
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h" PATTERN "*.hpp")
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/format/include/ ${PROJECT_BINARY_DIR}/lib/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.hpp")
if(MOSB_BUILD_TOOLS)
  install(TARGETS mosb RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
# The example solvers' sources, which build against the installed package (examples/CMakeLists.txt).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/ DESTINATION ${CMAKE_INSTALL_DATADIR}/mosb/examples)
# The shipped solver profiles (also embedded in the program: mosb run --profile NAME).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/profiles/ DESTINATION ${CMAKE_INSTALL_DATADIR}/mosb/profiles
        FILES_MATCHING PATTERN "*.toml")

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

# pkg-config: mosb-core.pc (the reader alone), mosb.pc (every C++ component) and mosb_c.pc (the C
# ABI, libmosb.so). A static library's own dependencies must appear in plain `--libs` (most users
# do not pass --static); a shared one hides them.
if(BUILD_SHARED_LIBS)
  set(mosb_requires "Requires.private:")
else()
  set(mosb_requires "Requires:")
endif()
set(MOSB_PC_CORE_REQUIRES "${mosb_requires} libxxhash")
set(MOSB_PC_REQUIRES "${mosb_requires} libxxhash libzstd libcrypto")
# The files name their prefix relative to where they lie, so a moved prefix (or
# `cmake --install --prefix`) still works.
file(RELATIVE_PATH MOSB_PC_PREFIX_FROM_PCDIR /root/${CMAKE_INSTALL_LIBDIR}/pkgconfig /root)
string(REGEX REPLACE "/$" "" MOSB_PC_PREFIX_FROM_PCDIR "${MOSB_PC_PREFIX_FROM_PCDIR}")
foreach(pc mosb mosb-core mosb_c)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/${pc}.pc.in ${PROJECT_BINARY_DIR}/${pc}.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/${pc}.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endforeach()
