# A Debian package of what `cmake --install` installs, under /usr:
#
#   cmake --build build --target package     (or: cd build && cpack -G DEB)
#
# gives build/superball_VERSION_ARCH.deb.  Its run-time dependencies come from
# dpkg-shlibdeps (the shared libraries the command, the libraries and the
# Python module load: GiNaC, CLN, toml++, and Open MPI with the MPI runner),
# plus python3 and python3-numpy with the Python module; what a program built
# against the headers also needs (GiNaC's, CLN's, Eigen's and nlohmann-json's
# headers, pkg-config) is Recommends, so that installing the command does not
# pull in a compiler's worth of -dev packages.  docs/LIBRARY.md, "The Debian package".
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME superball)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_CONTACT "superball developers <superball@invalid>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)

set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # superball_0.2.0_amd64.deb
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# The synopsis is CPACK_PACKAGE_DESCRIPTION_SUMMARY; CPack indents these lines.
string(JOIN "\n" CPACK_DEBIAN_PACKAGE_DESCRIPTION
  "The superball command solves collisions of aligned balls exactly (double,"
  "long double, CLN floats, exact rationals) and derives, with GiNaC, each"
  "evolution case's admissibility conditions symbolically, after M. Fremond's"
  "theory of collisions.  The package holds the command, its manual page, the"
  "paper's scenes, the shared libraries with their headers, CMake package"
  "and pkg-config file, and the Python module when it was built.")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The package's own libraries, which dpkg-shlibdeps must not look for in
# another package.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${CMAKE_BINARY_DIR}/cases ${CMAKE_BINARY_DIR}/numeric
    ${CMAKE_BINARY_DIR}/symbolic ${CMAKE_BINARY_DIR}/verify ${CMAKE_BINARY_DIR}/present)
set(SUPERBALL_DEB_RECOMMENDS "libginac-dev, libcln-dev, libeigen3-dev, nlohmann-json3-dev, pkg-config")
if(SUPERBALL_BUILD_PYTHON)
  # dpkg-shlibdeps sees libpython's symbols as the interpreter's; the module needs NumPy at import.
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, python3-numpy")
endif()
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "${SUPERBALL_DEB_RECOMMENDS}")
# With the MPI runner the command loads Open MPI's library (libopenmpi3, found
# by dpkg-shlibdeps); launching it on several ranks needs mpirun besides.
# Built with -DSUPERBALL_WITH_MPI=OFF the package neither depends on nor
# suggests MPI (docs/LIBRARY.md, "The Debian package").
if(SUPERBALL_WITH_MPI)
  set(CPACK_DEBIAN_PACKAGE_SUGGESTS "openmpi-bin")
endif()
include(CPack)
