# The Debian package (issue 29, part 3): what is installed where, the man
# pages, the Debian documentation files and the CPack DEB settings.
# `packaging/setup.sh deb` (or `cpack -G DEB` in the build folder) builds
# paintlab_<version>-<release>_amd64.deb; docs/PACKAGING.md lists the layout
# and what lintian says about it.
#
# Installed layout (prefix /usr), each program finding its files relative to
# its own executable, never through an environment variable:
#   bin/paintlab, bin/paintlab-cli          the workstation, the command line
#   libexec/paintlab/paintlab-cli-full      the CLI's helper (cli/CMakeLists.txt)
#   lib/paintlab/plugins/                   plugins (plugins/CMakeLists.txt; registry.cpp)
#   share/paintlab/{recipes,scenes,ingredients,measurements}/   demo data
#                                           (gui/src/workstation_paths.cpp)
#   share/applications, share/icons         desktop entry and icon
#   share/man/man1                          man pages made from --help (help2man)
#   share/doc/paintlab                      copyright, changelog.Debian.gz, changelog.gz
include(GNUInstallDirs)

set(PAINTLAB_DEB_RELEASE 1)  # the Debian revision: bump when only the packaging changes
set(PAINTLAB_MAINTAINER "PaintLab maintainers <maintainers@users.noreply.h-seed-185da851.example>")
set(packaging_dir ${PROJECT_SOURCE_DIR}/packaging)
set(doc_dir ${CMAKE_INSTALL_DATADIR}/doc/paintlab)

# Demo data: the recipes, scenes and the database seed (ingredients and the
# made-up panel measurement; `db init` compiles the same files in, so the
# installed copies are for the user to read, open and import).
foreach(folder recipes scenes ingredients measurements)
  install(DIRECTORY ${PAINTLAB_DEMO_DIR}/${folder} DESTINATION ${CMAKE_INSTALL_DATADIR}/paintlab
    COMPONENT data FILES_MATCHING PATTERN "*.json")
endforeach()

if(TARGET paintlab)
  install(TARGETS paintlab RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT gui)
  install(FILES ${packaging_dir}/paintlab.desktop DESTINATION ${CMAKE_INSTALL_DATADIR}/applications COMPONENT gui)
  install(FILES ${packaging_dir}/paintlab.svg DESTINATION ${CMAKE_INSTALL_DATADIR}/icons/hicolor/scalable/apps
    COMPONENT gui)
endif()

# Debian wants every file compressed with gzip -9n (no name, no time stamp:
# the same bytes at every build).
find_program(PAINTLAB_GZIP gzip REQUIRED)

# Man pages from each program's --help (and its commands' --help), made at
# build time so they never drift from the options.
find_program(PAINTLAB_HELP2MAN help2man)
set(man_pages)
function(paintlab_man_page target name summary)
  set(page ${CMAKE_BINARY_DIR}/man/${name}.1)
  add_custom_command(OUTPUT ${page}.gz
    COMMAND ${CMAKE_COMMAND} -DHELP2MAN=${PAINTLAB_HELP2MAN} -DGZIP=${PAINTLAB_GZIP}
      -DPROGRAM=$<TARGET_FILE:${target}> -DSUMMARY=${summary} -DVERSION=${PROJECT_VERSION}
      -DINCLUDE=${packaging_dir}/man/${name}.h2m -DOUTPUT=${page} ${ARGN} -P ${PROJECT_SOURCE_DIR}/cmake/PaintLabManPage.cmake
    DEPENDS ${target} ${packaging_dir}/man/${name}.h2m ${PROJECT_SOURCE_DIR}/cmake/PaintLabManPage.cmake
    COMMENT "Man page ${name}.1 from ${name} --help" VERBATIM)
  set(man_pages ${man_pages} ${page}.gz PARENT_SCOPE)
  install(FILES ${page}.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT data)
endfunction()
if(PAINTLAB_HELP2MAN)
  # paintlab-cli's helper must exist too: the front end runs it for `mc --help` and the others.
  paintlab_man_page(paintlab_cli paintlab-cli "PaintLab command line: paint recipes, BRDFs, ray maps, database"
    -DCOMMANDS=ON)
  if(TARGET paintlab)
    # The workstation parses --help before it opens a window, but Qt needs a
    # platform even for that: the offscreen one, no display needed.
    paintlab_man_page(paintlab paintlab "PaintLab workstation: paint recipes, BRDF plots and a relit scene"
      -DQT_OFFSCREEN=ON)
  endif()
else()
  message(STATUS "help2man not found: no man pages (packaging/setup.sh deps installs it)")
endif()

# /usr/share/doc/paintlab: the copyright file, the Debian changelog (one
# entry per packaged version) and the project's own changelog.
configure_file(${packaging_dir}/debian/changelog.Debian.in ${CMAKE_BINARY_DIR}/debian/changelog.Debian @ONLY)
set(doc_files ${CMAKE_BINARY_DIR}/debian/changelog.Debian.gz ${CMAKE_BINARY_DIR}/debian/changelog.gz)
add_custom_command(OUTPUT ${CMAKE_BINARY_DIR}/debian/changelog.Debian.gz
  COMMAND ${PAINTLAB_GZIP} -9nfk ${CMAKE_BINARY_DIR}/debian/changelog.Debian
  DEPENDS ${CMAKE_BINARY_DIR}/debian/changelog.Debian VERBATIM)
add_custom_command(OUTPUT ${CMAKE_BINARY_DIR}/debian/changelog.gz
  COMMAND ${PAINTLAB_GZIP} -9nc ${PROJECT_SOURCE_DIR}/docs/CHANGELOG.md > ${CMAKE_BINARY_DIR}/debian/changelog.gz
  DEPENDS ${PROJECT_SOURCE_DIR}/docs/CHANGELOG.md)
add_custom_target(paintlab_package_files ALL DEPENDS ${man_pages} ${doc_files})
install(FILES ${packaging_dir}/debian/copyright ${doc_files} DESTINATION ${doc_dir} COMPONENT data)

# CPack: one binary package holding every component above (and the CLI's).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME paintlab)
set(CPACK_PACKAGE_VENDOR "PaintLab")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT ${PAINTLAB_MAINTAINER})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "engineering workstation for paint laboratories")
set(CPACK_PACKAGE_DESCRIPTION
    "PaintLab composes multi-layer paints (binders, absorbing and scattering
pigments, metallic and interference flakes, clear coats) from an ingredient
database, computes their spectral BRDF with a fast layered model checked
against a Monte Carlo full model, relights a painted object from a
precomputed ray map, fits recipes to multi-angle measurements and writes
production sheets.

This package holds the Qt workstation (paintlab), the scriptable command
line (paintlab-cli), the file-format plugins and the demo recipes, scenes
and ingredient library.")
set(CPACK_STRIP_FILES ON)
set(CPACK_INSTALL_DEFAULT_DIRECTORY_PERMISSIONS
    OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
set(CPACK_DEBIAN_PACKAGE_RELEASE ${PAINTLAB_DEB_RELEASE})
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # paintlab_0.1.0-1_amd64.deb
set(CPACK_DEBIAN_PACKAGE_MAINTAINER ${PAINTLAB_MAINTAINER})
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Depends: computed by dpkg-shlibdeps from the binaries and plugins, never listed by hand.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The courtyard demo scene lights the car with Blender's CC0 HDR environment.
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "blender-data, xvfb, xauth")
include(CPack)
