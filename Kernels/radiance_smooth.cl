// radiance_smooth.cl: turns the photon pass's fixed-point accumulators into the Radiance and
// RadianceDirection arrays, with the optional 3x3x3 smoothing of Sun et al. 2008, section 4.4.
//
// radiance_resolve: one work-item per voxel; fixed point -> float; Radiance divided by the voxel
//   volume (Physics.md: power per unit volume), the direction sums kept unnormalised.
// radiance_smooth: one work-item per voxel, 3-component field. Kernel: the binomial (1, 2, 1) / 4
//   per axis (a 3x3x3 approximation of a Gaussian). It is applied in scatter form: each source
//   voxel's weights are renormalised over the neighbours that exist, so the total over the grid
//   is conserved exactly (the smoothing moves energy, it never creates or loses it at the edges).
// radiance_normalize: one work-item per voxel; unit direction, or zero where nothing arrived.

__kernel void radiance_resolve(__global const long* radianceFixed,
  __global const long* directionFixed, const float radianceFactor, const float directionFactor,
  __global float* radiance, __global float* direction, const uint count)
{
  const size_t id = get_global_id(0);
  if (id >= count)
  {
    return;
  }
  for (int c = 0; c < 3; ++c)
  {
    radiance[3 * id + c] = (float)radianceFixed[3 * id + c] * radianceFactor;
    direction[3 * id + c] = (float)directionFixed[3 * id + c] * directionFactor;
  }
}

// Sum of the in-grid binomial weights around index i on an axis of n voxels.
inline float radiance_axis_norm(int i, int n)
{
  return 0.5f + (i > 0 ? 0.25f : 0.0f) + (i < n - 1 ? 0.25f : 0.0f);
}

__kernel void radiance_smooth(
  __global const float* in, const int4 dims, __global float* out, const uint count)
{
  const size_t id = get_global_id(0);
  if (id >= count)
  {
    return;
  }
  const int i = (int)(id % (size_t)dims.x);
  const int j = (int)((id / (size_t)dims.x) % (size_t)dims.y);
  const int k = (int)(id / ((size_t)dims.x * (size_t)dims.y));
  float3 sum = (float3)(0.0f);
  for (int dk = -1; dk <= 1; ++dk)
  {
    const int kk = k + dk;
    if (kk < 0 || kk >= dims.z)
    {
      continue;
    }
    const float wk = (dk == 0 ? 0.5f : 0.25f) / radiance_axis_norm(kk, dims.z);
    for (int dj = -1; dj <= 1; ++dj)
    {
      const int jj = j + dj;
      if (jj < 0 || jj >= dims.y)
      {
        continue;
      }
      const float wj = wk * (dj == 0 ? 0.5f : 0.25f) / radiance_axis_norm(jj, dims.y);
      for (int di = -1; di <= 1; ++di)
      {
        const int ii = i + di;
        if (ii < 0 || ii >= dims.x)
        {
          continue;
        }
        const float w = wj * (di == 0 ? 0.5f : 0.25f) / radiance_axis_norm(ii, dims.x);
        sum += w * vload3(refracta_voxel_index(dims, ii, jj, kk), in);
      }
    }
  }
  vstore3(sum, id, out);
}

__kernel void radiance_normalize(__global float* direction, const uint count)
{
  const size_t id = get_global_id(0);
  if (id >= count)
  {
    return;
  }
  const float3 d = vload3(id, direction);
  const float m = length(d);
  vstore3(m > 0.0f && isfinite(m) ? d / m : (float3)(0.0f), id, direction);
}
