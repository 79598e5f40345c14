// The user's wrench path, scenes, and the admittance_sim component driven like the robot would.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "scene/tool_load.hpp"
#include "wysiwyf/harness.hpp"
#include "wysiwyf/msgs.hpp"

namespace wysiwyf::haptics {

TEST(WrenchPath, RemovesTheToolWeightAndMovesTheWrenchToTheBody) {
  // Sensor 0.5 m above the body's centre, turned 90 degrees about z.
  Eigen::Isometry3d world_T_sensor = Eigen::Isometry3d::Identity();
  world_T_sensor.linear() = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()).toRotationMatrix();
  world_T_sensor.translation() = Vec3(1.0, 0.0, 0.5);
  const Vec3 com(1.0, 0.0, 0.0);
  const Vec3 gravity(0, 0, -9.81);
  const double tool_mass = 0.5;
  const Vec3 tool_com(0.0, 0.0, 0.1);  // in the sensor frame (sensor z = world z here)
  // The sensor sees the user's 10 N push along world +y (sensor +x after the turn) plus the tool's weight.
  SensorReading measured;
  const Vec3 weight_sensor = world_T_sensor.linear().transpose() * (tool_mass * gravity);
  measured.force = Vec3(10.0, 0.0, 0.0) + weight_sensor;
  measured.torque = tool_com.cross(weight_sensor);  // the weight acts at the tool's centre of mass
  const BodyWrench w = user_wrench_on_body(measured, world_T_sensor, com, tool_mass, tool_com, gravity);
  EXPECT_LE((w.force - Vec3(0, 10, 0)).norm(), 1e-12);
  // The push at the sensor, 0.5 m above the centre: torque r x F = (0,0,0.5) x (0,10,0) = (-5, 0, 0).
  EXPECT_LE((w.torque - Vec3(-5, 0, 0)).norm(), 1e-12);
}

TEST(WrenchPath, AToolHangingStillGivesNoUserWrenchInAnyOrientation) {
  for (double angle : {0.0, 0.7, 2.1, -1.3}) {
    Eigen::Isometry3d world_T_sensor = Eigen::Isometry3d::Identity();
    world_T_sensor.linear() = Eigen::AngleAxisd(angle, Vec3(0.3, 1, 0.2).normalized()).toRotationMatrix();
    const Vec3 g(0, 0, -9.81), tool_com(0.01, -0.02, 0.05);
    SensorReading measured;
    measured.force = world_T_sensor.linear().transpose() * (0.35 * g);
    measured.torque = tool_com.cross(measured.force);
    const BodyWrench w = user_wrench_on_body(measured, world_T_sensor, Vec3::Zero(), 0.35, tool_com, g);
    EXPECT_LE(w.force.norm(), 1e-12);
    EXPECT_LE(w.torque.norm(), 1e-12);
  }
}

TEST(Scene, ThePapersCubeOnTableLoads) {
  const Scene s = load_scene(std::string(WYSIWYF_CONFIG_DIR) + "/scenes/cube_on_table.yaml");
  ASSERT_EQ(s.models.size(), 2u);
  EXPECT_EQ(s.models[1].name, "cube");
  EXPECT_EQ(s.models[1].half_extents, Vec3::Constant(0.1));
  EXPECT_EQ(s.device.body, 1);
  // The plate is the +x face: z out of the face.
  EXPECT_LE((s.device.obj_T_dev.linear().col(2) - Vec3::UnitX()).norm(), 1e-12);
  EXPECT_LE((s.device.obj_T_dev.translation() - Vec3(0.1, 0, 0)).norm(), 1e-12);
}

TEST(Scene, MistakesAreReportedWithTheirLine) {
  try {
    load_scene_from_string("scene: 1\nbodies:\n  cube:\n    size: [0.2, 0.2]\n    mass: 1\n", "bad.yaml");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "bad.yaml:4:11: body 'cube' size: expected a list of three numbers");
  }
  try {
    load_scene_from_string("scene: 1\nbodies:\n  cube: {size: [0.2, 0.2, 0.2], mass: 1, friction: -0.4}\n", "f.yaml");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              "f.yaml:3:52: body 'cube' friction: found -0.4; expected a Coulomb coefficient in [0, 2]");
  }
  EXPECT_EQ(
      load_scene_from_string("scene: 1\nbodies:\n  cube: {size: [0.2, 0.2, 0.2], mass: 1, friction: 0.4}\n", "f.yaml")
          .models.front()
          .friction,
      0.4);
}

constexpr std::int64_t kMs = 1'000'000;

// What the wrist sensor reads when the user pushes the plate with `newtons` toward the robot
// (plate -z) while the sensor carries the tool (its weight and moment, in the sensor frame).
msg::WrenchStamped sensor_reading_of_push(const std::string& scene, double newtons) {
  const Scene s = load_scene(std::string(WYSIWYF_CONFIG_DIR) + "/" + scene);
  const Eigen::Matrix3d R = (s.device.obj_T_dev * s.device.dev_T_sensor).linear();
  const Vec3 weight = R.transpose() * (s.device.tool_mass * s.gravity);
  msg::WrenchStamped w;
  const Vec3 f = Vec3(0, 0, -newtons) + weight;
  const Vec3 t = s.device.tool_com.cross(weight);
  w.wrench().force().x(f.x()), w.wrench().force().y(f.y()), w.wrench().force().z(f.z());
  w.wrench().torque().x(t.x()), w.wrench().torque().y(t.y()), w.wrench().torque().z(t.z());
  return w;
}

TEST(AdmittanceSim, AUserPushAccelerateTheCubeByFOverMAndTheSetpointFollows) {
  // (the object's own motion: no preview window)
  Harness h("admittance_sim", "{scene: scenes/cube_on_table.yaml, preview_window: 0}", 1000);
  auto wrench = h.feed<msg::WrenchStamped>("wrench");
  auto setpoints = h.watch<msg::CartesianSetpoint>("setpoint");
  auto objects = h.watch<msg::ObjectState>("objects");
  h.activate();
  // The sensor (plate frame: z along world +x, out of the cube) carries the tool; the user pushes
  // the plate with 2 N toward the robot (world -x, plate -z).
  msg::WrenchStamped w = sensor_reading_of_push("scenes/cube_on_table.yaml", 2.0);
  for (int i = 0; i <= 500; ++i) {
    w.header().stamp_ns(i * kMs + 1000 * kMs - 250'000);  // sampled 250 us before the tick
    wrench.write(w);
    h.tick(Time{i * kMs + 1000 * kMs});
  }
  msg::CartesianSetpoint sp;
  ASSERT_TRUE(setpoints.take_latest(sp));
  EXPECT_EQ(sp.sensed_ns(), 1500 * kMs - 250'000) << "the stamp of the wrench sample it answers";
  // 501 steps of 1 ms under 2 N on 1 kg, frictionless: x = 0.7 - 1/2 * 2 * 0.501^2.
  const double expected_face = 0.7 - 0.5 * 2.0 * 0.501 * 0.501;
  EXPECT_NEAR(sp.pose().position().x(), expected_face, 1e-6);
  EXPECT_NEAR(sp.twist().linear().x(), -2.0 * 0.501, 1e-6);
  EXPECT_EQ(std::string(sp.source().c_str()), "admittance");
  msg::ObjectState o;
  ASSERT_TRUE(objects.take_latest(o));
  EXPECT_EQ(std::string(o.child_frame_id().c_str()), "cube");
  EXPECT_EQ(o.contacts().size(), 4u);  // resting on its four bottom corners
  double weight_carried = 0;
  for (const auto& c : o.contacts()) weight_carried += c.force();
  EXPECT_NEAR(weight_carried, 9.81, 1e-3);
}

TEST(AdmittanceSim, EachObjectsContactNormalsPointOutOfTheOtherBodyIntoIt) {
  // A stack: each cube touches the next face on face, the corners of one on the face of the other
  // (the world keeps one of the two twins, its normal out of that contact's second body). In
  // cube1's ObjectState the contact with cube2 points out of cube2, downwards, and the table's
  // upwards, whichever body the world lists first: every normal points from the contact into the
  // object.
  Harness h("admittance_sim", "{scene: scenes/stack_5.yaml}", 1000);
  auto objects = h.watch<msg::ObjectState>("objects");
  h.activate();
  std::map<std::string, msg::ObjectState> latest;
  for (int i = 0; i < 5; ++i) {
    h.tick(Time{i * kMs});
    for (msg::ObjectState o; objects.take(o);) latest[o.child_frame_id().c_str()] = o;
  }
  ASSERT_EQ(latest.size(), 5u);
  for (const auto& [name, o] : latest) {
    ASSERT_FALSE(o.contacts().empty()) << name;
    const Vec3 centre(o.pose().position().x(), o.pose().position().y(), o.pose().position().z());
    for (const auto& c : o.contacts()) {
      const Vec3 n(c.normal().x(), c.normal().y(), c.normal().z());
      const Vec3 p(c.position().x(), c.position().y(), c.position().z());
      EXPECT_NEAR(n.norm(), 1.0, 1e-9) << name;
      EXPECT_GT(n.dot(centre - p), 0.0) << name << " against " << c.other().c_str();
    }
  }
  for (const auto& c : latest["cube1"].contacts())
    EXPECT_NEAR(c.normal().z(), std::string(c.other().c_str()) == "table" ? 1.0 : -1.0, 1e-6) << c.other().c_str();
}

// The user's push through the sensor path on a scene; returns the setpoint after 501 ms (the
// object's own motion: no preview window).
msg::CartesianSetpoint push_for_501ms(const std::string& scene, double newtons) {
  Harness h("admittance_sim", "{scene: " + scene + ", preview_window: 0}", 1000);
  auto wrench = h.feed<msg::WrenchStamped>("wrench");
  auto setpoints = h.watch<msg::CartesianSetpoint>("setpoint");
  h.activate();
  const msg::WrenchStamped w = sensor_reading_of_push(scene, newtons);
  for (int i = 0; i <= 500; ++i) {
    wrench.write(w);
    h.tick(Time{i * kMs});
  }
  msg::CartesianSetpoint sp;
  EXPECT_TRUE(setpoints.take_latest(sp));
  return sp;
}

TEST(AdmittanceSim, OnTheRoughTableAPushBelowMuMgHoldsAndOneAboveSlidesByTheDifference) {
  // mu = 0.4: 2 N does not move the 1 kg cube (0.4 m g = 3.924 N); 6 N accelerates it by
  // (6 - 3.924) / 1 m/s^2 from the first step.
  const msg::CartesianSetpoint held = push_for_501ms("scenes/cube_on_rough_table.yaml", 2.0);
  EXPECT_NEAR(held.pose().position().x(), 0.7, 1e-6);
  EXPECT_NEAR(held.twist().linear().x(), 0.0, 1e-6);
  const msg::CartesianSetpoint slid = push_for_501ms("scenes/cube_on_rough_table.yaml", 6.0);
  const double a = 6.0 - 0.4 * 9.81;
  EXPECT_NEAR(slid.twist().linear().x(), -a * 0.501, 1e-4);
  EXPECT_NEAR(slid.pose().position().x(), 0.7 - 0.5 * a * 0.501 * 0.501, 1e-4);
}

TEST(AdmittanceSim, ANonFiniteWrenchIsIgnored) {
  Harness h("admittance_sim", "{scene: scenes/cube_on_table.yaml}", 1000);
  auto wrench = h.feed<msg::WrenchStamped>("wrench");
  auto setpoints = h.watch<msg::CartesianSetpoint>("setpoint");
  h.activate();
  msg::WrenchStamped w;
  w.wrench().force().x(std::nan(""));
  for (int i = 0; i < 100; ++i) {
    wrench.write(w);
    h.tick(Time{i * kMs});
  }
  msg::CartesianSetpoint sp;
  ASSERT_TRUE(setpoints.take_latest(sp));
  EXPECT_TRUE(std::isfinite(sp.pose().position().x()));
  EXPECT_NEAR(sp.pose().position().x(), 0.7, 1e-6);  // the cube did not move
}

// A push of 0.5 N into the wall of cube_against_wall (frictionless): the device face (x = 0.7)
// meets it at x = 0.6 after sqrt(2 0.1 / 0.5) = 632 ms at 0.32 m/s and stops within a step.
// Returns per tick the setpoint's x and speed and the held face's x and speed.
struct PushIntoWall {
  std::vector<double> setpoint_x, setpoint_v, face_x, face_v;
};
PushIntoWall push_into_wall(const std::string& preview_window) {
  Harness h("admittance_sim", "{scene: scenes/cube_against_wall.yaml, preview_window: " + preview_window + "}", 1000);
  auto wrench = h.feed<msg::WrenchStamped>("wrench");
  auto setpoints = h.watch<msg::CartesianSetpoint>("setpoint");
  auto objects = h.watch<msg::ObjectState>("objects");
  h.activate();
  const msg::WrenchStamped w = sensor_reading_of_push("scenes/cube_against_wall.yaml", 0.5);
  PushIntoWall r;
  for (int i = 0; i < 800; ++i) {
    wrench.write(w);
    h.tick(Time{i * kMs});
    msg::CartesianSetpoint sp;
    msg::ObjectState o;
    EXPECT_TRUE(setpoints.take_latest(sp) && objects.take_latest(o));
    r.setpoint_x.push_back(sp.pose().position().x());
    r.setpoint_v.push_back(sp.twist().linear().x());
    r.face_x.push_back(o.pose().position().x() + 0.1);
    r.face_v.push_back(o.twist().linear().x());
  }
  return r;
}

TEST(AdmittanceSim, TheSetpointBrakesAheadOfAnImpactAndArrivesWhereTheObjectStopsNeverPastIt) {
  const PushIntoWall r = push_into_wall("0.04");
  std::size_t impact = 100;  // the first tick the face is stopped, once it has moved
  while (impact < r.face_v.size() && std::abs(r.face_v[impact]) > 1e-3) ++impact;
  ASSERT_GT(impact, 600u);
  ASSERT_LT(impact, 700u);
  const double speed = std::abs(r.face_v[impact - 1]);
  EXPECT_NEAR(speed, 0.316, 0.01);
  double most_apart = 0;
  for (std::size_t i = 0; i < r.setpoint_x.size(); ++i) {
    EXPECT_GE(r.setpoint_x[i], 0.6 - 1e-6) << "past the face where the object stops, at tick " << i;
    most_apart = std::max(most_apart, std::abs(r.setpoint_x[i] - r.face_x[i]));
  }
  // The window's average of a path that stops: at most (speed change) x window / 8 from it, and
  // braking from half a window before the impact at (speed change) / window.
  EXPECT_LE(most_apart, speed * 0.04 / 8 + 1e-5);
  EXPECT_GT(most_apart, speed * 0.04 / 8 * 0.8) << "the setpoint did not brake ahead";
  EXPECT_NEAR(std::abs(r.setpoint_v[impact - 1]), speed / 2, 0.02) << "half the speed left at the impact";
  EXPECT_NEAR(std::abs(r.setpoint_v[impact - 15]), speed * 0.875, 0.02) << "braking since 20 ms before it";
  EXPECT_NEAR(std::abs(r.setpoint_v[impact - 25]), speed, 0.02) << "not braking 25 ms before it";
  // Away from the impact the average of a uniformly accelerated path is that path, a window^2 / 24
  // ahead (a = 0.5 m/s^2: 33 um), and once the window has passed the impact, the stopped face.
  EXPECT_NEAR(r.setpoint_x[300], r.face_x[300] - 0.5 * 0.04 * 0.04 / 24, 2e-6);
  EXPECT_NEAR(r.setpoint_x[impact + 25], 0.6, 1e-6);
  EXPECT_NEAR(r.setpoint_v[impact + 25], 0.0, 1e-6);
}

TEST(AdmittanceSim, WithoutAPreviewWindowTheSetpointIsTheObjectsOwnMotion) {
  const PushIntoWall r = push_into_wall("0");
  for (std::size_t i = 0; i < r.setpoint_x.size(); ++i) {
    ASSERT_NEAR(r.setpoint_x[i], r.face_x[i], 1e-12) << i;
    ASSERT_NEAR(r.setpoint_v[i], r.face_v[i], 1e-12) << i;
  }
}

}  // namespace wysiwyf::haptics
