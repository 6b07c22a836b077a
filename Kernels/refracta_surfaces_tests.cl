// refracta_surfaces_tests.cl: kernels that expose refracta_surfaces.cl to RefractaCore's tests
// (closest hit, any hit, texel index). Built after refracta_surfaces.cl by the tests only, so
// that no production program carries them.

// One ray per work-item (surface frame): hits[i] = (t, u, v, triangle as int bits), triangle -1
// when nothing is hit; occluded[i] = any hit before tMax[i].
__kernel void refracta_test_trace(__global const float4* nodes, const int nodeCount,
  __global const float4* triangles, __global const float4* origins,
  __global const float4* directions, __global const float* tMax, __global float4* hits,
  __global int* occluded, const uint n)
{
  const size_t i = get_global_id(0);
  if (i >= n)
  {
    return;
  }
  const float3 o = origins[i].xyz;
  const float3 d = directions[i].xyz;
  const refracta_hit h =
    refracta_bvh_closest(nodes, nodeCount, triangles, o, d, 0.0f, tMax[i]);
  hits[i] = (float4)(h.t, h.u, h.v, as_float(h.triangle));
  occluded[i] = refracta_bvh_occluded(nodes, nodeCount, triangles, o, d, 0.0f, tMax[i]) ? 1 : 0;
}

// out[i] = refracta_texel_index(uv[2 i], uv[2 i + 1], subdivision[i]).
__kernel void refracta_test_texel(__global const float* uv, __global const int* subdivision,
  __global int* out, const uint n)
{
  const size_t i = get_global_id(0);
  if (i < n)
  {
    out[i] = refracta_texel_index(uv[2 * i], uv[2 * i + 1], subdivision[i]);
  }
}

// One dielectric choice per work-item: in[3 i] = (d, nInside), in[3 i + 1] = (ng, nOutside),
// in[3 i + 2] = (ns, xi); out[i] = (direction, reflectance), transmitted[i] = the branch.
__kernel void refracta_test_dielectric(__global const float4* in, __global float4* out,
  __global int* transmitted, const uint n)
{
  const size_t i = get_global_id(0);
  if (i >= n)
  {
    return;
  }
  const float4 a = in[3 * i];
  const float4 b = in[3 * i + 1];
  const float4 c = in[3 * i + 2];
  int t;
  float r, etaFrom, etaTo;
  const float3 dir =
    refracta_dielectric_sample(a.xyz, b.xyz, c.xyz, a.w, b.w, c.w, &t, &r, &etaFrom, &etaTo);
  out[i] = (float4)(dir, r);
  transmitted[i] = t;
}
