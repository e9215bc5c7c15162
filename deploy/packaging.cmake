# Debian packages (CPack DEB), one per component (issue 3):
#   kapfix-agent    the platform: kapfix-agent, kapfix-keygen, the systemd unit, the
#                   configuration (/etc/kapfix/agent.json, from resources/kite.json) and the
#                   examples; postinst creates the service's user (deploy/debian/agent/)
#   kapfix-station  the operator's laptop: kapfix-station, kapfix-ctl, kapfix-analyze
# deploy/check-agent-deb.sh installs the agent's into a clean Debian root and checks it.
# Build them with:  cmake --build build/default && cpack --config build/default/CPackConfig.cmake
# Release .debs: configure with -DKAPFIX_REQUIRE_HARDWARE=ON (agent/CMakeLists.txt), so that a
# host without Aravis, libusb or libsystemd fails instead of packaging a lesser agent.
#
# Included at the end of the top-level CMakeLists.txt, after every add_subdirectory, so that
# the executables' targets exist if they are built at all; each install() is guarded, so the
# build and the packages work before kapfix-agent or kapfix-station exist (the packages then
# just lack those programs).

include(GNUInstallDirs)

set(KAPFIX_SYSTEMD_UNIT_DIR "/lib/systemd/system" CACHE PATH
    "Where the Debian package installs kapfix-agent.service")

# --- agent -------------------------------------------------------------------------------
foreach(program IN ITEMS kapfix-agent kapfix-keygen)
  if(TARGET ${program})
    install(TARGETS ${program} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT agent)
  endif()
endforeach()
install(FILES ${PROJECT_SOURCE_DIR}/deploy/kapfix-agent.service
        DESTINATION ${KAPFIX_SYSTEMD_UNIT_DIR} COMPONENT agent)
# Lets the agent (group plugdev) open a Maestro's native USB interface to set its serial
# timeout and home positions (agent/servo/libusb_maestro_usb_port.hpp).
install(FILES ${PROJECT_SOURCE_DIR}/deploy/udev/99-kapfix-maestro.rules
              ${PROJECT_SOURCE_DIR}/deploy/udev/99-kapfix-usb3vision.rules
        DESTINATION /lib/udev/rules.d COMPONENT agent)
# /dev/i2c-N for PCA9685 boards needs i2c-dev, loaded at every boot.
install(FILES ${PROJECT_SOURCE_DIR}/deploy/kapfix-i2c.conf
        DESTINATION /usr/lib/modules-load.d RENAME kapfix.conf COMPONENT agent)
# The kite rig is the default configuration; the operator edits it (a conffile: upgrades keep
# local changes).
install(FILES ${PROJECT_SOURCE_DIR}/resources/kite.json
        DESTINATION /etc/kapfix RENAME agent.json COMPONENT agent)
install(FILES ${PROJECT_SOURCE_DIR}/resources/kite.json ${PROJECT_SOURCE_DIR}/resources/boat.json
        DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/kapfix-agent/examples COMPONENT agent)
install(FILES ${PROJECT_SOURCE_DIR}/resources/README.md
        DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/kapfix-agent RENAME configuration.md
        COMPONENT agent)
install(FILES ${PROJECT_SOURCE_DIR}/README.md
        DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/kapfix-agent COMPONENT agent)

# --- station -----------------------------------------------------------------------------
set(KAPFIX_STATION_HAS_FILES OFF)
foreach(program IN ITEMS kapfix-station kapfix-ctl kapfix-analyze)
  if(TARGET ${program})
    # kapfix-analyze also has a component-less install rule of its own (plain
    # `cmake --install`); this one puts it in the station package.
    install(TARGETS ${program} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT station)
    set(KAPFIX_STATION_HAS_FILES ON)
  endif()
endforeach()

# --- CPack -------------------------------------------------------------------------------
set(CPACK_GENERATOR "DEB")
set(CPACK_PACKAGE_NAME "kapfix")
set(CPACK_PACKAGE_VENDOR "kapfix")
set(CPACK_PACKAGE_CONTACT "kapfix maintainers <kapfix@localhost>")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Keeps a camera locked on a view while its platform swings")
set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
set(CPACK_DEB_COMPONENT_INSTALL ON)
# Only the two components (kapfix-analyze's component-less rule stays out), and the station
# only once something is built for it: CPack refuses an empty package.
set(CPACK_COMPONENTS_ALL agent)
if(KAPFIX_STATION_HAS_FILES)
  list(APPEND CPACK_COMPONENTS_ALL station)
endif()

set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_STRIP_FILES ON)  # the build is RelWithDebInfo; the packages need no symbols
set(CPACK_DEBIAN_PACKAGE_SECTION "science")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)  # Depends: from the linked libraries (dpkg-shlibdeps)

set(CPACK_DEBIAN_AGENT_PACKAGE_NAME "kapfix-agent")
set(CPACK_COMPONENT_AGENT_DESCRIPTION
    "kapfix agent: camera fixation on a kite line or a boat, headless, with its systemd unit")
# adduser for postinst; udev for the device rules. The libraries come from dpkg-shlibdeps
# (no Qt: the agent does not link it; deploy/check-agent-deb.sh checks).
set(CPACK_DEBIAN_AGENT_PACKAGE_DEPENDS "adduser, udev")
# The scene photos `kapfix-agent --sim` flies over (and its --preflight checks).
set(CPACK_DEBIAN_AGENT_PACKAGE_RECOMMENDS "opencv-doc")
set(CPACK_DEBIAN_AGENT_PACKAGE_CONTROL_EXTRA
    ${PROJECT_SOURCE_DIR}/deploy/debian/agent/conffiles
    ${PROJECT_SOURCE_DIR}/deploy/debian/agent/postinst
    ${PROJECT_SOURCE_DIR}/deploy/debian/agent/prerm
    ${PROJECT_SOURCE_DIR}/deploy/debian/agent/postrm)
set(CPACK_DEBIAN_AGENT_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)

set(CPACK_DEBIAN_STATION_PACKAGE_NAME "kapfix-station")
set(CPACK_COMPONENT_STATION_DESCRIPTION
    "kapfix ground station: live video, displacement graphs, slice selection, photos")

include(CPack)
