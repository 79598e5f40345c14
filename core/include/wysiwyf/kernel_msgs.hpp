#pragma once
/// @file
/// Kernel message types (interfaces/kernel/*.idl) bound to ports, and the header every message carries.
#include <cstdint>

#include "wysiwyf/idl/diagnostics.h"
#include "wysiwyf/idl/std_msgs.h"
#include "wysiwyf/message_traits.hpp"

// The kernel's diagnostics (interfaces/kernel/diagnostics.idl), usable on ports.
WYSIWYF_MESSAGE(wysiwyf::kernel_msgs, Diagnostics)

namespace wysiwyf {

/// The topic the kernel publishes every component's diagnostics on (kernel_msgs::Diagnostics).
inline constexpr const char* kDiagnosticsTopic = "wysiwyf/diagnostics";

/// A message's header: the time its data refers to, the publisher's sequence number (from 0, one
/// per sample written) and the frame the data is expressed in.
inline void fill_header(std_msgs::Header& h, std::int64_t stamp_ns, std::uint64_t seq, const char* frame_id) {
  h.stamp_ns(stamp_ns);
  h.seq(seq);
  h.frame_id() = frame_id;  // (copied into the bounded string: no allocation)
}

}  // namespace wysiwyf
