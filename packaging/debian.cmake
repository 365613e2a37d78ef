# The Debian package (scripts/package-deb.sh runs cpack -G DEB): the plugin in the folder the
# installed meshlab reads, support-slim in /usr/bin with its man page, the README and the .mlx
# examples in /usr/share/doc/<package>. It depends on exactly the meshlab version it was built
# against (MeshLab refuses a plugin of another version, and libmeshlab-common.so has no stable
# ABI), and through dpkg-shlibdeps on the libraries it links (CHOLMOD, TetGen, Qt, OpenMP);
# OpenBLAS is named as well, because CHOLMOD runs several times faster with it than with the
# reference BLAS.
set(SLIM_DEB_PACKAGE "meshlab-support-slimming")
set(SLIM_DEB_MAINTAINER "support-slimming maintainers <support-slimming@users.noreply.github.com>" CACHE STRING
    "Maintainer field of the Debian package")
execute_process(COMMAND dpkg-query -W "-f=\${Version}" meshlab OUTPUT_VARIABLE SLIM_DEB_MESHLAB_VERSION
                ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
execute_process(COMMAND dpkg --print-architecture OUTPUT_VARIABLE SLIM_DEB_ARCH ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
execute_process(COMMAND sh -c ". /etc/os-release && echo \${VERSION_CODENAME:-unstable}" OUTPUT_VARIABLE SLIM_DEB_DISTRIBUTION
                ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
# The Debian revision names the MeshLab it is for: one package per MeshLab release.
set(SLIM_DEB_VERSION "${PROJECT_VERSION}-1+meshlab${MESHLAB_VERSION}")
if(NOT SLIM_DEB_MESHLAB_VERSION)
  message(WARNING "meshlab is not installed (dpkg-query): the Debian package cannot be made here")
endif()
set(doc "share/doc/${SLIM_DEB_PACKAGE}")

# Debian policy: copyright as is, changelog gzip -9n (no name, no time stamp).
configure_file("${CMAKE_CURRENT_LIST_DIR}/changelog.Debian.in" "${CMAKE_BINARY_DIR}/deb/changelog.Debian" @ONLY)
add_custom_command(OUTPUT "${CMAKE_BINARY_DIR}/deb/changelog.Debian.gz"
  COMMAND gzip -9nkf "${CMAKE_BINARY_DIR}/deb/changelog.Debian"
  DEPENDS "${CMAKE_BINARY_DIR}/deb/changelog.Debian")
add_custom_target(slim_deb_changelog ALL DEPENDS "${CMAKE_BINARY_DIR}/deb/changelog.Debian.gz")
install(FILES "${CMAKE_CURRENT_LIST_DIR}/copyright" "${CMAKE_BINARY_DIR}/deb/changelog.Debian.gz"
        DESTINATION "${doc}" COMPONENT deb_only EXCLUDE_FROM_ALL)
install(FILES "${PROJECT_SOURCE_DIR}/README.md" DESTINATION "${doc}" COMPONENT deb_only EXCLUDE_FROM_ALL)

# support-slim's man page, made from its own --help and --version by help2man (Debian's help2man),
# so it says what the binary in the package says; gzip -9n as the changelog. help2man runs the
# binary, hence the dependency on the target.
find_program(SLIM_HELP2MAN help2man)
if(SLIM_HELP2MAN)
  set(slim_man "${CMAKE_BINARY_DIR}/deb/support-slim.1")
  add_custom_command(OUTPUT "${slim_man}.gz"
    COMMAND "${SLIM_HELP2MAN}" --no-info --section=1
            "--name=reshape a mesh so that it needs less support material when 3D printed"
            "--include=${CMAKE_CURRENT_LIST_DIR}/support-slim.h2m" "--output=${slim_man}" "$<TARGET_FILE:support-slim>"
    COMMAND gzip -9nf "${slim_man}"
    DEPENDS support-slim "${CMAKE_CURRENT_LIST_DIR}/support-slim.h2m"
    COMMENT "Generating support-slim.1.gz (help2man)"
    VERBATIM)
  add_custom_target(slim_deb_man ALL DEPENDS "${slim_man}.gz")
  install(FILES "${slim_man}.gz" DESTINATION share/man/man1 COMPONENT deb_only EXCLUDE_FROM_ALL)
else()
  add_custom_target(slim_deb_man COMMAND "${CMAKE_COMMAND}" -E echo
                    "help2man is missing (apt-get install help2man): the package would have no man page" COMMAND false)
  message(WARNING "help2man is missing (apt-get install help2man): support-slim's man page cannot be made")
endif()
# The pages the README links to, beside it as in the source tree.
file(GLOB slim_doc_pages "${PROJECT_SOURCE_DIR}/docs/*.md" "${PROJECT_SOURCE_DIR}/docs/*.png")
install(FILES ${slim_doc_pages} DESTINATION "${doc}/docs" COMPONENT deb_only EXCLUDE_FROM_ALL)
file(GLOB slim_mlx_examples "${PROJECT_SOURCE_DIR}/examples/*.mlx")
install(FILES ${slim_mlx_examples} DESTINATION "${doc}/examples" COMPONENT deb_only EXCLUDE_FROM_ALL)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME "${SLIM_DEB_PACKAGE}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_PACKAGE_DIRECTORY "${CMAKE_BINARY_DIR}/packages")
set(CPACK_DEBIAN_PACKAGE_NAME "${SLIM_DEB_PACKAGE}")
set(CPACK_DEBIAN_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_DEBIAN_PACKAGE_RELEASE "1+meshlab${MESHLAB_VERSION}")
set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE "${SLIM_DEB_ARCH}")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${SLIM_DEB_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "https://github.com/support-slimming/support-slimming")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "MeshLab filters that cut the support material of 3D prints")
# The synopsis is the summary; CPack puts the description below it.
set(CPACK_PACKAGE_DESCRIPTION "Overhang Analysis colours and selects the faces of a mesh that need support
when it is 3D printed. Support Slimming reshapes the mesh, as rigidly as
possible, so that fewer faces overhang (Direct Computation of Minimal Rotation
for Support Slimming), and Print Orientation finds the print pose that needs
the least support. The filters appear in MeshLab's Filters menu and in
meshlabserver scripts; support-slim runs the same optimizer from the command
line.")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "meshlab (= ${SLIM_DEB_MESHLAB_VERSION}), libopenblas0-pthread")
# One package: what cmake --install installs (the plugin and support-slim) plus the package's own
# documentation files, which a plain cmake --install leaves out.
set(CPACK_COMPONENTS_ALL Unspecified deb_only)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
include(CPack)
