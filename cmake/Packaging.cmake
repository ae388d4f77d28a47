# The licence and docs go beside the binaries; `cpack -G DEB` packs everything install() names
# into a Debian package whose dependencies dpkg-shlibdeps reads from the binaries.
include(GNUInstallDirs)
if(BONELESS_INSTALL)
  # The README is the manual: the docs/ pages it links to go with it, at the same relative paths.
  install(FILES ${CMAKE_SOURCE_DIR}/LICENSE ${CMAKE_SOURCE_DIR}/README.md
          DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/boneless)
  install(DIRECTORY ${CMAKE_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/boneless/docs)
  # Debian's place for the licence: /usr/share/doc/<package>/copyright.
  install(FILES ${CMAKE_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/boneless
          RENAME copyright)
endif()

set(CPACK_PACKAGE_NAME boneless)
set(CPACK_PACKAGE_VENDOR "The Boneless authors")
set(CPACK_PACKAGE_CONTACT "The Boneless authors <boneless@invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "skeleton-free mesh animation from motion-capture markers")
# One string: set() of several strings makes a list, whose ";" began the package's lines.
string(CONCAT CPACK_PACKAGE_DESCRIPTION
       "Boneless turns the markers of a C3D take into mesh animation without a\n"
       "skeleton: a desktop application (boneless) for mapping markers and\n"
       "previewing, and a command-line tool (boneless-cli) for solving takes into\n"
       "OBJ sequences, point caches or glTF animations.")
set(CPACK_RESOURCE_FILE_LICENSE ${CMAKE_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGE_INSTALL_DIRECTORY boneless)
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The symbols are a sixth of each binary (0.6 MB) and help no user of the package.
set(CPACK_STRIP_FILES ON)
# An OpenGL driver and a font are loaded at run time, so they are not in the binaries' library list.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libgl1-mesa-dri, fonts-dejavu-core")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
configure_file(${PROJECT_SOURCE_DIR}/cmake/PackageVersion.cmake.in
               ${PROJECT_BINARY_DIR}/PackageVersion.cmake @ONLY)
set(CPACK_PROJECT_CONFIG_FILE ${PROJECT_BINARY_DIR}/PackageVersion.cmake)
include(CPack)
