// refracta_atomics.cl: accumulation of float quantities from many work-items into one buffer.
//
// Refracta accumulates deposits (radiance, energy tallies) as 64-bit fixed point: each value is
// multiplied by REFRACTA_FIXED_SCALE (a power of two chosen on the host so that the largest
// possible sum fits in 2^62), rounded to the nearest integer, and added with atom_add on a long.
// Integer addition is associative, so the sum is exact (up to the per-deposit rounding) and does
// not depend on the order in which work-items arrive: a run with the same seed gives the same
// bits on every device. PoCL 3.1 has no float atomics; a compare-and-swap float loop is kept
// below for comparison only (it is slower and its result depends on arrival order).
//
// Prepend this file to a program's sources; define REFRACTA_FIXED_SCALE with -D (a float).
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

#ifndef REFRACTA_FIXED_SCALE
#define REFRACTA_FIXED_SCALE 4294967296.0f
#endif

// Adds value (any sign) to a fixed-point accumulator; rounds to nearest.
inline void refracta_atomic_add_fixed(volatile __global long* accumulator, float value)
{
  const long increment = convert_long_rte(value * REFRACTA_FIXED_SCALE);
  if (increment != 0)
  {
    atom_add(accumulator, increment);
  }
}

// Float add by compare-and-swap on the value's bits. Order-dependent; for measurement only.
inline void refracta_atomic_add_float_cas(volatile __global float* address, float value)
{
  union
  {
    unsigned int u;
    float f;
  } expected, desired;
  do
  {
    expected.f = *address;
    desired.f = expected.f + value;
  } while (atomic_cmpxchg((volatile __global unsigned int*)address, expected.u, desired.u) !=
    expected.u);
}
