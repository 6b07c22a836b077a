// view_caustic.cl: the single-scattered light the view pass shows, from the lighting grid's S1
// and from the volume caustic's bricks (Documentation/Physics.md "Volume caustics"). Prepended to
// view_pass.cl (after refracta_common.cl: the HG phase, the voxel index).

#ifndef REFRACTA_INV_4PI
#define REFRACTA_INV_4PI 0.0795774715459476679f
#endif

// The phase-weighted S1 of light with (trilinearly blended) mean direction `mean` seen towards
// -d: unit vectors shorten when blended, so `mean` is re-normalised, and the phase falls back to
// isotropic where the stored directions cancel.
inline float3 refracta_view_single(float3 s1, float3 mean, float3 d, float g)
{
  const float len = length(mean);
  const float phase = len > 1e-6f ? refracta_hg_phase(dot(mean, -d) / len, g) : REFRACTA_INV_4PI;
  return phase * s1;
}

#ifdef REFRACTA_HAS_SINGLE
// The volume caustic (vtkRefractaLightingVolume::VolumeCaustic*Name(); Physics.md "Volume
// caustics"): in a voxel with a brick, the focused light's S1 at c times the resolution, trilinear
// over the brick's c^3 fine voxels (clamped at the brick's faces: a brick holds only the light
// that crossed its own voxel), with its own mean direction. `u` is the point in voxel coordinates
// (voxel centres at integers). Zero outside bricks: there the light is in Radiance.
inline float3 refracta_view_volume_caustic(int4 dims, float3 u, float3 d, float g,
  __global const int* bricks, __global const float* fine, __global const float* fineDirection,
  int c)
{
  const int3 v = clamp(convert_int3_rtn(u + 0.5f), (int3)(0), dims.xyz - 1);
  const int brick = bricks[refracta_voxel_index(dims, v.x, v.y, v.z)];
  if (brick < 0)
  {
    return (float3)(0.0f);
  }
  // Fine coordinates with fine-voxel centres at integers 0 .. c - 1.
  const float3 f =
    clamp((u - convert_float3(v) + 0.5f) * (float)c - 0.5f, (float3)(0.0f), (float3)(c - 1));
  const int3 f0 = min(convert_int3_rtn(f), (int3)(c - 2));
  const float3 w = f - convert_float3(f0);
  const size_t first = (size_t)brick * (size_t)(c * c * c);
  float3 s1 = (float3)(0.0f);
  float3 mean = (float3)(0.0f);
  for (int corner = 0; corner < 8; ++corner)
  {
    const int3 o = (int3)(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const float weight = (o.x ? w.x : 1.0f - w.x) * (o.y ? w.y : 1.0f - w.y) *
      (o.z ? w.z : 1.0f - w.z);
    const int3 q = f0 + o;
    const size_t index = first + (size_t)((q.z * c + q.y) * c + q.x);
    s1 += weight * vload3(index, fine);
    mean += weight * vload3(index, fineDirection);
  }
  return refracta_view_single(s1, mean, d, g);
}
#endif
