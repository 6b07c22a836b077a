// radiance_smooth.cl: turns the photon pass's fixed-point accumulators into the Radiance and
// RadianceDirection arrays, with the optional 3x3x3 smoothing of Sun et al. 2008, section 4.4.
//
// radiance_resolve: one work-item per voxel; fixed point -> float, 3 values per voxel from long
//   `first` on, times `factor` (deposits: 1 / (scale x voxel volume), power per unit volume;
//   direction sums: 1 / scale, kept unnormalised until after the smoothing).
// radiance_smooth: one work-item per voxel, 3-component field. Kernel: the binomial (1, 2, 1) / 4
//   per axis (a 3x3x3 approximation of a Gaussian), with a mirror boundary: a weight that falls
//   outside the grid lands on the voxel mirrored back inside (the face voxel itself). Per axis the
//   operator is then a symmetric matrix whose rows and columns all sum to 1, so a constant field
//   stays constant at faces, edges and corners (rows) and the total over the grid is conserved
//   (columns): the smoothing moves energy, it never creates or loses it, and it biases no layer.
//   (Renormalising each source voxel's weights over the neighbours that exist also conserves the
//   total, but a uniform field then reads 0.92 in the face layer and 1.08 in the next.)
// radiance_normalize: one work-item per voxel; unit direction, or zero where nothing arrived.

__kernel void radiance_resolve(__global const long* fixedPoint, const ulong first,
  const float factor, __global float* out, const uint count)
{
  const size_t id = get_global_id(0);
  if (id >= count)
  {
    return;
  }
  for (int c = 0; c < 3; ++c)
  {
    out[3 * id + c] = (float)fixedPoint[first + 3 * id + c] * factor;
  }
}

// Mirror of index i into [0, n): the neighbour beyond a face is the face voxel itself
// (half-sample symmetric reflection, -1 -> 0 and n -> n - 1).
inline int radiance_mirror(int i, int n)
{
  return i < 0 ? 0 : (i >= n ? n - 1 : i);
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
    const int kk = radiance_mirror(k + dk, dims.z);
    const float wk = dk == 0 ? 0.5f : 0.25f;
    for (int dj = -1; dj <= 1; ++dj)
    {
      const int jj = radiance_mirror(j + dj, dims.y);
      const float wj = wk * (dj == 0 ? 0.5f : 0.25f);
      for (int di = -1; di <= 1; ++di)
      {
        const int ii = radiance_mirror(i + di, dims.x);
        const float w = wj * (di == 0 ? 0.5f : 0.25f);
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
