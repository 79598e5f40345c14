// Every message type of this build reads by its description, the dynamic type built from its type
// object, the way `topic echo`, the dashboard and `monitor` read them (no printer per type): a
// sample written with the compiled type support decodes field by field to the values written.
#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastrtps/types/DynamicTypePtr.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "../../apps/wysiwyf/cdr_yaml.hpp"
#include "../../apps/wysiwyf/message_libraries.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::test {

namespace types = eprosima::fastrtps::types;

// `sample` through its compiled type support, back through the dynamic type of its name, as YAML.
template <class T>
YAML::Node through_dynamic_type(T& sample) {
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> compiled(MessageTraits<T>::make_type());
  eprosima::fastrtps::rtps::SerializedPayload_t payload(compiled->getSerializedSizeProvider(&sample)() + 4);
  EXPECT_TRUE(compiled->serialize(&sample, &payload));
  types::DynamicType_ptr type;
  std::string searched;
  EXPECT_TRUE(cli::find_dynamic_type(MessageTraits<T>::type_name(), type, searched)) << searched;
  if (!type) return {};
  return YAML::Load(cli::cdr_to_yaml(payload.data, payload.length, type));
}

template <class T>
void decodes_default() {
  T sample;
  sample.header().stamp_ns(123456789);
  sample.header().frame_id("base");
  const YAML::Node y = through_dynamic_type(sample);
  EXPECT_EQ(y["header"]["stamp_ns"].as<std::int64_t>(), 123456789) << MessageTraits<T>::type_name();
  EXPECT_EQ(y["header"]["frame_id"].as<std::string>(), "base") << MessageTraits<T>::type_name();
}

TEST(DynamicTypes, EveryMessageTypeOfThisBuildDecodes) {
  decodes_default<kernel_msgs::Diagnostics>();
  decodes_default<msg::Image>();
  decodes_default<msg::CameraInfo>();
  decodes_default<msg::JointState>();
  decodes_default<msg::PoseStamped>();
  decodes_default<msg::PoseWithCovariance>();
  decodes_default<msg::WrenchStamped>();
  decodes_default<msg::CartesianSetpoint>();
  decodes_default<msg::ObjectState>();
  decodes_default<msg::DisplayMode>();
  decodes_default<msg::RobotStatus>();
  decodes_default<msg::ArmRequest>();
  decodes_default<msg::MarkerObservation>();
  decodes_default<msg::HandPosition>();
  decodes_default<msg::Attachment>();
  decodes_default<msg::PlannerStatus>();
  decodes_default<msg::UserEvent>();
  decodes_default<msg::ContactReport>();
  decodes_default<msg::HapticRegistration>();
}

TEST(DynamicTypes, NestedSequencesArraysEnumsAndStringsDecodeToTheirValues) {
  msg::ObjectState objects;
  objects.child_frame_id("v_obj");
  objects.pose().position().x(0.25);
  for (int i = 0; i < 2; ++i) {
    msg::Contact c;
    c.gap(-0.001 * (i + 1));
    c.kind(i == 0 ? msg::CONTACT_RESTING : msg::CONTACT_SEPARATING);
    c.other(i == 0 ? "table" : "wall");
    objects.contacts().push_back(c);
  }
  const YAML::Node o = through_dynamic_type(objects);
  EXPECT_EQ(o["child_frame_id"].as<std::string>(), "v_obj");
  EXPECT_EQ(o["pose"]["position"]["x"].as<double>(), 0.25);
  ASSERT_EQ(o["contacts"].size(), 2u);
  EXPECT_EQ(o["contacts"][1]["gap"].as<double>(), -0.002);
  EXPECT_EQ(o["contacts"][1]["kind"].as<std::string>(), "CONTACT_SEPARATING");
  EXPECT_EQ(o["contacts"][0]["other"].as<std::string>(), "table");

  msg::JointState joints;
  joints.position().resize(6);
  for (int i = 0; i < 6; ++i) joints.position()[i] = 0.1 * i;
  const YAML::Node j = through_dynamic_type(joints);
  ASSERT_EQ(j["position"].size(), 6u);
  EXPECT_EQ(j["position"][5].as<double>(), 0.1 * 5);

  msg::CameraInfo info;
  info.d({0.1, -0.2, 0.0, 0.0, 0.05});
  info.k()[0] = 800;
  const YAML::Node c = through_dynamic_type(info);
  ASSERT_EQ(c["d"].size(), 5u);
  EXPECT_EQ(c["d"][1].as<double>(), -0.2);
  EXPECT_EQ(c["k"][0].as<double>(), 800);

  kernel_msgs::Diagnostics d;
  d.instance("physics");
  d.state(kernel_msgs::STATE_HOLDING);
  kernel_msgs::PortCount port;
  port.port("wrench");
  port.count(7);
  d.dropped_by_port().push_back(port);
  const YAML::Node g = through_dynamic_type(d);
  EXPECT_EQ(g["state"].as<std::string>(), "STATE_HOLDING");
  EXPECT_EQ(g["dropped_by_port"][0]["port"].as<std::string>(), "wrench");
  EXPECT_EQ(g["dropped_by_port"][0]["count"].as<std::uint64_t>(), 7u);

  msg::Image image;
  image.width(4);
  image.height(2);
  image.encoding("mono8");
  image.data(std::vector<std::uint8_t>(8, 9));
  const YAML::Node i = through_dynamic_type(image);
  EXPECT_EQ(i["encoding"].as<std::string>(), "mono8");
  EXPECT_EQ(i["data"].size(), 8u);  // short: shown byte by byte
  EXPECT_EQ(i["data"][7].as<int>(), 9);
  image.data(std::vector<std::uint8_t>(640 * 480 * 3, 1));
  image.step(1920);
  const YAML::Node big = through_dynamic_type(image);
  EXPECT_EQ(big["data"].as<std::string>(), "<921600 bytes>");  // long: its length
  EXPECT_EQ(big["step"].as<int>(), 1920);                      // and what follows it still reads
}

}  // namespace wysiwyf::test
