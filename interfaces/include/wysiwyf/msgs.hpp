#pragma once
// The message types of interfaces/msgs/*.idl, bound to ports, and their YAML printers. (Their DDS
// type support is compiled into the message library, src/msgs.cpp.)
#include <string>

#include "wysiwyf/idl/display_msgs.h"
#include "wysiwyf/idl/geometry_msgs.h"
#include "wysiwyf/idl/sensor_msgs.h"
#include "wysiwyf/idl/wysiwyf_msgs.h"
#include "wysiwyf/kernel_msgs.hpp"
#include "wysiwyf/message_registry.hpp"

WYSIWYF_MESSAGE(wysiwyf::msg, Image)
WYSIWYF_MESSAGE(wysiwyf::msg, CameraInfo)
WYSIWYF_MESSAGE(wysiwyf::msg, JointState)
WYSIWYF_MESSAGE(wysiwyf::msg, PoseStamped)
WYSIWYF_MESSAGE(wysiwyf::msg, PoseWithCovariance)
WYSIWYF_MESSAGE(wysiwyf::msg, WrenchStamped)
WYSIWYF_MESSAGE(wysiwyf::msg, CartesianSetpoint)
WYSIWYF_MESSAGE(wysiwyf::msg, ObjectState)
WYSIWYF_MESSAGE(wysiwyf::msg, DisplayMode)
WYSIWYF_MESSAGE(wysiwyf::msg, RobotStatus)
WYSIWYF_MESSAGE(wysiwyf::msg, MarkerObservation)
WYSIWYF_MESSAGE(wysiwyf::msg, HandPosition)
WYSIWYF_MESSAGE(wysiwyf::msg, Attachment)
WYSIWYF_MESSAGE(wysiwyf::msg, PlannerStatus)
WYSIWYF_MESSAGE(wysiwyf::msg, UserEvent)
WYSIWYF_MESSAGE(wysiwyf::msg, ContactReport)
WYSIWYF_MESSAGE(wysiwyf::msg, HapticRegistration)

namespace wysiwyf::msgs {

// YAML text of a sample, as `wysiwyf topic echo` prints it (image pixels are summarised).
std::string to_yaml(const kernel_msgs::Diagnostics& m);
std::string to_yaml(const msg::Image& m);
std::string to_yaml(const msg::CameraInfo& m);
std::string to_yaml(const msg::JointState& m);
std::string to_yaml(const msg::PoseStamped& m);
std::string to_yaml(const msg::PoseWithCovariance& m);
std::string to_yaml(const msg::WrenchStamped& m);
std::string to_yaml(const msg::CartesianSetpoint& m);
std::string to_yaml(const msg::ObjectState& m);
std::string to_yaml(const msg::DisplayMode& m);
std::string to_yaml(const msg::RobotStatus& m);
std::string to_yaml(const msg::MarkerObservation& m);
std::string to_yaml(const msg::HandPosition& m);
std::string to_yaml(const msg::Attachment& m);
std::string to_yaml(const msg::PlannerStatus& m);
std::string to_yaml(const msg::UserEvent& m);
std::string to_yaml(const msg::ContactReport& m);
std::string to_yaml(const msg::HapticRegistration& m);

// Every port message type of this build, by DDS type name.
const MessageRegistry& registry();

}  // namespace wysiwyf::msgs
