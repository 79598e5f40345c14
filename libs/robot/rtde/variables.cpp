#include "rtde/variables.hpp"

#include <array>
#include <charconv>
#include <utility>

namespace wysiwyf::robot::rtde {
namespace {

using Entry = std::pair<std::string_view, FieldType>;

constexpr std::array<Entry, 37> kOutputs = {{
    {"timestamp", FieldType::kDouble},
    {"target_q", FieldType::kVector6d},
    {"target_qd", FieldType::kVector6d},
    {"target_qdd", FieldType::kVector6d},
    {"target_current", FieldType::kVector6d},
    {"target_moment", FieldType::kVector6d},
    {"actual_q", FieldType::kVector6d},
    {"actual_qd", FieldType::kVector6d},
    {"actual_current", FieldType::kVector6d},
    {"joint_control_output", FieldType::kVector6d},
    {"actual_TCP_pose", FieldType::kVector6d},
    {"actual_TCP_speed", FieldType::kVector6d},
    {"actual_TCP_force", FieldType::kVector6d},
    {"target_TCP_pose", FieldType::kVector6d},
    {"target_TCP_speed", FieldType::kVector6d},
    {"actual_digital_input_bits", FieldType::kUint64},
    {"joint_temperatures", FieldType::kVector6d},
    {"actual_execution_time", FieldType::kDouble},
    {"robot_mode", FieldType::kInt32},
    {"joint_mode", FieldType::kVector6Int32},
    {"safety_mode", FieldType::kInt32},
    {"safety_status", FieldType::kInt32},
    {"actual_tool_accelerometer", FieldType::kVector3d},
    {"speed_scaling", FieldType::kDouble},
    {"target_speed_fraction", FieldType::kDouble},
    {"actual_momentum", FieldType::kDouble},
    {"actual_main_voltage", FieldType::kDouble},
    {"actual_robot_voltage", FieldType::kDouble},
    {"actual_robot_current", FieldType::kDouble},
    {"actual_joint_voltage", FieldType::kVector6d},
    {"actual_digital_output_bits", FieldType::kUint64},
    {"runtime_state", FieldType::kUint32},
    {"robot_status_bits", FieldType::kUint32},
    {"safety_status_bits", FieldType::kUint32},
    {"ft_raw_wrench", FieldType::kVector6d},
    {"payload", FieldType::kDouble},
    {"payload_cog", FieldType::kVector3d},
}};

constexpr std::array<Entry, 4> kInputs = {{
    {"speed_slider_mask", FieldType::kUint32},
    {"speed_slider_fraction", FieldType::kDouble},
    {"input_bit_registers0_to_31", FieldType::kUint32},
    {"input_bit_registers32_to_63", FieldType::kUint32},
}};

// N of `name` = prefix + N (decimal, no sign or leading zero), when it lies in [lo, hi).
bool numbered(std::string_view name, std::string_view prefix, int lo, int hi) {
  if (name.substr(0, prefix.size()) != prefix) return false;
  const std::string_view digits = name.substr(prefix.size());
  if (digits.empty() || (digits.size() > 1 && digits[0] == '0')) return false;
  int n = -1;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
  return ec == std::errc() && end == digits.data() + digits.size() && n >= lo && n < hi;
}

// The registers' types, for both directions ("input_" or "output_").
std::optional<FieldType> register_type(std::string_view name, std::string_view direction) {
  if (name.substr(0, direction.size()) != direction) return std::nullopt;
  const std::string_view rest = name.substr(direction.size());
  if (numbered(rest, "int_register_", 0, kRegisters)) return FieldType::kInt32;
  if (numbered(rest, "double_register_", 0, kRegisters)) return FieldType::kDouble;
  if (numbered(rest, "bit_register_", 64, 128)) return FieldType::kBool;
  return std::nullopt;
}

template <std::size_t N>
std::optional<FieldType> find(const std::array<Entry, N>& table, std::string_view name) {
  for (const auto& [n, t] : table)
    if (n == name) return t;
  return std::nullopt;
}

}  // namespace

std::optional<FieldType> output_type(std::string_view name) {
  if (auto t = find(kOutputs, name)) return t;
  if (auto t = find(kInputs, name)) return t;  // the inputs can be read back as outputs
  if (auto t = register_type(name, "output_")) return t;
  return register_type(name, "input_");
}

std::optional<FieldType> input_type(std::string_view name) {
  if (auto t = find(kInputs, name)) return t;
  return register_type(name, "input_");
}

}  // namespace wysiwyf::robot::rtde
