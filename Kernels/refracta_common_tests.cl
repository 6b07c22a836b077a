// refracta_common_tests.cl: kernels that expose refracta_common.cl's helpers to RefractaOpenCL's
// tests (trilinear sampling, the Henyey-Greenstein phase, the random streams). Built after
// refracta_common.cl by the tests only, so that no production program carries them.

// out[i] = trilinear sample of field at points[i] (continuous voxel coordinates).
__kernel void refracta_test_sample(__global const float* field, const int4 dims,
  __global const float* points, __global float* out, const uint n)
{
  const size_t i = get_global_id(0);
  if (i < n)
  {
    out[i] = refracta_sample1(field, dims, vload3(i, points));
  }
}

// out[i] = HG phase for cosTheta[i].
__kernel void refracta_test_phase(__global const float* cosTheta, const float g,
  __global float* out, const uint n)
{
  const size_t i = get_global_id(0);
  if (i < n)
  {
    out[i] = refracta_hg_phase(cosTheta[i], g);
  }
}

// out[i * count + c] = the c-th uniform number of stream (seed, i).
__kernel void refracta_test_rng(const uint seed, const uint count, __global float* out, const uint n)
{
  const size_t i = get_global_id(0);
  if (i < n)
  {
    uint state = refracta_rng_seed(seed, (uint)i);
    for (uint c = 0; c < count; ++c)
    {
      out[i * count + c] = refracta_rng_uniform(&state);
    }
  }
}
