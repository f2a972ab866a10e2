# Install rules and the relocatable CMake package: after `cmake --install build --prefix P`, a project
# finds the libraries with `find_package(sedwave)` (CMAKE_PREFIX_PATH=P) and links e.g. sedwave::inversion
# (examples/12-own-model/CMakeLists.txt). In this tree the same names are ALIAS targets.
#
# Every library target named sedwave_<name> outside tests/, bench/ and examples/ is exported as
# sedwave::<name>, with the `sedwave` command as sedwave::sedwave; a new library needs no edit here.
# Three build-only details are kept out of the exported interface:
#   - include folders in the source or build tree (the installed headers are under include/);
#   - the warning policy (sedwave_warnings) and the generated version header (sedwave_version),
#     which static libraries would otherwise list as link dependencies of their users.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The targets defined in `dir` and the folders below it, tests/, bench/ and examples/ left out.
function(sedwave_collect_targets dir out)
  get_property(found DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(sub ${subdirs})
    file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR} ${sub})
    if(NOT rel MATCHES "^(tests|bench|examples)(/|$)")
      sedwave_collect_targets(${sub} below)
      list(APPEND found ${below})
    endif()
  endforeach()
  set(${out} ${found} PARENT_SCOPE)
endfunction()

sedwave_collect_targets(${PROJECT_SOURCE_DIR} sedwave_all_targets)
set(sedwave_exported_targets)
set(sedwave_header_dirs)
foreach(target ${sedwave_all_targets})
  get_target_property(type ${target} TYPE)
  if(target STREQUAL "sedwave")
    add_executable(sedwave::sedwave ALIAS sedwave)
    list(APPEND sedwave_exported_targets ${target})
    continue()
  endif()
  if(NOT type MATCHES "^(STATIC|SHARED)_LIBRARY$" OR NOT target MATCHES "^sedwave_(.+)$")
    continue()
  endif()
  set(name ${CMAKE_MATCH_1})
  add_library(sedwave::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  list(APPEND sedwave_exported_targets ${target})

  # Include folders: the tree's while building, the installed include/ for users.
  get_target_property(includes ${target} INTERFACE_INCLUDE_DIRECTORIES)
  if(includes)
    set(rewritten)
    foreach(dir ${includes})
      if(IS_ABSOLUTE "${dir}")
        list(APPEND rewritten "$<BUILD_INTERFACE:${dir}>")
        list(APPEND sedwave_header_dirs ${dir})
      else()
        list(APPEND rewritten "${dir}")
      endif()
    endforeach()
    list(APPEND rewritten "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
    set_property(TARGET ${target} PROPERTY INTERFACE_INCLUDE_DIRECTORIES "${rewritten}")
  endif()

  # A static library's private dependencies reach its users as $<LINK_ONLY:...>; the two
  # compile-only helpers have nothing to link.
  get_target_property(links ${target} INTERFACE_LINK_LIBRARIES)
  if(links)
    list(REMOVE_ITEM links "$<LINK_ONLY:sedwave_warnings>" "$<LINK_ONLY:sedwave_version>")
    set_property(TARGET ${target} PROPERTY INTERFACE_LINK_LIBRARIES "${links}")
  endif()
endforeach()
list(REMOVE_DUPLICATES sedwave_header_dirs)

install(TARGETS ${sedwave_exported_targets} EXPORT sedwaveTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(dir ${sedwave_header_dirs})
  install(DIRECTORY ${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.hpp")
endforeach()

set(sedwave_config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/sedwave)
install(EXPORT sedwaveTargets NAMESPACE sedwave:: DESTINATION ${sedwave_config_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/sedwaveConfig.cmake.in
  ${PROJECT_BINARY_DIR}/package/sedwaveConfig.cmake INSTALL_DESTINATION ${sedwave_config_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/sedwaveConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/package/sedwaveConfig.cmake
  ${PROJECT_BINARY_DIR}/package/sedwaveConfigVersion.cmake ${PROJECT_SOURCE_DIR}/cmake/sedwave_cubature.cmake
  DESTINATION ${sedwave_config_dir})
