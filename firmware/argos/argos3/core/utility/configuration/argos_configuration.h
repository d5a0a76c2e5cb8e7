// DECLARATION-ONLY stand-in for ARGoS 3's <argos3/core/utility/configuration/argos_configuration.h>
// (XML parameter access). Compile-only; link against a real ARGoS install.
#ifndef ARGOS_CONFIGURATION_H
#define ARGOS_CONFIGURATION_H

#include <string>

#include <argos3/core/utility/configuration/argos_exception.h>

namespace ticpp {
class Element;
}

namespace argos {
typedef ticpp::Element TConfigurationNode;

bool NodeExists(TConfigurationNode& t_node, const std::string& str_tag);
TConfigurationNode& GetNode(TConfigurationNode& t_node, const std::string& str_tag);
template <typename T>
void GetNodeAttribute(TConfigurationNode& t_node, const std::string& str_attribute, T& t_buffer);
template <typename T>
void GetNodeAttributeOrDefault(TConfigurationNode& t_node, const std::string& str_attribute, T& t_buffer,
                               const T& t_default);
}  // namespace argos

#endif
