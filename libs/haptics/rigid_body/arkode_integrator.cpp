#include "rigid_body/arkode_integrator.hpp"

#include <nvector/nvector_serial.h>

#include <stdexcept>
#include <string>

#include "rigid_body/fast_serial_ops.hpp"

namespace wysiwyf::haptics {

ArkodeIntegrator::ArkodeIntegrator(int size, const IntegratorOptions& options, void* system, ARKRhsFn rhs)
    : OdeIntegrator(system), options_(options), rhs_(rhs) {
  rtol_ = options.rtol, atol_ = options.atol;
  if (SUNContext_Create(nullptr, &ctx_) != 0) throw std::runtime_error("SUNDIALS: cannot create a context");
  y_ = N_VNew_Serial(size, ctx_);
  y_between_ = N_VNew_Serial(size, ctx_);
  if (!y_ || !y_between_) throw std::runtime_error("SUNDIALS: cannot create the state vector");
  install_fast_serial_ops(y_);  // (before ERKStepCreate clones its vectors from y_)
  install_fast_serial_ops(y_between_);
  N_VConst(0.0, y_);
}

void ArkodeIntegrator::keep_message(int, const char*, const char* function, char* msg, void* self) {
  static_cast<ArkodeIntegrator*>(static_cast<OdeIntegrator*>(self))->message_ = std::string(function) + ": " + msg;
}

ArkodeIntegrator::~ArkodeIntegrator() {
  if (mem_) ERKStepFree(&mem_);
  if (y_) N_VDestroy(y_);
  if (y_between_) N_VDestroy(y_between_);
  if (ctx_) SUNContext_Free(&ctx_);
}

void ArkodeIntegrator::restart(double t) {
  if (!mem_) {
    initialise(t);
    return;
  }
  check(ERKStepReset(mem_, t, y_), "ERKStepReset");
}

void ArkodeIntegrator::take_step(double t_end, double& t_reached) {
  check(ERKStepEvolve(mem_, t_end, y_, &t_reached, ARK_ONE_STEP), "ERKStepEvolve");
}

const double* ArkodeIntegrator::state_at(double t) {
  check(ERKStepGetDky(mem_, t, 0, y_between_), "ERKStepGetDky");
  return N_VGetArrayPointer(y_between_);
}

void ArkodeIntegrator::count_work(int& steps, int& error_test_failures) {
  long now_steps = 0, now_failures = 0;
  ERKStepGetNumSteps(mem_, &now_steps);
  ERKStepGetNumErrTestFails(mem_, &now_failures);
  add_work(now_steps, now_failures, steps, error_test_failures);
}

void ArkodeIntegrator::initialise(double t) {
  mem_ = ERKStepCreate(rhs_, t, y_, ctx_);  // explicit: non-stiff dynamics
  if (!mem_) throw std::runtime_error("SUNDIALS: cannot create the ARKODE integrator");
  check(ERKStepSetErrHandlerFn(mem_, &ArkodeIntegrator::keep_message, static_cast<OdeIntegrator*>(this)),
        "ERKStepSetErrHandlerFn");
  check(ERKStepSetUserData(mem_, static_cast<OdeIntegrator*>(this)), "ERKStepSetUserData");
  check(ERKStepSetTableNum(mem_, ARKODE_BOGACKI_SHAMPINE_4_2_3), "ERKStepSetTableNum");
  check(ERKStepSetMaxNumSteps(mem_, options_.max_steps), "ERKStepSetMaxNumSteps");
  check(ERKStepWFtolerances(mem_, &OdeIntegrator::error_weights), "ERKStepWFtolerances");
}

}  // namespace wysiwyf::haptics
