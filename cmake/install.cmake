# Installation: the four programs; the engine as a library another CMake project
# can use (find_package(Aperture) and Aperture::engine); a .deb by CPack. Components: `runtime`
# (the programs, what deploy/Dockerfile installs) and `development` (libraries, headers, the
# package config and the schema). tests/install/check_install.sh installs both into a temporary
# prefix, builds tests/install/consumer/ against it, and builds and unpacks the .deb.
include(CMakePackageConfigHelpers)

install(TARGETS aperture-server aperture aperture-render aperture-tex
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)

# The engine and what it links of ours (static libraries).
install(TARGETS aperture_engine aperture_proto aperture_service_proto aperture_import
        EXPORT ApertureTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development)
# Headers under include/aperture/, in the engine's folders (the engine includes "scene/scene.h";
# a user writes <aperture/scene/scene.h>). Only the tools' and the tests' code stays out.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/aperture COMPONENT development
        FILES_MATCHING PATTERN "*.h"
        PATTERN "tools" EXCLUDE PATTERN "testing" EXCLUDE PATTERN "data" EXCLUDE)
install(FILES ${PROJECT_SOURCE_DIR}/import/gltf_import.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/aperture COMPONENT development)
# The generated messages (scene and service, no gRPC stubs) and the schema they come from.
install(FILES ${PROJECT_BINARY_DIR}/proto/aperture/v1/scene.pb.h
              ${PROJECT_BINARY_DIR}/proto/aperture/v1/render_service.pb.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/aperture/v1 COMPONENT development)
install(FILES ${PROJECT_BINARY_DIR}/proto/grpc/health/v1/health.pb.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/grpc/health/v1 COMPONENT development)
install(FILES ${PROJECT_SOURCE_DIR}/proto/aperture/v1/scene.proto
              ${PROJECT_SOURCE_DIR}/proto/aperture/v1/render_service.proto
        DESTINATION ${CMAKE_INSTALL_DATADIR}/aperture/proto/aperture/v1 COMPONENT development)

set(APERTURE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Aperture)
install(EXPORT ApertureTargets NAMESPACE Aperture:: DESTINATION ${APERTURE_CMAKE_DIR}
        COMPONENT development)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ApertureConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/ApertureConfig.cmake
                              INSTALL_DESTINATION ${APERTURE_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ApertureConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/ApertureConfig.cmake
              ${PROJECT_BINARY_DIR}/ApertureConfigVersion.cmake
        DESTINATION ${APERTURE_CMAKE_DIR} COMPONENT development)

# cpack -G DEB: one package with both components, its dependencies read off the binaries by
# dpkg-shlibdeps (dpkg-dev, with build-essential).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME aperture)
set(CPACK_PACKAGE_VENDOR "Aperture")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Render service for visual simulation: exact edges, prefiltered anisotropic textures")
set(CPACK_PACKAGE_CONTACT "Aperture developers <aperture@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_STRIP_FILES ON)
include(CPack)
