#pragma once
/// @file
/// What a component type declares about itself: the result of running its configure() in
/// describe mode (`wysiwyf components describe`, Harness::description()).
#include <string>
#include <vector>

#include "wysiwyf/params.hpp"
#include "wysiwyf/port.hpp"

namespace wysiwyf {

/// What a component type declares about itself: its configure() run in describe mode.
struct ComponentDescription {
  std::string type;               ///< the component type, as pipelines name it
  std::string summary;            ///< the one line Context::summary() gave
  std::string library;            ///< the shared library it was loaded from
  std::vector<ParamSpec> params;  ///< every declared parameter, with its default
  std::vector<PortSpec> ports;    ///< every declared port, with its type and QoS
};

}  // namespace wysiwyf
