# vobench_add_plugin(<target> SOURCES <files...> [NAME <plugin name>] [LINK_LIBRARIES <libs...>] [INSTALL])
#
# Builds a vobench plugin: a MODULE library named vobench_<name>.so (name defaults to the target; give
# NAME when the target name would clash, e.g. with an imported library) that links vobench::sdk,
# compiles with hidden visibility, exports only the entry symbol (linker version script), and is
# linked with -z defs so that a missing symbol is a link error, not a load-time surprise.
# Used by the in-tree plugins and, through find_package(vobench), by out-of-tree ones.
set(_VOBENCH_PLUGIN_MAP "${CMAKE_CURRENT_LIST_DIR}/vobench_plugin.map")

function(vobench_add_plugin target)
  cmake_parse_arguments(ARG "INSTALL" "NAME" "SOURCES;LINK_LIBRARIES" ${ARGN})
  if(NOT ARG_NAME)
    set(ARG_NAME ${target})
  endif()
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "vobench_add_plugin(${target}): SOURCES is required")
  endif()
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE vobench::sdk ${ARG_LINK_LIBRARIES})
  if(TARGET vobench_warnings)
    target_link_libraries(${target} PRIVATE vobench_warnings)
  endif()
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    OUTPUT_NAME "vobench_${ARG_NAME}"
    C_VISIBILITY_PRESET hidden
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    LINK_DEPENDS "${_VOBENCH_PLUGIN_MAP}")
  target_link_options(${target} PRIVATE "LINKER:-z,defs" "LINKER:--version-script=${_VOBENCH_PLUGIN_MAP}")
  set_property(GLOBAL APPEND PROPERTY VOBENCH_PLUGIN_TARGETS ${target})
  if(DEFINED VOBENCH_PLUGIN_OUTPUT_DIR)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY "${VOBENCH_PLUGIN_OUTPUT_DIR}")
  endif()
  if(ARG_INSTALL)
    if(NOT DEFINED VOBENCH_INSTALL_PLUGINDIR)
      set(VOBENCH_INSTALL_PLUGINDIR lib/vobench/plugins)
    endif()
    install(TARGETS ${target} LIBRARY DESTINATION ${VOBENCH_INSTALL_PLUGINDIR} COMPONENT plugins)
  endif()
endfunction()
