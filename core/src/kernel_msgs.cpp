// The DDS type support of the kernel's messages (the only place their PubSubTypes are seen).
#include "wysiwyf/kernel_msgs.hpp"

#include "wysiwyf/idl/diagnosticsPubSubTypes.h"
#include "wysiwyf/message_type_support.hpp"

WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::kernel_msgs, Diagnostics)
