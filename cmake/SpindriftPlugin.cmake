# spindrift_add_plugin(<kind> <name> <sources...>)
# Builds plugins/<kind>/<name>/ into lib/spindrift/plugins/libspindrift_<kind>_<name>.so, the
# file name the ModelRegistry derives from "<kind> <name>" (so only named plugins are opened).
function(spindrift_add_plugin kind name)
  set(target spindrift_${kind}_${name})
  add_library(${target} MODULE ${ARGN})
  target_link_libraries(${target} PRIVATE spindrift)
  set_target_properties(${target} PROPERTIES
    PREFIX "lib"
    OUTPUT_NAME "spindrift_${kind}_${name}"
    LIBRARY_OUTPUT_DIRECTORY ${SPINDRIFT_PLUGIN_BUILD_DIR}
    CXX_VISIBILITY_PRESET hidden
    INSTALL_RPATH "$ORIGIN/../..")
  install(TARGETS ${target} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/spindrift/plugins)
  set_property(GLOBAL APPEND PROPERTY SPINDRIFT_PLUGIN_TARGETS ${target})
endfunction()
