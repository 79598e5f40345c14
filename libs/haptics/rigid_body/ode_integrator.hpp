#pragma once
// What the rigid-body world needs of an ODE integrator (SUNDIALS behind it): the autonomous
// y' = f(y) of a system called back on a flat vector, taken one internal step at a time with the
// state anywhere within the last step (the world looks for impacts between steps,
// gap_closing.hpp), restarts from a new state (every sensor sample, every impact). It knows
// nothing of physics.
// Two are offered (WorldParams::integrator): CVODE's variable-order Adams (cvode_integrator.hpp)
// and ARKODE's explicit Runge-Kutta (arkode_integrator.hpp).
#include <sundials/sundials_nvector.h>
#include <sundials/sundials_types.h>

#include <exception>
#include <stdexcept>
#include <string>

namespace wysiwyf::haptics {

// Thrown by a right-hand side that cannot be evaluated at this state but might be at a nearer
// one: the integrator is told so (a recoverable failure) and tries a smaller step.
struct RetryWithSmallerStep : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct IntegratorOptions {
  double rtol = 0, atol = 0;           // scalar tolerances of the local error test
  double initial_step = 0;             // CVODE: first step after a (re)start; 0: CVODE estimates it
  double max_early_growth = 10;        // CVODE: CVodeSetEtaMaxEarlyStep, growth of the first steps after a restart
  double nonlinear_convergence = 0.1;  // CVODE: CVodeSetNonlinConvCoef, the corrector's stopping fraction
  long max_steps = 100000;             // internal steps per call
};

class OdeIntegrator {
 public:
  virtual ~OdeIntegrator() = default;
  // The state y: write it before restart(), read it after take_step().
  virtual double* state() = 0;
  // Starts over from state() at time t (the first call initialises the integrator); the stop
  // time is cleared (SUNDIALS' reset clears it).
  virtual void restart(double t) = 0;
  virtual void set_stop_time(double t) = 0;
  // One internal step towards t_end, never past the stop time; t_reached gets where it ended
  // (state() holds the state there).
  virtual void take_step(double t_end, double& t_reached) = 0;
  // The state at t within the last step (its dense output), in a vector of the integrator's own
  // that the next call overwrites.
  virtual const double* state_at(double t) = 0;
  // The local error test's tolerances from the next step on.
  void set_tolerances(double rtol, double atol) { rtol_ = rtol, atol_ = atol; }
  // Adds the internal steps and error test failures since the last count or restart.
  virtual void count_work(int& steps, int& error_test_failures) = 0;

 protected:
  explicit OdeIntegrator(void* system) : system_(system) {}
  // SUNDIALS' callback (the same signature for CVODE and ARKODE; user data: this). An exception
  // must not cross SUNDIALS' C frames: it is kept, SUNDIALS is told the call failed, and the
  // call that made it throws it again with its own failure.
  template <class System>
  static int call_rhs(sunrealtype, N_Vector y, N_Vector ydot, void* self) {
    auto* me = static_cast<OdeIntegrator*>(self);
    try {
      static_cast<System*>(me->system_)->rhs(N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
    } catch (const RetryWithSmallerStep& e) {
      me->callback_error_ = e.what();
      return 1;
    } catch (const std::exception& e) {
      me->callback_error_ = e.what();
      return -1;
    }
    return 0;
  }
  // The error weights 1 / (rtol |y_i| + atol), in one pass (SUNDIALS' own scalar-tolerance
  // version takes five vector operations, at every step); user data: this.
  static int error_weights(N_Vector y, N_Vector ewt, void* self);
  // Throws std::runtime_error naming the call, SUNDIALS' message and what a callback threw.
  [[noreturn]] void fail(const std::string& what);
  // Adds to steps and error_test_failures what SUNDIALS' counters gained since the last call
  // (counters_reset(): they started again from zero).
  void add_work(long now_steps, long now_failures, int& steps, int& error_test_failures);
  void counters_reset() { steps_seen_ = failures_seen_ = 0; }

  void* system_;
  std::string message_;         // SUNDIALS' last error message
  std::string callback_error_;  // what the system's callback threw
  double rtol_ = 0, atol_ = 0;
  long steps_seen_ = 0, failures_seen_ = 0;  // SUNDIALS' counters at the last count
};

}  // namespace wysiwyf::haptics
