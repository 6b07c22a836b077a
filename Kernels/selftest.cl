// selftest.cl: kernels that prove the OpenCL device works and measure its atomics.
// Built after refracta_atomics.cl.

// y[i] = a * x[i] + y[i]. Work layout: one work-item per element, global size = n.
__kernel void refracta_saxpy(const float a, __global const float* x, __global float* y,
  const unsigned int n)
{
  const size_t i = get_global_id(0);
  if (i < n)
  {
    y[i] = a * x[i] + y[i];
  }
}

// Contention test for fixed-point accumulation: every work-item adds values[i] into
// accumulators[i % numberOfTargets]. With numberOfTargets = 1 all work-items hit one address.
// Work layout: one work-item per value, global size = number of values.
__kernel void refracta_atomic_fixed_contention(__global const float* values,
  volatile __global long* accumulators, const unsigned int numberOfTargets)
{
  const size_t i = get_global_id(0);
  refracta_atomic_add_fixed(&accumulators[i % numberOfTargets], values[i]);
}

// The same contention pattern with the compare-and-swap float add.
__kernel void refracta_atomic_float_cas_contention(__global const float* values,
  volatile __global float* accumulators, const unsigned int numberOfTargets)
{
  const size_t i = get_global_id(0);
  refracta_atomic_add_float_cas(&accumulators[i % numberOfTargets], values[i]);
}
