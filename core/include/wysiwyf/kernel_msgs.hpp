#pragma once
// Kernel message types (interfaces/kernel/*.idl) bound to ports.
#include "wysiwyf/idl/diagnosticsPubSubTypes.h"
#include "wysiwyf/idl/std_msgsPubSubTypes.h"
#include "wysiwyf/message_traits.hpp"

WYSIWYF_MESSAGE(wysiwyf::kernel_msgs, Diagnostics)

namespace wysiwyf {
inline constexpr const char* kDiagnosticsTopic = "wysiwyf/diagnostics";
}
