#pragma once
// The safety gate's parameters, declared the same way by every component that drives the arm
// (puma_sim, puma_driver): same names, defaults, ranges and descriptions.
#include "safety_gate/safety_gate.hpp"
#include "wysiwyf/context.hpp"

namespace wysiwyf::robot {

// Declares the gate's parameters on ctx and returns them; the caller sets `limits` and `dt` from
// its model and period, then SafetyConfig::validate(). Throws std::invalid_argument for a wrong
// number of acceleration limits.
SafetyConfig declare_gate_params(Context& ctx);

}  // namespace wysiwyf::robot
