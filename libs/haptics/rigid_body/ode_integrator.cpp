#include "rigid_body/ode_integrator.hpp"

#include <cmath>

namespace wysiwyf::haptics {

int OdeIntegrator::error_weights(N_Vector y, N_Vector ewt, void* self) {
  const auto* me = static_cast<const OdeIntegrator*>(self);
  const double* yy = N_VGetArrayPointer(y);
  double* w = N_VGetArrayPointer(ewt);
  for (sunindextype i = 0, n = N_VGetLength(y); i < n; ++i) w[i] = 1.0 / (me->rtol_ * std::abs(yy[i]) + me->atol_);
  return 0;
}

void OdeIntegrator::add_work(long now_steps, long now_failures, int& steps, int& error_test_failures) {
  steps += static_cast<int>(now_steps - steps_seen_);
  error_test_failures += static_cast<int>(now_failures - failures_seen_);
  steps_seen_ = now_steps, failures_seen_ = now_failures;
}

void OdeIntegrator::fail(const std::string& what) {
  std::string why = what;
  if (!message_.empty()) why += " (" + message_ + ")";
  if (!callback_error_.empty()) why += "; the right-hand side threw: " + callback_error_;
  message_.clear();
  callback_error_.clear();
  throw std::runtime_error(why);
}

}  // namespace wysiwyf::haptics
