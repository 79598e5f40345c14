#pragma once
// SUNDIALS' serial vector operations that the integrators spend their own time in, compiled with
// this library's flags. Debian's SUNDIALS 6.4.1 is built without optimisation (its loops keep
// their index on the stack: about 20 instructions an element), which would make the vector
// arithmetic of a Runge-Kutta step a large share of a pushed pile's haptic step. The integrators
// clone their work vectors from the state vector, operations table included, so setting it on
// that one vector before the integrator is created is enough.
#include <sundials/sundials_nvector.h>

namespace wysiwyf::haptics {

// Replaces linear sum, scale, constant, weighted RMS norm and linear combination (fused: one
// pass over the vectors) in v's operations table; v must be a serial vector (N_VNew_Serial).
void install_fast_serial_ops(N_Vector v);

}  // namespace wysiwyf::haptics
