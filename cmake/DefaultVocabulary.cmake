# The default place-recognition vocabulary (data/vocabulary/README.md): where
# loop/vocabulary_choice.cpp looks for it (the source tree, the install prefix, and the install
# folder relative to the installed executable and to the installed shared library), and its
# install rule. Included after the modules are added; the definitions go on that one source
# file so that moving the tree or changing the prefix recompiles nothing else.
set(LUMASLAM_DEFAULT_VOCABULARY "${PROJECT_SOURCE_DIR}/data/vocabulary/lumaslam_orb_k8l5.bin")

get_filename_component(vocabulary_name ${LUMASLAM_DEFAULT_VOCABULARY} NAME)
get_filename_component(vocabulary_source_dir ${LUMASLAM_DEFAULT_VOCABULARY} DIRECTORY)
set(vocabulary_install_dir ${CMAKE_INSTALL_FULL_DATADIR}/lumaslam)
file(RELATIVE_PATH bin_to_vocabulary_dir ${CMAKE_INSTALL_FULL_BINDIR} ${vocabulary_install_dir})
file(RELATIVE_PATH lib_to_vocabulary_dir ${CMAKE_INSTALL_FULL_LIBDIR} ${vocabulary_install_dir})
set_source_files_properties(
  ${PROJECT_SOURCE_DIR}/src/lumaslam/loop/vocabulary_choice.cpp
  DIRECTORY ${PROJECT_SOURCE_DIR}/src/lumaslam/loop
  PROPERTIES COMPILE_DEFINITIONS
  "LUMASLAM_DEFAULT_VOCABULARY_NAME=\"${vocabulary_name}\";LUMASLAM_SOURCE_VOCABULARY_DIR=\"${vocabulary_source_dir}\";LUMASLAM_INSTALL_VOCABULARY_DIR=\"${vocabulary_install_dir}\";LUMASLAM_BIN_TO_VOCABULARY_DIR=\"${bin_to_vocabulary_dir}\";LUMASLAM_LIB_TO_VOCABULARY_DIR=\"${lib_to_vocabulary_dir}\"")

install(FILES ${LUMASLAM_DEFAULT_VOCABULARY} DESTINATION ${CMAKE_INSTALL_DATADIR}/lumaslam)
