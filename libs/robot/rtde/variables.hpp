#pragma once
// The controller's RTDE variables this project reads and writes, with their types as the RTDE
// Guide lists them: the robot's state (outputs) and the general purpose registers (inputs, which
// a program on the controller reads). The emulator answers setup requests from these tables and
// the driver checks the controller's answers against them.
#include <optional>
#include <string_view>

#include "rtde/protocol.hpp"

namespace wysiwyf::robot::rtde {

// General purpose registers: input_int_register_N, input_double_register_N and the output ones,
// N in [0, kRegisters); input_bit_register_N, N in [64, 128). Registers 0..23 are the fieldbus
// adapters' (EtherNet/IP, PROFINET, MODBUS) on the controller; an RTDE client keeps to 24..47.
constexpr int kRegisters = 48;
constexpr int kFirstClientRegister = 24;

// The type of an output variable (what the controller sends), or none for a name it lacks.
std::optional<FieldType> output_type(std::string_view name);
// The type of an input variable (what a client may write), or none.
std::optional<FieldType> input_type(std::string_view name);

}  // namespace wysiwyf::robot::rtde
