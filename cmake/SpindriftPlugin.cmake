# spindrift_add_plugin(<kind> [<name>] <sources...>)
#
# Builds the plugin library libspindrift_<kind>_<name>.so, the file the ModelRegistry opens for
# `type <name>;` in a <kind> dictionary. <name> defaults to the name of the folder holding the
# CMakeLists.txt when the second argument is a source file. Kind and name become the compile
# definitions SPINDRIFT_PLUGIN_KIND and SPINDRIFT_PLUGIN_NAME, read by SPINDRIFT_PLUGIN(Base,
# Class) (Plugin.hpp): they are written nowhere else, and a base class of another kind does not
# compile.
#
# In Spindrift's tree the library goes to <build>/lib/spindrift/plugins/. Outside it (after
# find_package(Spindrift), which includes this file) it goes to the build directory; either way
# `cmake --install` puts it in <prefix>/lib/spindrift/plugins/.
include_guard(GLOBAL)
include(GNUInstallDirs)

function(spindrift_add_plugin kind)
  # the kinds of ModelRegistry::kinds() (ModelRegistryTest checks the two lists agree)
  set(kinds kernel pressure viscosity integrator boundary force surfaceTension densityDiffusion shifting passive functionObject)
  if(NOT kind IN_LIST kinds)
    string(REPLACE ";" " " kinds "${kinds}")
    message(FATAL_ERROR "spindrift_add_plugin: unknown kind '${kind}' (kinds: ${kinds})")
  endif()
  set(sources ${ARGN})
  if(NOT sources)
    message(FATAL_ERROR "spindrift_add_plugin(${kind} ...): no source files")
  endif()
  list(GET sources 0 first)
  if(first MATCHES "\\.(cpp|cc|cxx|c\\+\\+|C)$")
    get_filename_component(name "${CMAKE_CURRENT_SOURCE_DIR}" NAME)
  else()
    set(name "${first}")
    list(REMOVE_AT sources 0)
  endif()
  if(NOT name MATCHES "^[A-Za-z][A-Za-z0-9_]*$")
    message(FATAL_ERROR "spindrift_add_plugin(${kind} ...): '${name}' is not a valid plugin name "
                        "(a letter, then letters, digits, _): name it as the second argument")
  endif()
  if(NOT sources)
    message(FATAL_ERROR "spindrift_add_plugin(${kind} ${name}): no source files")
  endif()

  set(target spindrift_${kind}_${name})
  add_library(${target} MODULE ${sources})
  target_link_libraries(${target} PRIVATE Spindrift::spindrift)
  target_compile_definitions(${target} PRIVATE
    SPINDRIFT_PLUGIN_KIND="${kind}" SPINDRIFT_PLUGIN_NAME="${name}")
  set_target_properties(${target} PROPERTIES
    PREFIX "lib"
    OUTPUT_NAME "spindrift_${kind}_${name}"
    CXX_VISIBILITY_PRESET hidden
    INSTALL_RPATH "$ORIGIN/../..")
  if(DEFINED SPINDRIFT_PLUGIN_BUILD_DIR)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${SPINDRIFT_PLUGIN_BUILD_DIR})
  endif()
  install(TARGETS ${target} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/spindrift/plugins)
  set_property(GLOBAL APPEND PROPERTY SPINDRIFT_PLUGIN_TARGETS ${target})
endfunction()
