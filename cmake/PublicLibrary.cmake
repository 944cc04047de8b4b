# The installed package (docs/api.md): the shared library lumaslam::lumaslam with only the
# public API exported (system.h, dataset.h, evaluate.h), its headers, lumaslamConfig.cmake and
# the configs. The library's own dependencies (Ceres, TBB, spdlog, ...) are linked in privately
# and hidden, so a consumer needs only OpenCV's core and Eigen, which the public headers use.
set(LUMASLAM_PUBLIC_HEADERS
    ${PROJECT_SOURCE_DIR}/src/lumaslam/system.h
    ${PROJECT_SOURCE_DIR}/src/lumaslam/camera_pose.h
    ${PROJECT_SOURCE_DIR}/src/lumaslam/dataset.h
    ${PROJECT_SOURCE_DIR}/src/lumaslam/evaluate.h
    ${PROJECT_SOURCE_DIR}/src/lumaslam/export.h)

add_library(lumaslam_shared SHARED ${LUMASLAM_PUBLIC_SOURCES})
add_library(lumaslam::lumaslam ALIAS lumaslam_shared)
set_target_properties(lumaslam_shared PROPERTIES
  OUTPUT_NAME lumaslam EXPORT_NAME lumaslam
  VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}
  CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
# The static libraries it is built on stay inside it: none of their symbols is exported.
target_link_libraries(lumaslam_shared PRIVATE lumaslam PUBLIC opencv_core Eigen3::Eigen)
lumaslam_target_defaults(lumaslam_shared)
target_link_options(lumaslam_shared PRIVATE "LINKER:--exclude-libs,ALL")
target_include_directories(lumaslam_shared INTERFACE
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/src> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_compile_features(lumaslam_shared INTERFACE cxx_std_17)

install(TARGETS lumaslam_shared EXPORT lumaslamTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(FILES ${LUMASLAM_PUBLIC_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lumaslam)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/configs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/lumaslam/configs)
install(EXPORT lumaslamTargets NAMESPACE lumaslam:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/lumaslam)

include(CMakePackageConfigHelpers)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/lumaslamConfig.cmake.in
  ${PROJECT_BINARY_DIR}/lumaslamConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/lumaslam
  PATH_VARS CMAKE_INSTALL_DATADIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/lumaslamConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/lumaslamConfig.cmake
              ${PROJECT_BINARY_DIR}/lumaslamConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/lumaslam)
