# Install rules: cmake --install build --prefix P puts
#   bin/       hemirad and the other tools (RPATH $ORIGIN/../lib, so any prefix works)
#   lib/       libhemirad.so.MAJOR.MINOR (+ links), the CMake package, hemirad.pc
#   include/   hemirad/*.h (the public API; hemirad/hemirad.h includes it all)
#   lib/python3/dist-packages/hemirad*.so (python/CMakeLists.txt)
# Shaders are embedded into libhemirad at build time: nothing else is read at run time.
include(CMakePackageConfigHelpers)

set(HEMIRAD_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/hemirad)

foreach(tool hemirad hemirad-preview hemirad-bench hemirad-view)
  if(TARGET ${tool})
    set_target_properties(${tool} PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
    install(TARGETS ${tool} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endforeach()

install(TARGETS hemirad_core EXPORT hemiradTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/include/hemirad DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
install(FILES ${CMAKE_BINARY_DIR}/generated/include/hemirad/version.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hemirad)

install(EXPORT hemiradTargets NAMESPACE hemirad:: DESTINATION ${HEMIRAD_CMAKE_DIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/hemiradConfig.cmake.in
  ${CMAKE_BINARY_DIR}/generated/hemiradConfig.cmake INSTALL_DESTINATION ${HEMIRAD_CMAKE_DIR})
# 0.x: only the same minor version is compatible (as the SONAME says).
write_basic_package_version_file(${CMAKE_BINARY_DIR}/generated/hemiradConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/generated/hemiradConfig.cmake
              ${CMAKE_BINARY_DIR}/generated/hemiradConfigVersion.cmake
        DESTINATION ${HEMIRAD_CMAKE_DIR})

# pkg-config: relocatable (the prefix found from the .pc file's own folder), so that
# --prefix P and the Debian package's /usr both work.
file(RELATIVE_PATH HEMIRAD_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" HEMIRAD_PC_TO_PREFIX "${HEMIRAD_PC_TO_PREFIX}")
configure_file(${CMAKE_SOURCE_DIR}/cmake/hemirad.pc.in ${CMAKE_BINARY_DIR}/generated/hemirad.pc
               @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/generated/hemirad.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
