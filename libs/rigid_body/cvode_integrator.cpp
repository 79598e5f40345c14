#include "rigid_body/cvode_integrator.hpp"

#include <nvector/nvector_serial.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace wysiwyf::haptics {

CvodeIntegrator::CvodeIntegrator(int size, const CvodeOptions& options, void* system, CVRhsFn rhs, CVRootFn roots)
    : options_(options), system_(system), rhs_(rhs), roots_(roots) {
  if (SUNContext_Create(nullptr, &ctx_) != 0) throw std::runtime_error("SUNDIALS: cannot create a context");
  y_ = N_VNew_Serial(size, ctx_);
  mem_ = CVodeCreate(CV_ADAMS, ctx_);  // non-stiff rigid-body dynamics: Adams-Moulton
  if (!y_ || !mem_) throw std::runtime_error("SUNDIALS: cannot create the CVODE integrator");
  check(CVodeSetErrHandlerFn(mem_, &CvodeIntegrator::keep_message, this), "CVodeSetErrHandlerFn");
}

void CvodeIntegrator::keep_message(int, const char*, const char* function, char* msg, void* self) {
  static_cast<CvodeIntegrator*>(self)->message_ = std::string(function) + ": " + msg;
}

CvodeIntegrator::~CvodeIntegrator() {
  if (mem_) CVodeFree(&mem_);
  if (nls_) SUNNonlinSolFree(nls_);
  if (y_) N_VDestroy(y_);
  if (ctx_) SUNContext_Free(&ctx_);
}

// CVODE's error weights 1 / (rtol |y_i| + atol), in one pass (its own scalar-tolerance
// version takes five vector operations, at every step).
int CvodeIntegrator::error_weights(N_Vector y, N_Vector ewt, void* self) {
  const CvodeOptions& o = static_cast<CvodeIntegrator*>(self)->options_;
  const double* yy = N_VGetArrayPointer(y);
  double* w = N_VGetArrayPointer(ewt);
  for (sunindextype i = 0, n = N_VGetLength(y); i < n; ++i) w[i] = 1.0 / (o.rtol * std::abs(yy[i]) + o.atol);
  return 0;
}

void CvodeIntegrator::initialise(double t) {
  check(CVodeInit(mem_, rhs_, t, y_), "CVodeInit");
  check(CVodeSetUserData(mem_, this), "CVodeSetUserData");
  nls_ = SUNNonlinSol_FixedPoint(y_, 0, ctx_);
  check(CVodeSetNonlinearSolver(mem_, nls_), "CVodeSetNonlinearSolver");
  check(CVodeSetMaxNumSteps(mem_, options_.max_steps), "CVodeSetMaxNumSteps");
  check(CVodeWFtolerances(mem_, &CvodeIntegrator::error_weights), "CVodeWFtolerances");
  // A restart (every new sensor sample) would otherwise begin with CVODE's own estimate of
  // the first step, which costs right-hand sides; a small fixed one grows within a few steps.
  if (options_.initial_step > 0) check(CVodeSetInitStep(mem_, options_.initial_step), "CVodeSetInitStep");
  check(CVodeSetEtaMaxEarlyStep(mem_, options_.max_early_growth), "CVodeSetEtaMaxEarlyStep");
  check(CVodeSetNonlinConvCoef(mem_, options_.nonlinear_convergence), "CVodeSetNonlinConvCoef");
  initialised_ = true;  // (CVodeReInit keeps these options)
}

void CvodeIntegrator::watch_roots(int count) {
  std::vector<int> directions(static_cast<std::size_t>(count), -1);  // downward only
  check(CVodeRootInit(mem_, count, count == 0 ? nullptr : roots_), "CVodeRootInit");
  if (count != 0) check(CVodeSetRootDirection(mem_, directions.data()), "CVodeSetRootDirection");
}

void CvodeIntegrator::fail(int flag, const char* call) {
  std::string what = std::string("CVODE ") + call + " failed: " + CVodeGetReturnFlagName(flag);
  if (!message_.empty()) what += " (" + message_ + ")";
  if (!callback_error_.empty()) what += "; the right-hand side or a root function threw: " + callback_error_;
  message_.clear();
  callback_error_.clear();
  throw std::runtime_error(what);
}

}  // namespace wysiwyf::haptics
