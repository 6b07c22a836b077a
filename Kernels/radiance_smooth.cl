// radiance_smooth.cl: turns the photon pass's fixed-point accumulators into the Radiance and
// RadianceDirection arrays, with the optional 3x3x3 smoothing of Sun et al. 2008, section 4.4.
//
// radiance_resolve: one work-item per voxel; fixed point -> float, 3 values per voxel from long
//   `first` on, `stride` longs apart from voxel to voxel, times `factor` (deposits: 1 / (scale x voxel volume), power per unit volume;
//   direction sums: 1 / scale, kept unnormalised until after the smoothing).
// radiance_smooth_axis: one work-item per voxel, 3-component field, one grid axis per launch (the
//   three launches make the 3x3x3 filter). Each neighbour pair (i, j) along the axis exchanges
//   out_i = in_i + w_ij (in_j - in_i) with a symmetric weight w_ij = g_ij / 4. With g = 1 this is
//   the binomial (1, 2, 1) / 4 (a 3x3x3 approximation of a Gaussian) with a mirror boundary (a
//   weight that falls outside the grid lands on the face voxel itself: nothing crosses a face).
//   The operator is a symmetric matrix whose rows and columns all sum to 1, for any g: a constant
//   field stays constant at faces, edges and corners (rows) and the total over the grid is
//   conserved (columns). g_ij = (lo / hi) x b(tau), with lo and hi the pair's smaller and larger
//   sigma_t (largest channel) and tau = h hi: the plain filter between alike, optically thin
//   voxels; none where either voxel has no extinction (a body and the vacuum beside it, or two
//   vacuum voxels that hold deposits from the edge of a body's cell); and b < 1 where a voxel is
//   optically thick, where deposits fall off within a voxel (light entering a dense medium): b
//   keeps the filter's relative change of exp(-sigma_t x) within `biasLimit`
//   (vtkPhotonTracer::SmoothingBias). Otherwise the filter moves light out of a dense body's
//   first voxels into the thinner ones outside, which the camera sees unattenuated.
//   (Renormalising each source voxel's weights over the neighbours that exist also conserves the
//   total, but a uniform field then reads 0.92 in the face layer and 1.08 in the next.)
//   A pair whose link an opaque surface cuts (bit `axis` of cut[lower voxel], with cutLinks) is
//   not exchanged either: light on the two sides of a wall is not one field.
//   Symmetric and row-stochastic still, so conservation and constants hold.
// radiance_normalize: one work-item per voxel; unit direction, or zero where nothing arrived.

// radiance_sum_lobes: one work-item per accumulator of a block (6 per voxel): S1's lobes (the
// blocks 1 .. lobes after block 0, `count` accumulators each, vtkPhotonTracer::
// MaximumRadianceLobes) summed into block 0, which the photons then leave empty: all of S1.
__kernel void radiance_sum_lobes(__global long* fixedPoint, const ulong count, const int lobes)
{
  const size_t id = get_global_id(0);
  if (id >= count)
  {
    return;
  }
  long sum = 0;
  for (int k = 1; k <= lobes; ++k)
  {
    sum += fixedPoint[(size_t)k * count + id];
  }
  fixedPoint[id] = sum;
}

__kernel void radiance_resolve(__global const long* fixedPoint, const ulong first,
  const uint stride, const float factor, __global float* out, const uint count)
{
  const size_t id = get_global_id(0);
  if (id >= count)
  {
    return;
  }
  for (int c = 0; c < 3; ++c)
  {
    out[3 * id + c] = (float)fixedPoint[first + stride * id + c] * factor;
  }
}

// Smoothing weight factor g of a neighbour pair whose optical depth across one voxel is tau:
// 1 where the plain filter's bias on exp(-sigma_t x) stays within biasLimit, else what keeps it
// there (the filter's relative change of exp(-tau i) is g (cosh(tau) - 1) / 2). tauLimit =
// acosh(1 + 2 biasLimit), from the host: cosh (a slow call on CPU devices, 12% of a photon pass's
// samples when it ran for every pair) is evaluated only for optically thick pairs.
inline float radiance_pair_weight(float tau, float biasLimit, float tauLimit)
{
  if (tau <= tauLimit)
  {
    return 1.0f;
  }
  const float c = cosh(tau) - 1.0f;
  return c <= 2.0f * biasLimit ? 1.0f : 2.0f * biasLimit / c;
}

// The largest channel of sigma_t in voxel v; `channels` values per voxel (1: a grey medium).
inline float radiance_sigma_max(__global const float* extinction, int channels, size_t v)
{
  if (channels == 1)
  {
    return extinction[v];
  }
  const float3 s = vload3(v, extinction);
  return fmax(s.x, fmax(s.y, s.z));
}

// extinctionChannels: 0 where nothing attenuates (the plain filter), else the values per voxel of
// `extinction` (1 grey, 3 RGB).
__kernel void radiance_smooth_axis(__global const float* in, __global const float* extinction,
  const int extinctionChannels, const int4 dims, const int axis, const float spacing,
  const float biasLimit, const float tauLimit, __global const uchar* cut, const int cutLinks,
  __global float* out, const uint count)
{
  const size_t id = get_global_id(0);
  if (id >= count)
  {
    return;
  }
  const int3 ijk = (int3)((int)(id % (size_t)dims.x),
    (int)((id / (size_t)dims.x) % (size_t)dims.y), (int)(id / ((size_t)dims.x * (size_t)dims.y)));
  const int i = axis == 0 ? ijk.x : (axis == 1 ? ijk.y : ijk.z);
  const int n = axis == 0 ? dims.x : (axis == 1 ? dims.y : dims.z);
  const size_t stride = axis == 0 ? 1 : (axis == 1 ? (size_t)dims.x : (size_t)dims.x * dims.y);
  const float3 own = vload3(id, in);
  const bool attenuates = extinctionChannels > 0;
  const float sigmaOwn = attenuates ? radiance_sigma_max(extinction, extinctionChannels, id) : 0.0f;
  float3 sum = own;
  for (int side = -1; side <= 1; side += 2)
  {
    if (i + side < 0 || i + side >= n)
    {
      continue; // mirror boundary: nothing crosses the grid's face
    }
    const size_t other = side < 0 ? id - stride : id + stride;
    if (cutLinks && ((cut[side < 0 ? other : id] >> axis) & 1))
    {
      continue; // a surface between them
    }
    float g = 1.0f;
    if (attenuates)
    {
      const float sigmaOther = radiance_sigma_max(extinction, extinctionChannels, other);
      const float hi = fmax(sigmaOwn, sigmaOther), lo = fmin(sigmaOwn, sigmaOther);
      // Deposits are sigma_s x fluence: between unlike voxels the plain filter would move light
      // from the denser into the thinner one (out of a body into the vacuum beside it); with
      // lo / hi the thinner one gains at most a quarter of what it would deposit at its
      // neighbour's fluence, and a voxel without extinction never changes.
      g = radiance_pair_weight(spacing * hi, biasLimit, tauLimit) * (hi > 0.0f ? lo / hi : 0.0f);
    }
    sum += (0.25f * g) * (vload3(other, in) - own);
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

// radiance_scale_voxels: one work-item per listed voxel, values[voxel] *= scale: the owned volumes
// of the sided deposits (vtkRefractaGridCuts::GetScaledVoxels: deposits gathered from a volume
// other than the voxel's own box become power per unit volume again), before the smoothing.
__kernel void radiance_scale_voxels(__global float* values, __global const ulong* voxels,
  __global const float* scales, const uint count)
{
  const size_t id = get_global_id(0);
  if (id >= count)
  {
    return;
  }
  const size_t v = voxels[id];
  vstore3(vload3(v, values) * scales[id], v, values);
}
