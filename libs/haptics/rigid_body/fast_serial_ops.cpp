#include "rigid_body/fast_serial_ops.hpp"

#include <nvector/nvector_serial.h>

#include <cmath>

namespace wysiwyf::haptics {

namespace {

double* data(N_Vector v) { return NV_DATA_S(v); }
sunindextype length(N_Vector v) { return NV_LENGTH_S(v); }

// z = a x + b y (z may be x or y)
void linear_sum(sunrealtype a, N_Vector x, sunrealtype b, N_Vector y, N_Vector z) {
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  for (sunindextype i = 0, n = length(z); i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
}

// z = c x (z may be x)
void scale(sunrealtype c, N_Vector x, N_Vector z) {
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0, n = length(z); i < n; ++i) zd[i] = c * xd[i];
}

void constant(sunrealtype c, N_Vector z) {
  double* zd = data(z);
  for (sunindextype i = 0, n = length(z); i < n; ++i) zd[i] = c;
}

// sqrt(sum (x_i w_i)^2 / n)
sunrealtype weighted_rms_norm(N_Vector x, N_Vector w) {
  const double *xd = data(x), *wd = data(w);
  const sunindextype n = length(x);
  double sum = 0;
  for (sunindextype i = 0; i < n; ++i) sum += (xd[i] * wd[i]) * (xd[i] * wd[i]);
  return std::sqrt(sum / static_cast<double>(n));
}

// z = sum_j c_j X_j, element by element (z may be X_0: each element is read before it is written)
int linear_combination(int count, sunrealtype* c, N_Vector* X, N_Vector z) {
  double* zd = data(z);
  const sunindextype n = length(z);
  if (count == 1) {
    scale(c[0], X[0], z);
    return 0;
  }
  const double *x0 = data(X[0]), *x1 = data(X[1]);
  int j = 2;
  for (sunindextype i = 0; i < n; ++i) zd[i] = c[0] * x0[i] + c[1] * x1[i];
  for (; j + 1 < count; j += 2) {  // (two vectors a pass)
    const double *xa = data(X[j]), *xb = data(X[j + 1]);
    for (sunindextype i = 0; i < n; ++i) zd[i] += c[j] * xa[i] + c[j + 1] * xb[i];
  }
  if (j < count) {
    const double* xa = data(X[j]);
    for (sunindextype i = 0; i < n; ++i) zd[i] += c[j] * xa[i];
  }
  return 0;
}

}  // namespace

void install_fast_serial_ops(N_Vector v) {
  v->ops->nvlinearsum = &linear_sum;
  v->ops->nvscale = &scale;
  v->ops->nvconst = &constant;
  v->ops->nvwrmsnorm = &weighted_rms_norm;
  v->ops->nvlinearcombination = &linear_combination;
}

}  // namespace wysiwyf::haptics
