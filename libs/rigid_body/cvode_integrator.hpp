#pragma once
// The SUNDIALS CVODE adapter of the rigid-body world: Adams-Moulton with a fixed-point corrector
// (non-stiff dynamics), scalar tolerances, root functions watched in one direction, restarts
// from a new state. It knows nothing of physics: the system is called back on a flat vector.
// (The calls made at every step are inline: a haptic step restarts and counts every 1 ms.)
#include <cvode/cvode.h>

#include <exception>
#include <stdexcept>
#include <string>

namespace wysiwyf::haptics {

// Thrown by a right-hand side that cannot be evaluated at this state but might be at a nearer
// one: CVODE is told so (a recoverable failure) and tries a smaller step.
struct RetryWithSmallerStep : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct CvodeOptions {
  double rtol = 0, atol = 0;           // scalar tolerances of the local error test
  double initial_step = 0;             // first step after a (re)start; 0: CVODE estimates it
  double max_early_growth = 10;        // CVodeSetEtaMaxEarlyStep: growth of the first steps after a restart
  double nonlinear_convergence = 0.1;  // CVodeSetNonlinConvCoef: the corrector's stopping fraction
  long max_steps = 100000;             // internal steps per call
};

class CvodeIntegrator {
 public:
  // The autonomous ODE y' = f(y) of `system`, with root functions g(y): System has
  // rhs(const double* y, double* ydot) and roots(const double* y, double* g), both reachable
  // from here (a friend). It must outlive the integrator. Throws std::runtime_error if SUNDIALS
  // cannot create its context, vector or integrator.
  template <class System>
  CvodeIntegrator(int size, const CvodeOptions& options, System& system)
      : CvodeIntegrator(size, options, &system, &call_rhs<System>, &call_roots<System>) {}
  ~CvodeIntegrator();
  CvodeIntegrator(const CvodeIntegrator&) = delete;
  CvodeIntegrator& operator=(const CvodeIntegrator&) = delete;

  // The state y: write it before restart(), read it after advance().
  double* state() { return N_VGetArrayPointer(y_); }
  // Starts over from state() at time t: the first time CVodeInit with the options, later
  // CVodeReInit (which keeps them, and resets CVODE's counters).
  void restart(double t) {
    if (!initialised_) {
      initialise(t);
      return;
    }
    check(CVodeReInit(mem_, t, y_), "CVodeReInit");
    steps_seen_ = failures_seen_ = 0;
  }
  // Watches the first `count` root functions, each for a downward crossing only.
  void watch_roots(int count);
  void set_stop_time(double t) { check(CVodeSetStopTime(mem_, t), "CVodeSetStopTime"); }
  // Integrates towards t_end (stopping at the stop time); t_reached gets where it stopped.
  // Returns true if it stopped at a root.
  bool advance(double t_end, double& t_reached) {
    const int flag = CVode(mem_, t_end, y_, &t_reached, CV_NORMAL);
    check(flag, "CVode");
    return flag == CV_ROOT_RETURN;
  }
  // found[k] != 0 for each watched root function that crossed at the last stop.
  void root_info(int* found) { check(CVodeGetRootInfo(mem_, found), "CVodeGetRootInfo"); }
  // Adds CVODE's internal steps and error test failures since the last count or restart.
  void count_work(int& steps, int& error_test_failures) {
    long now_steps = 0, now_failures = 0;
    CVodeGetNumSteps(mem_, &now_steps);
    CVodeGetNumErrTestFails(mem_, &now_failures);
    steps += static_cast<int>(now_steps - steps_seen_);
    error_test_failures += static_cast<int>(now_failures - failures_seen_);
    steps_seen_ = now_steps, failures_seen_ = now_failures;
  }

 private:
  CvodeIntegrator(int size, const CvodeOptions& options, void* system, CVRhsFn rhs, CVRootFn roots);
  // (An exception must not cross CVODE's C frames: it is kept, CVODE is told the call failed,
  // and the CVODE call that made it throws it again with its own failure.)
  template <class System>
  static int call_rhs(sunrealtype, N_Vector y, N_Vector ydot, void* self) {
    auto* me = static_cast<CvodeIntegrator*>(self);
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
  template <class System>
  static int call_roots(sunrealtype, N_Vector y, sunrealtype* g, void* self) {
    auto* me = static_cast<CvodeIntegrator*>(self);
    try {
      static_cast<System*>(me->system_)->roots(N_VGetArrayPointer(y), g);
    } catch (const std::exception& e) {
      me->callback_error_ = e.what();
      return -1;
    }
    return 0;
  }
  static int error_weights(N_Vector y, N_Vector ewt, void* self);
  // CVODE's own account of a failure, kept for the exception instead of printed.
  static void keep_message(int code, const char* module, const char* function, char* msg, void* self);
  void initialise(double t);
  void check(int flag, const char* call) {
    if (flag < 0) fail(flag, call);
  }
  [[noreturn]] void fail(int flag, const char* call);

  CvodeOptions options_;
  void* system_;
  CVRhsFn rhs_;
  CVRootFn roots_;
  SUNContext ctx_ = nullptr;
  N_Vector y_ = nullptr;
  void* mem_ = nullptr;
  SUNNonlinearSolver nls_ = nullptr;
  bool initialised_ = false;
  long steps_seen_ = 0, failures_seen_ = 0;  // CVODE's counters at the last count (reset by CVodeReInit)
  std::string message_;                      // CVODE's last error message
  std::string callback_error_;               // what the system's callback threw
};

}  // namespace wysiwyf::haptics
