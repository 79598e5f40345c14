#pragma once
// ARKODE's explicit Runge-Kutta, Bogacki-Shampine 3(2) (ERKStep, an embedded second-order error
// estimate), behind OdeIntegrator. One-step, so a restart (every new sensor sample) costs
// nothing but its first stage: the step size history is kept (ERKStepReset). Under a push held
// for the step a resting or sliding box moves along a quadratic, which a third-order method
// integrates exactly: a 1 ms haptic step is one step of four right-hand sides, where CVODE's
// Adams, restarted at order 1, takes several steps and more right-hand sides and stays further
// off the exact motion. (ERKStep rather than ARKStep, whose explicit path takes a fifth right-hand side
// after each reset.)
#include <arkode/arkode_erkstep.h>

#include "rigid_body/ode_integrator.hpp"

namespace wysiwyf::haptics {

class ArkodeIntegrator : public OdeIntegrator {
 public:
  // As CvodeIntegrator's (IntegratorOptions: rtol, atol and max_steps apply).
  template <class System>
  ArkodeIntegrator(int size, const IntegratorOptions& options, System& system)
      : ArkodeIntegrator(size, options, &system, &call_rhs<System>) {}
  ~ArkodeIntegrator() override;
  ArkodeIntegrator(const ArkodeIntegrator&) = delete;
  ArkodeIntegrator& operator=(const ArkodeIntegrator&) = delete;

  double* state() override { return N_VGetArrayPointer(y_); }
  // The first time ERKStepCreate with the options, later ERKStepReset (which keeps them, the
  // counters and the step size history).
  void restart(double t) override;
  void set_stop_time(double t) override { check(ERKStepSetStopTime(mem_, t), "ERKStepSetStopTime"); }
  void take_step(double t_end, double& t_reached) override;
  const double* state_at(double t) override;  // (ERKStepGetDky: ARKODE's Hermite interpolant)
  void count_work(int& steps, int& error_test_failures) override;

 private:
  ArkodeIntegrator(int size, const IntegratorOptions& options, void* system, ARKRhsFn rhs);
  static void keep_message(int code, const char* module, const char* function, char* msg, void* self);
  void initialise(double t);
  void check(int flag, const char* call) {
    if (flag < 0) fail(std::string("ARKODE ") + call + " failed: " + ERKStepGetReturnFlagName(flag));
  }

  IntegratorOptions options_;
  ARKRhsFn rhs_;
  SUNContext ctx_ = nullptr;
  N_Vector y_ = nullptr;
  N_Vector y_between_ = nullptr;  // state_at's
  void* mem_ = nullptr;
};

}  // namespace wysiwyf::haptics
