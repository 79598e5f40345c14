#pragma once
// CVODE's variable-order Adams-Moulton (orders 1-12, a fixed-point corrector: non-stiff
// dynamics) behind OdeIntegrator. Its high orders pay on long smooth motion at tight tolerances
// (a tumbling box); a restart, which every new sensor sample is, starts it again at order 1.
#include <cvode/cvode.h>

#include "rigid_body/ode_integrator.hpp"

namespace wysiwyf::haptics {

class CvodeIntegrator : public OdeIntegrator {
 public:
  // Throws std::runtime_error if SUNDIALS cannot create its context, vector or integrator.
  // System has rhs(const double* y, double* ydot), reachable from here (a friend); it must
  // outlive the integrator.
  template <class System>
  CvodeIntegrator(int size, const IntegratorOptions& options, System& system)
      : CvodeIntegrator(size, options, &system, &call_rhs<System>) {}
  ~CvodeIntegrator() override;
  CvodeIntegrator(const CvodeIntegrator&) = delete;
  CvodeIntegrator& operator=(const CvodeIntegrator&) = delete;

  double* state() override { return N_VGetArrayPointer(y_); }
  // The first time CVodeInit with the options, later CVodeReInit (which keeps them, and resets
  // CVODE's counters).
  void restart(double t) override;
  void set_stop_time(double t) override { check(CVodeSetStopTime(mem_, t), "CVodeSetStopTime"); }
  void take_step(double t_end, double& t_reached) override;
  const double* state_at(double t) override;  // (CVodeGetDky: CVODE's interpolating polynomial)
  void count_work(int& steps, int& error_test_failures) override;

 private:
  CvodeIntegrator(int size, const IntegratorOptions& options, void* system, CVRhsFn rhs);
  // CVODE's own account of a failure, kept for the exception instead of printed.
  static void keep_message(int code, const char* module, const char* function, char* msg, void* self);
  void initialise(double t);
  void check(int flag, const char* call) {
    if (flag < 0) fail(std::string("CVODE ") + call + " failed: " + CVodeGetReturnFlagName(flag));
  }

  IntegratorOptions options_;
  CVRhsFn rhs_;
  SUNContext ctx_ = nullptr;
  N_Vector y_ = nullptr;
  N_Vector y_between_ = nullptr;  // state_at's
  void* mem_ = nullptr;
  SUNNonlinearSolver nls_ = nullptr;
  bool initialised_ = false;
};

}  // namespace wysiwyf::haptics
