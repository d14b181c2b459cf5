// The logistic function, evaluated without overflow: the one place the slice model's lobe
// 1 / (1 + e^t) = Logistic(-t) is computed (brdf/, the reconstruction's fit and its light
// refinement). T is double or a ceres::Jet (exp is found by argument-dependent lookup).
#pragma once

#include <cmath>

namespace brdfrig::brdf {

// 1 / (1 + e^-x), never evaluating exp of a positive number: branches on the sign of x.
template <typename T>
T Logistic(const T& x) {
  using std::exp;
  if (x >= T(0)) return T(1) / (T(1) + exp(-x));
  const T e = exp(x);
  return e / (T(1) + e);
}

}  // namespace brdfrig::brdf
