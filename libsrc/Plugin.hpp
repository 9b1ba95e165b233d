// Spindrift — how a model becomes a plugin library.
//
// In the plugin's .cpp, after the class:
//     SPINDRIFT_PLUGIN(PressureModel, Wcsph)
// and in its CMakeLists.txt:
//     spindrift_add_plugin(pressure wcsph Wcsph.cpp)      # or (pressure Wcsph.cpp): name = folder
// The macro builds a factory `std::unique_ptr<PressureModel>(const ModelContext&)` and exports,
// with BOOST_DLL_ALIAS, what the ModelRegistry reads before calling it: the kind (from the base
// class, KindName<PressureModel> = "pressure"), the name (SPINDRIFT_PLUGIN_NAME, defined by
// spindrift_add_plugin, which also names the file libspindrift_<kind>_<name>.so) and the ABI
// tag (interface version and precision, Types.hpp). A base class of another kind than the one
// given to spindrift_add_plugin is a compile error.
#pragma once

#include "ModelContext.hpp"

#include <boost/dll/alias.hpp>
#include <memory>
#include <string_view>

#if !defined(SPINDRIFT_PLUGIN_KIND) || !defined(SPINDRIFT_PLUGIN_NAME)
#error "Build plugins with spindrift_add_plugin(kind name sources...) (cmake/SpindriftPlugin.cmake): it defines SPINDRIFT_PLUGIN_KIND and SPINDRIFT_PLUGIN_NAME"
#endif

#define SPINDRIFT_PLUGIN(Base, Class)                                                              \
    static_assert(std::string_view(::spindrift::KindName<::spindrift::Base>::value) ==             \
                      std::string_view(SPINDRIFT_PLUGIN_KIND),                                     \
                  "the plugin's base class is of another kind than spindrift_add_plugin's");       \
    namespace spindrift_plugin_exports {                                                           \
    std::unique_ptr<::spindrift::Base> create(const ::spindrift::ModelContext& context) {          \
        return std::make_unique<Class>(context);                                                   \
    }                                                                                              \
    const char* const kind = ::spindrift::KindName<::spindrift::Base>::value;                      \
    const char* const name = SPINDRIFT_PLUGIN_NAME;                                                \
    const ::spindrift::PluginAbiTag abiTag = ::spindrift::pluginAbiTag;                            \
    }                                                                                              \
    BOOST_DLL_ALIAS(spindrift_plugin_exports::create, spindrift_create)                            \
    BOOST_DLL_ALIAS(spindrift_plugin_exports::kind, spindrift_kind)                                \
    BOOST_DLL_ALIAS(spindrift_plugin_exports::name, spindrift_name)                                \
    BOOST_DLL_ALIAS(spindrift_plugin_exports::abiTag, spindrift_abi_tag)
