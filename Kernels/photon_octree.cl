// photon_octree.cl: the photon pass's acceleration structure (Sun et al. 2008, sections 4.2 and
// 5.3) and the refractive-index gradient when the medium does not carry one.
//
// The octree is the paper's dense level array: one byte per voxel holding the level L of the
// leaf node that covers it (node = the 2^L-voxel cube containing it, aligned to multiples of 2^L)
// and, in bit 7, whether the node's index range only met the secondary tolerance (then the step
// inside it is capped). It is built from a min/max pyramid of the refractive index:
//   level 0: min/max of n over the 3x3x3 neighbourhood of each voxel (clamped to the grid): the
//            trilinear field inside a voxel's box depends on its neighbours, so this range bounds
//            what a photon can see there;
//   level k: min/max over the (up to) 2x2x2 children of level k-1; level k has ceil(N / 2^k)
//            nodes per axis, so any grid size works (remainder nodes just have fewer children).
// Labelling walks each voxel's ancestors from the coarsest level to the finest and takes the
// first whose range is < REFRACTA_EPS (unlimited step) or < REFRACTA_EPS2 (step capped), as in section 5.3.
//
// Options: -DEPS=<float> primary tolerance, -DEPS2=<float> secondary tolerance.
// Work layout: one work-item per voxel (or per node of the level being built), 1D.

#ifndef REFRACTA_EPS
#define REFRACTA_EPS 0.005f
#endif
#ifndef REFRACTA_EPS2
#define REFRACTA_EPS2 0.02f
#endif

inline int3 photon_voxel_ijk(int4 dims, size_t id)
{
  const int i = (int)(id % (size_t)dims.x);
  const int j = (int)((id / (size_t)dims.x) % (size_t)dims.y);
  const int k = (int)(id / ((size_t)dims.x * (size_t)dims.y));
  return (int3)(i, j, k);
}

// grad n by central differences (one-sided at the edges, 0 along an axis of one voxel).
__kernel void photon_gradient(__global const float* n, const int4 dims, const float4 spacing,
  __global float* gradient, const uint count)
{
  const size_t id = get_global_id(0);
  if (id >= count)
  {
    return;
  }
  const int3 c = photon_voxel_ijk(dims, id);
  float g[3];
  const int d[3] = { dims.x, dims.y, dims.z };
  const float s[3] = { spacing.x, spacing.y, spacing.z };
  for (int a = 0; a < 3; ++a)
  {
    int3 lo = c;
    int3 hi = c;
    const int ca = a == 0 ? c.x : (a == 1 ? c.y : c.z);
    const int l = max(ca - 1, 0);
    const int h = min(ca + 1, d[a] - 1);
    if (a == 0)
    {
      lo.x = l;
      hi.x = h;
    }
    else if (a == 1)
    {
      lo.y = l;
      hi.y = h;
    }
    else
    {
      lo.z = l;
      hi.z = h;
    }
    g[a] = h > l ? (n[refracta_voxel_index(dims, hi.x, hi.y, hi.z)] -
                     n[refracta_voxel_index(dims, lo.x, lo.y, lo.z)]) /
        ((float)(h - l) * s[a])
                 : 0.0f;
  }
  vstore3((float3)(g[0], g[1], g[2]), id, gradient);
}

// Level 0 of the pyramid: (min, max) of n over the clamped 3x3x3 neighbourhood.
__kernel void photon_pyramid_base(
  __global const float* n, const int4 dims, __global float2* level0, const uint count)
{
  const size_t id = get_global_id(0);
  if (id >= count)
  {
    return;
  }
  const int3 c = photon_voxel_ijk(dims, id);
  float lo = INFINITY;
  float hi = -INFINITY;
  for (int k = max(c.z - 1, 0); k <= min(c.z + 1, dims.z - 1); ++k)
  {
    for (int j = max(c.y - 1, 0); j <= min(c.y + 1, dims.y - 1); ++j)
    {
      for (int i = max(c.x - 1, 0); i <= min(c.x + 1, dims.x - 1); ++i)
      {
        const float v = n[refracta_voxel_index(dims, i, j, k)];
        lo = fmin(lo, v);
        hi = fmax(hi, v);
      }
    }
  }
  level0[id] = (float2)(lo, hi);
}

// Level k from level k-1: (min, max) over the existing children.
// `pyramid` holds every level; fineOffset and coarseOffset locate the two levels in it.
__kernel void photon_pyramid_reduce(__global float2* pyramid, const uint fineOffset,
  const int4 fineDims, const uint coarseOffset, const int4 coarseDims, const uint count)
{
  __global const float2* fine = pyramid + fineOffset;
  __global float2* coarse = pyramid + coarseOffset;
  const size_t id = get_global_id(0);
  if (id >= count)
  {
    return;
  }
  const int3 c = photon_voxel_ijk(coarseDims, id);
  float lo = INFINITY;
  float hi = -INFINITY;
  for (int k = 2 * c.z; k <= min(2 * c.z + 1, fineDims.z - 1); ++k)
  {
    for (int j = 2 * c.y; j <= min(2 * c.y + 1, fineDims.y - 1); ++j)
    {
      for (int i = 2 * c.x; i <= min(2 * c.x + 1, fineDims.x - 1); ++i)
      {
        const float2 v = fine[refracta_voxel_index(fineDims, i, j, k)];
        lo = fmin(lo, v.x);
        hi = fmax(hi, v.y);
      }
    }
  }
  coarse[id] = (float2)(lo, hi);
}

// The level array: bits 0-4 the leaf level, bit 7 set when the step inside is capped.
// levelOffsets[k] is the offset of pyramid level k in `pyramid`; `levels` the number of levels.
__kernel void photon_octree_label(__global const float2* pyramid,
  __global const uint* levelOffsets, const int levels, const int4 dims, __global uchar* octree,
  const uint count)
{
  const size_t id = get_global_id(0);
  if (id >= count)
  {
    return;
  }
  const int3 c = photon_voxel_ijk(dims, id);
  uchar label = 0;
  for (int k = levels - 1; k >= 0; --k)
  {
    const int4 dk = (int4)((dims.x + (1 << k) - 1) >> k, (dims.y + (1 << k) - 1) >> k,
      (dims.z + (1 << k) - 1) >> k, 0);
    const float2 r = pyramid[levelOffsets[k] + refracta_voxel_index(dk, c.x >> k, c.y >> k, c.z >> k)];
    const float range = r.y - r.x;
    if (range < REFRACTA_EPS)
    {
      label = (uchar)k;
      break;
    }
    if (range < REFRACTA_EPS2)
    {
      label = (uchar)(k | 0x80);
      break;
    }
  }
  octree[id] = label;
}
