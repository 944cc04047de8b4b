# Shared compile settings for our own targets (warnings, sanitizers).
function(lumaslam_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  if(NOT LUMASLAM_SANITIZE)
    return()
  endif()
  target_link_options(${target} PRIVATE -fsanitize=${LUMASLAM_SANITIZE})
  if(LUMASLAM_SANITIZE MATCHES "address")
    # Eigen assumes glibc's malloc is 16-byte aligned except when __SANITIZE_ADDRESS__ is set;
    # then it over-allocates and frees with its own offset. Ceres and OpenCV are not rebuilt
    # with ASan, so an Eigen matrix allocated inside libceres (GradientChecker's Jacobians)
    # and freed in our code would be freed at the wrong address. Keep one convention: ASan's
    # malloc is 16-byte aligned on x86-64 too.
    target_compile_definitions(${target} PRIVATE EIGEN_MALLOC_ALREADY_ALIGNED=1)
  endif()
  if(target MATCHES "${LUMASLAM_SANITIZE_TARGETS}")
    # -O1 (after the build type's -O3, so it wins): sanitizer builds compile much faster and
    # keep usable stack traces; their reports do not depend on the optimisation level.
    target_compile_options(${target} PRIVATE -fsanitize=${LUMASLAM_SANITIZE} -fno-omit-frame-pointer
                                             -g -O1)
  endif()
endfunction()

# lumaslam_add_module(NAME DEPS dep...): one static library per folder of src/lumaslam,
# named lumaslam_NAME, built from every .cpp in that folder. DEPS are other modules' or
# packages' targets. Modules build separately so one module's tests never wait on another.
function(lumaslam_add_module name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  set(target lumaslam_${name})
  if(NOT sources)  # header-only (or not yet written) module
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
    set_property(GLOBAL APPEND PROPERTY LUMASLAM_MODULES ${target})
    return()
  endif()
  add_library(${target} STATIC ${sources})
  target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(${target} PUBLIC ${ARG_DEPS})
  lumaslam_target_defaults(${target})
  set_property(GLOBAL APPEND PROPERTY LUMASLAM_MODULES ${target})
endfunction()
