# Debian package: in the build folder, `cpack -G DEB` writes hemirad_VERSION_amd64.deb
# (everything install.cmake installs, under /usr). The version is project(VERSION ...);
# library dependencies come from dpkg-shlibdeps.
set(CPACK_PACKAGE_NAME hemirad)
set(CPACK_PACKAGE_VENDOR hemirad)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "radiosity engine: progressive shooting with GPU hemicube form factors")
set(CPACK_PACKAGE_CONTACT "hemirad developers <hemirad@localhost>")
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT) # hemirad_0.1.0_amd64.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# libhemirad is in the package itself: dpkg-shlibdeps finds it there, not in another package.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${CMAKE_BINARY_DIR})
# Not linked, so not found by dpkg-shlibdeps: libEGL.so.1, which glad opens at run time, and
# Mesa's EGL and software GL drivers behind it; recommended: Python and numpy for the
# module, glm for the public headers.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libegl1, libegl-mesa0, libgl1-mesa-dri")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3 (>= 3.11), python3 (<< 3.12), python3-numpy, libglm-dev")
include(CPack)
