#include "wysiwyf/msgs.hpp"

#include "wysiwyf/message_type_support.hpp"

#include "wysiwyf/idl/geometry_msgsPubSubTypes.h"
#include "wysiwyf/idl/sensor_msgsPubSubTypes.h"
#include "wysiwyf/idl/display_msgsPubSubTypes.h"
#include "wysiwyf/idl/wysiwyf_msgsPubSubTypes.h"
#include "wysiwyf/idl/diagnosticsTypeObject.h"
#include "wysiwyf/idl/display_msgsTypeObject.h"
#include "wysiwyf/idl/geometry_msgsTypeObject.h"
#include "wysiwyf/idl/sensor_msgsTypeObject.h"
#include "wysiwyf/idl/std_msgsTypeObject.h"
#include "wysiwyf/idl/wysiwyf_msgsTypeObject.h"

WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, Image)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, CameraInfo)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, JointState)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, PoseStamped)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, PoseWithCovariance)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, WrenchStamped)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, CartesianSetpoint)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, ObjectState)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, DisplayMode)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, RobotStatus)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, ArmRequest)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, MarkerObservation)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, HandPosition)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, Attachment)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, PlannerStatus)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, UserEvent)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, ContactReport)
WYSIWYF_MESSAGE_TYPE_SUPPORT(wysiwyf::msg, HapticRegistration)

namespace wysiwyf::msgs {

void register_type_objects() {
  static const bool registered = [] {
    registerstd_msgsTypes();
    registerdiagnosticsTypes();
    registergeometry_msgsTypes();
    registersensor_msgsTypes();
    registerwysiwyf_msgsTypes();
    registerdisplay_msgsTypes();
    return true;
  }();
  (void)registered;
}

}  // namespace wysiwyf::msgs
