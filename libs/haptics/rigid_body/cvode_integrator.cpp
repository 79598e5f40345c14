#include "rigid_body/cvode_integrator.hpp"

#include <nvector/nvector_serial.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "rigid_body/fast_serial_ops.hpp"

namespace wysiwyf::haptics {

CvodeIntegrator::CvodeIntegrator(int size, const IntegratorOptions& options, void* system, CVRhsFn rhs)
    : OdeIntegrator(system), options_(options), rhs_(rhs) {
  rtol_ = options.rtol, atol_ = options.atol;
  if (SUNContext_Create(nullptr, &ctx_) != 0) throw std::runtime_error("SUNDIALS: cannot create a context");
  y_ = N_VNew_Serial(size, ctx_);
  y_between_ = N_VNew_Serial(size, ctx_);
  mem_ = CVodeCreate(CV_ADAMS, ctx_);  // non-stiff rigid-body dynamics: Adams-Moulton
  if (!y_ || !y_between_ || !mem_) throw std::runtime_error("SUNDIALS: cannot create the CVODE integrator");
  install_fast_serial_ops(y_);  // (before CVodeInit clones its vectors from y_)
  install_fast_serial_ops(y_between_);
  check(CVodeSetErrHandlerFn(mem_, &CvodeIntegrator::keep_message, static_cast<OdeIntegrator*>(this)),
        "CVodeSetErrHandlerFn");
}

void CvodeIntegrator::keep_message(int, const char*, const char* function, char* msg, void* self) {
  static_cast<CvodeIntegrator*>(static_cast<OdeIntegrator*>(self))->message_ = std::string(function) + ": " + msg;
}

CvodeIntegrator::~CvodeIntegrator() {
  if (mem_) CVodeFree(&mem_);
  if (nls_) SUNNonlinSolFree(nls_);
  if (y_) N_VDestroy(y_);
  if (y_between_) N_VDestroy(y_between_);
  if (ctx_) SUNContext_Free(&ctx_);
}

void CvodeIntegrator::restart(double t) {
  if (!initialised_) {
    initialise(t);
    return;
  }
  check(CVodeReInit(mem_, t, y_), "CVodeReInit");
  counters_reset();
}

void CvodeIntegrator::take_step(double t_end, double& t_reached) {
  check(CVode(mem_, t_end, y_, &t_reached, CV_ONE_STEP), "CVode");
}

const double* CvodeIntegrator::state_at(double t) {
  check(CVodeGetDky(mem_, t, 0, y_between_), "CVodeGetDky");
  return N_VGetArrayPointer(y_between_);
}

void CvodeIntegrator::count_work(int& steps, int& error_test_failures) {
  long now_steps = 0, now_failures = 0;
  CVodeGetNumSteps(mem_, &now_steps);
  CVodeGetNumErrTestFails(mem_, &now_failures);
  add_work(now_steps, now_failures, steps, error_test_failures);
}

void CvodeIntegrator::initialise(double t) {
  check(CVodeInit(mem_, rhs_, t, y_), "CVodeInit");
  check(CVodeSetUserData(mem_, static_cast<OdeIntegrator*>(this)), "CVodeSetUserData");
  nls_ = SUNNonlinSol_FixedPoint(y_, 0, ctx_);
  check(CVodeSetNonlinearSolver(mem_, nls_), "CVodeSetNonlinearSolver");
  check(CVodeSetMaxNumSteps(mem_, options_.max_steps), "CVodeSetMaxNumSteps");
  check(CVodeWFtolerances(mem_, &OdeIntegrator::error_weights), "CVodeWFtolerances");
  // A restart (every new sensor sample) would otherwise begin with CVODE's own estimate of
  // the first step, which costs right-hand sides; a small fixed one grows within a few steps.
  if (options_.initial_step > 0) check(CVodeSetInitStep(mem_, options_.initial_step), "CVodeSetInitStep");
  check(CVodeSetEtaMaxEarlyStep(mem_, options_.max_early_growth), "CVodeSetEtaMaxEarlyStep");
  check(CVodeSetNonlinConvCoef(mem_, options_.nonlinear_convergence), "CVodeSetNonlinConvCoef");
  initialised_ = true;  // (CVodeReInit keeps these options)
}

}  // namespace wysiwyf::haptics
