// view_pass.cl: the viewing pass (Sun et al. 2008, section 4.5; Bernabei et al., III-D): the
// march of one leg of a view path (refracta_view_march). Prepend refracta_common.cl; the paths
// through glass, the pixels and the kernel refracta_view_pass follow in view_pixel.cl.
//
// What it computes, per pixel (Documentation/Physics.md, "The view pass"):
//   L = sum over steps of T [ p(g, cos) S1 + S_ms / (4 pi) + eps ] / n^2 ds + T_exit L_bg(d_exit)
// One view ray per pixel (several over edges of glass, view_pixel.cl) starts at the camera (perspective) or on the image plane (parallel),
// enters the medium's box [-s/2, (N - 1/2) s] (grid-local frame) and marches in fixed steps of
// STEP world units until it leaves the box, reaches the per-pixel depth limit (opaque geometry in
// a render window), falls below the transmittance cutoff, or runs out of steps. Within a step the
// medium is taken constant at the step's midpoint and the step is integrated exactly:
//   L += T Q (1 - exp(-sigma_t ds)) / sigma_t,  T *= exp(-sigma_t ds)
// so a constant medium gives the analytic emission-absorption answer for any step length.
// cos = dot(RadianceDirection, w_o) with w_o the unit direction back towards the camera.
//
// Curved rays (-DREFRACTA_CURVED): the ray equation d/ds (n dx/ds) = grad n is integrated in the
// optical parameter t (dt = ds / n), where x' = v, v' = n grad n = grad(n^2 / 2): a separable
// Hamiltonian system, advanced with the symplectic Stormer-Verlet (kick-drift-kick) scheme, which
// is second order where the papers' forward Euler is first order, and re-normalised to |v| = n
// after each step so that the speed cannot drift. Straight rays (default) need neither n nor
// grad n and step exactly along the chord, the last step clipped to the box exit.
//
// Work layout: one work-item per pixel, global size (width, height); pixel (i, j) has row j = 0 at
// the bottom (VTK's image convention). Output: hdr[4 * (i + width * j)] = (R, G, B, A) with
// A = 1 - mean transmittance of the path; steps[i + width * j] = number of steps marched;
// transmittanceOut[4 * (i + width * j)] = the path's RGB transmittance (w = 0), for compositing;
// backgroundOut[4 * (i + width * j)] = the part of the RGB radiance that is the background seen
// through the path (T_exit L_bg(d_exit) summed over its legs, w = 0), kept out of an exposure.
//
// Options (-D): REFRACTA_CURVED, REFRACTA_PARALLEL (parallel projection), REFRACTA_HAS_SINGLE
// (Radiance + RadianceDirection + Anisotropy given; with REFRACTA_RADIANCE_LOBES=K `radiance` holds
// per voxel K lobes' S1 and direction, vtkRefractaLightingVolume::RadianceLobeName), REFRACTA_HAS_MULTIPLE (MultipleScattering
// given; with REFRACTA_MULTIPLE_DIRECTION its flux over its fluence follows it in `multiple`, 3
// floats per voxel after S_ms's), REFRACTA_HAS_EMISSION, REFRACTA_HAS_ENVIRONMENT (equirectangular background image),
// REFRACTA_HAS_DEPTH_LIMIT (per-pixel maximum path length), REFRACTA_INDEX_WEIGHT (sources
// weighted by 1 / n^2 with n sampled per step), REFRACTA_SOURCE_SCALE=<1 / n^2> (a uniform n != 1),
// REFRACTA_SKIP (empty-space skipping, below), REFRACTA_HAS_SURFACES (opaque triangle surfaces,
// below; view_surfaces.cl), REFRACTA_SURFACE_NEAREST (no irradiance interpolation),
// REFRACTA_SIDED_LOOKUPS (opaque surfaces cut the grid: light is read from the sample's side of
// them, refracta_view_sided_weights; `cutLinks` and the surfaces),
// REFRACTA_DIELECTRIC (glass triangles: paths split at them, see refracta_view_dielectric_split)
// with REFRACTA_SPLIT_DEPTH=<interfaces where both legs are followed>, REFRACTA_PACKED_MEDIUM (an
// emitting medium with a grey extinction: `extinction` holds float4 (sigma, emission RGB) per voxel
// and `emission` is not read, one gather per step instead of two). With REFRACTA_HAS_SINGLE the volume caustic's
// bricks are read where causticSub > 1 (view_caustic.cl).
//
// Glass bodies (REFRACTA_DIELECTRIC; `bodies`, refracta_surfaces.cl): a leg refracted into the
// inside of a dielectric surface that has an inside medium is in that body until it is refracted
// out (reflected legs stay where they are); primary rays start in none (a camera inside glass
// sees the grid's medium until its first interface). Inside a body the medium is the body's
// homogeneous one, not the grid's trilinear samples (which blend the materials of the voxels the
// surface cuts, Physics.md "Glass bodies"): sigma_t is the body's extinction, the emission its
// emission, and the in-scattered light (S1, S_ms from the lighting volume) counts only in the
// channels where the body scatters (sigma_t albedo > 0): clear glass adds none.
//
// Surfaces (-DREFRACTA_HAS_SURFACES): the surface set's BVH (nodes, nodeCount, triangles) and atlas
// (triInfo, surfaceAlbedo, surfaceIrradiance) in the surface frame (view_surfaces.cl). Surfaces
// may lie inside, behind, under or around the medium's box, so the whole path is tested: a
// straight ray asks once for its closest hit from the camera and marches the medium up to it (the
// hit is its depth limit); a curved ray tests the straight run from the camera to the box, every
// step's chord, every skipped run, and the straight ray from its exit point. A ray that meets a
// surface stops there and adds T L_s / n^2 (L_s = E rho / pi, view_surfaces.cl; n the index at the
// hit, 1 outside the box); its pixel is opaque (alpha 1, transmittance 0) and surfaceDepth[pixel]
// is the path length from the ray's origin to the hit (INFINITY when the ray meets none), in the
// grid-local units of the depth limit.
//
// Empty-space skipping (-DREFRACTA_SKIP): `occupancy` holds one byte per macro cell of
// cellDims.w^3 voxels (cellDims.xyz cells; cell c covers continuous voxel coordinates
// [c B - 1/2, (c + 1) B - 1/2) per axis, clipped to the box). Bit 0 is set where a trilinear sample
// of extinction, emission, Radiance or MultipleScattering can be nonzero, bit 1 where a sample of
// grad n can be nonzero; the host dilates each cell by 2 voxels (one for the trilinear footprint,
// one of slack for rounding), so every sample point within one voxel of an empty cell reads zeros.
// `skipMask` selects the bits that matter (1 for straight rays, 3 for curved ones). At a step's
// start the ray measures the straight run of empty cells ahead (a 3D DDA, cell by cell) and jumps
// over the whole steps that lie inside it: such a step would add exactly 0 to L and multiply T by
// exactly 1, and (curved rays) bend nothing, since grad n = 0 there. The step grid is kept (a
// straight ray's steps stay at t0 + s STEP), so the image equals the one without skipping up to
// float rounding of positions; the depth limit, the box exit and the MaxSteps cap are handled by
// the ordinary steps, as without skipping. Skipped steps are not counted in `steps`.

#ifndef REFRACTA_INV_4PI
#define REFRACTA_INV_4PI 0.0795774715459476679f
#endif

// Trilinear samples with a stencil computed once per step and shared by every field (the medium
// and lighting arrays live on the same grid): refracta_make_stencil from refracta_common.cl.
typedef struct
{
  size_t c[8];
  float fx, fy, fz;
} refracta_view_stencil;

// The stencil whose first corner is voxel `base`, the next corners along x, y, z `dx`, `dy`, `dz`
// further (0 on a clamped edge), with weights fx, fy, fz.
inline refracta_view_stencil refracta_view_stencil_at(
  size_t base, size_t dx, size_t dy, size_t dz, float fx, float fy, float fz)
{
  refracta_view_stencil v;
  v.c[0] = base;
  v.c[1] = base + dx;
  v.c[2] = base + dy;
  v.c[3] = base + dx + dy;
  v.c[4] = base + dz;
  v.c[5] = base + dx + dz;
  v.c[6] = base + dy + dz;
  v.c[7] = base + dx + dy + dz;
  v.fx = fx;
  v.fy = fy;
  v.fz = fz;
  return v;
}

inline refracta_view_stencil refracta_view_make_stencil(int4 dims, float3 u)
{
  const refracta_stencil s = refracta_make_stencil(dims, u);
  // One 64-bit index and three offsets (0 on a clamped edge) instead of eight index products.
  return refracta_view_stencil_at(refracta_voxel_index(dims, s.i0, s.j0, s.k0),
    (size_t)(s.i1 - s.i0), (size_t)(s.j1 - s.j0) * (size_t)dims.x,
    (size_t)(s.k1 - s.k0) * (size_t)dims.x * (size_t)dims.y, s.fx, s.fy, s.fz);
}

inline float refracta_view_sample1(__global const float* f, const refracta_view_stencil* s)
{
  const float c00 = mix(f[s->c[0]], f[s->c[1]], s->fx);
  const float c10 = mix(f[s->c[2]], f[s->c[3]], s->fx);
  const float c01 = mix(f[s->c[4]], f[s->c[5]], s->fx);
  const float c11 = mix(f[s->c[6]], f[s->c[7]], s->fx);
  return mix(mix(c00, c10, s->fy), mix(c01, c11, s->fy), s->fz);
}

inline float4 refracta_view_sample4(__global const float* f, const refracta_view_stencil* s)
{
  const float4 c00 = mix(vload4(s->c[0], f), vload4(s->c[1], f), s->fx);
  const float4 c10 = mix(vload4(s->c[2], f), vload4(s->c[3], f), s->fx);
  const float4 c01 = mix(vload4(s->c[4], f), vload4(s->c[5], f), s->fx);
  const float4 c11 = mix(vload4(s->c[6], f), vload4(s->c[7], f), s->fx);
  return mix(mix(c00, c10, s->fy), mix(c01, c11, s->fy), s->fz);
}

inline float3 refracta_view_sample3(__global const float* f, const refracta_view_stencil* s)
{
  const float3 c00 = mix(vload3(s->c[0], f), vload3(s->c[1], f), s->fx);
  const float3 c10 = mix(vload3(s->c[2], f), vload3(s->c[3], f), s->fx);
  const float3 c01 = mix(vload3(s->c[4], f), vload3(s->c[5], f), s->fx);
  const float3 c11 = mix(vload3(s->c[6], f), vload3(s->c[7], f), s->fx);
  return mix(mix(c00, c10, s->fy), mix(c01, c11, s->fy), s->fz);
}

// One channel of a step's exact integration: w = (1 - exp(-tau)) / tau and the step's
// transmittance exp(-tau) = 1 - tau w. For tau <= 1/2 (almost every step of a view ray) w is its
// Taylor series sum_k (-tau)^k / (k + 1)!, k <= 9 (truncation below 3e-11 relative), evaluated by
// Estrin's scheme (four multiply-adds deep): on a CPU expm1 and exp cost most of a step. Thicker
// steps call them (exp keeps the relative accuracy of a tiny transmittance).
__attribute__((noinline)) float refracta_step_weight_thick(float tau, float* stepTransmittance)
{
  *stepTransmittance = exp(-tau);
  return -expm1(-tau) / tau;
}

// The series for t = -tau of type TYPE (float, or float8 in view_lanes.cl): declares w.
#define REFRACTA_STEP_WEIGHT_SERIES(TYPE, t, w)                                                   \
  const TYPE t2_ = t * t;                                                                          \
  const TYPE t4_ = t2_ * t2_;                                                                      \
  const TYPE a0_ = fma(t, (TYPE)(1.0f / 2.0f), (TYPE)(1.0f));                                      \
  const TYPE a1_ = fma(t, (TYPE)(1.0f / 24.0f), (TYPE)(1.0f / 6.0f));                              \
  const TYPE a2_ = fma(t, (TYPE)(1.0f / 720.0f), (TYPE)(1.0f / 120.0f));                           \
  const TYPE a3_ = fma(t, (TYPE)(1.0f / 40320.0f), (TYPE)(1.0f / 5040.0f));                        \
  const TYPE a4_ = fma(t, (TYPE)(1.0f / 3628800.0f), (TYPE)(1.0f / 362880.0f));                    \
  TYPE w = fma(t4_ * t4_, a4_, fma(t4_, fma(t2_, a3_, a2_), fma(t2_, a1_, a0_)))

__attribute__((always_inline)) inline float refracta_step_weight(
  float tau, float* stepTransmittance)
{
  if (tau > 0.5f)
  {
    return refracta_step_weight_thick(tau, stepTransmittance);
  }
  const float t = -tau;
  REFRACTA_STEP_WEIGHT_SERIES(float, t, w);
  *stepTransmittance = fma(t, w, 1.0f);
  return w;
}

// A step of length len through a medium constant over it (extinction sigma, source q per unit
// length): L += T q (1 - exp(-tau)) / sigma, T *= exp(-tau), tau = sigma len, per channel; a grey
// extinction (the same in every channel, e.g. any vtkVolumeProperty's scalar opacity) is
// integrated once for all three.
__attribute__((always_inline)) inline void refracta_integrate_step(
  float3 sigma, float3 q, float len, float3* radianceSum, float3* transmittance)
{
  float3 w, stepT;
  if (sigma.x == sigma.y && sigma.y == sigma.z)
  {
    float t;
    w = (float3)(refracta_step_weight(sigma.x * len, &t));
    stepT = (float3)(t);
  }
  else
  {
    float tx, ty, tz; // (no address of a vector component in OpenCL C)
    w = (float3)(refracta_step_weight(sigma.x * len, &tx),
      refracta_step_weight(sigma.y * len, &ty), refracta_step_weight(sigma.z * len, &tz));
    stepT = (float3)(tx, ty, tz);
  }
  *radianceSum += *transmittance * q * (len * w);
  *transmittance *= stepT;
}

// Background radiance seen in grid-local direction d. The environment image (RGB floats, row 0 at
// the bottom) is equirectangular in the basis (right, up, front = up x right) of
// vtkRefractaEnvironmentMap (VTK's skybox convention), given here in grid-local coordinates:
// x = d.right, y = d.up, z = d.front, u = atan2(x, z) / (2 pi) + 1/2 (wrapped into [0, 1)),
// v = atan2(y, |(x, z)|) / pi + 1/2. The host's vtkRefractaEnvironmentMap::DirectionToTexture
// computes the same mapping.
inline float3 refracta_background(float3 d, float4 background, __global const float* environment,
  int2 envSize, float4 envRight, float4 envUp, float4 envFront)
{
#ifdef REFRACTA_HAS_ENVIRONMENT
  const float x = dot(d, envRight.xyz);
  const float y = dot(d, envUp.xyz);
  const float z = dot(d, envFront.xyz);
  float u = atan2(x, z) * (0.5f / REFRACTA_PI) + 0.5f;
  u = u >= 1.0f ? u - 1.0f : u;
  const float v = atan2(y, sqrt(x * x + z * z)) * (1.0f / REFRACTA_PI) + 0.5f;
#ifdef REFRACTA_CHECKER_ENVIRONMENT
  // Procedural checkerboard (vtkRefractaEnvironmentMap::EvaluateChecker): envSize holds the
  // squares (nu, nv), `environment` colour 1 (odd squares) then colour 2; sharp at any size.
  const int su = clamp((int)floor(u * (float)envSize.x), 0, envSize.x - 1);
  const int sv = clamp((int)floor(v * (float)envSize.y), 0, envSize.y - 1);
  return vload3(((su + sv) & 1) ? 0 : 1, environment);
#endif
  // Bilinear between texel centres; wraps in u (longitude), clamps in v (latitude).
  const float px = u * (float)envSize.x - 0.5f;
  const float py = clamp(v * (float)envSize.y - 0.5f, 0.0f, (float)(envSize.y - 1));
  const float fx0 = floor(px);
  const float fy0 = floor(py);
  const float ax = px - fx0;
  const float ay = py - fy0;
  int i0 = (int)fx0 % envSize.x;
  if (i0 < 0)
  {
    i0 += envSize.x;
  }
  const int i1 = (i0 + 1) % envSize.x;
  const int j0 = (int)fy0;
  const int j1 = min(j0 + 1, envSize.y - 1);
  const float3 c00 = vload3(i0 + envSize.x * j0, environment);
  const float3 c10 = vload3(i1 + envSize.x * j0, environment);
  const float3 c01 = vload3(i0 + envSize.x * j1, environment);
  const float3 c11 = vload3(i1 + envSize.x * j1, environment);
  return mix(mix(c00, c10, ax), mix(c01, c11, ax), ay);
#else
  return background.xyz;
#endif
}

#ifdef REFRACTA_DIELECTRIC
// The medium of glass body `body` (>= 0) at a step: its extinction, and the source q of the grid
// kept only in its scattering channels plus its own emission (see the file comment). `gridEmission`
// is the part of q that is the grid's emission.
inline float3 refracta_view_body_medium(
  __global const float4* bodies, int body, float3 q, float3 gridEmission, float3* sigma)
{
  const float4 ext = bodies[3 * body];
  const float4 alb = bodies[3 * body + 1];
  *sigma = ext.xyz;
  const float3 scatters =
    select((float3)(0.0f), (float3)(1.0f), isgreater(ext.xyz * alb.xyz, (float3)(0.0f)));
  return (q - gridEmission) * scatters + bodies[3 * body + 2].xyz;
}
#endif

// The arguments of a sided lookup: the voxels near opaque triangles (bit REFRACTA_CUT_NEAR of
// cutLinks, vtkRefractaGridCuts), the surfaces and the grid-local -> surface frame rows.
#define REFRACTA_VIEW_SIDE_PARAMS                                                                 \
  __global const uchar *cutLinks, __global const float4 *nodes, const int nodeCount,              \
    __global const float4 *triangles, __global const int *triInfo, const float4 toSurface0,      \
    const float4 toSurface1, const float4 toSurface2
#define REFRACTA_VIEW_SIDE_ARGS                                                                   \
  cutLinks, nodes, nodeCount, triangles, triInfo, toSurface0, toSurface1, toSurface2

#ifdef REFRACTA_SIDED_LOOKUPS
// Sided lookups of light (where opaque surfaces cut the grid): the trilinear weights of the
// stencil's eight corners (corner k at offset (k & 1, k >> 1 & 1, k >> 2 & 1), the order of
// refracta_view_stencil_at) with the corners near an opaque triangle that one separates from the
// sample at voxel coordinates u (refracta_opaque_between, from u itself: a sample in the grid's
// outer half voxel is not clamped first) left out and the others renormalised, so that a sample
// reads only light from its own side of a wall, whatever the wall's shape (none where every
// corner is across). False, w untouched, where no corner is near an opaque triangle: the plain
// trilinear sample applies.
inline bool refracta_view_sided_weights(const refracta_view_stencil* st, int4 dims,
  float4 spacing, float3 u, REFRACTA_VIEW_SIDE_PARAMS, float* w)
{
  bool near = false;
  #pragma unroll
  for (int k = 0; k < 8; ++k)
  {
    near = near || (cutLinks[st->c[k]] & REFRACTA_CUT_NEAR);
  }
  if (!near)
  {
    return false;
  }
  const float3 hi = (float3)((float)(dims.x - 1), (float)(dims.y - 1), (float)(dims.z - 1));
  const float3 lo = floor(clamp(u, (float3)(0.0f), hi));
  const float3 up = fmin(lo + 1.0f, hi);
  const float3 x = u * spacing.xyz;
  float sum = 0.0f;
  for (int k = 0; k < 8; ++k)
  {
    const float3 corner =
      (float3)((k & 1) ? up.x : lo.x, (k & 2) ? up.y : lo.y, (k & 4) ? up.z : lo.z);
    const float wk = ((k & 1) ? st->fx : 1.0f - st->fx) * ((k & 2) ? st->fy : 1.0f - st->fy) *
      ((k & 4) ? st->fz : 1.0f - st->fz);
    const bool across = wk > 0.0f && (cutLinks[st->c[k]] & REFRACTA_CUT_NEAR) &&
      refracta_opaque_between(nodes, nodeCount, triangles, triInfo, toSurface0, toSurface1,
        toSurface2, x, corner * spacing.xyz);
    w[k] = across ? 0.0f : wk;
    sum += w[k];
  }
  const float scale = sum > 0.0f ? 1.0f / sum : 0.0f;
  #pragma unroll
  for (int k = 0; k < 8; ++k)
  {
    w[k] *= scale;
  }
  return true;
}

inline float3 refracta_view_weighted3(
  __global const float* f, const refracta_view_stencil* st, const float* w)
{
  float3 sum = (float3)(0.0f);
  #pragma unroll
  for (int k = 0; k < 8; ++k)
  {
    sum += w[k] * vload3(st->c[k], f);
  }
  return sum;
}
// A light field at the step: sided where a corner of the sample is near an opaque triangle.
#define REFRACTA_VIEW_LIGHT3(f)                                                                   \
  (sided ? refracta_view_weighted3((f), st, sidedWeights) : refracta_view_sample3((f), st))
#else
#define REFRACTA_VIEW_LIGHT3(f) refracta_view_sample3((f), st)
#endif

// Scattered source term Q of a step (midpoint at voxel coordinates u, the step `du` in voxel
// units) for a ray travelling in unit direction d: the voxel fields at the midpoint; the volume
// caustic, c times finer, as the mean of c points evenly spread over the step (one midpoint per
// fine voxel crossed, where a single midpoint would alias the focused light into streaks). The
// grid's emission is added by the caller (refracta_view_march).
inline float3 refracta_view_source(const refracta_view_stencil* st, float3 u, float3 du, float3 d,
  int4 dims, __global const float* anisotropy, __global const float* radiance,
  __global const float* radianceDirection, __global const float* multiple,
  __global const int* causticBricks, __global const float* causticRadiance,
  __global const float* causticDirection, int causticSub, float4 spacing,
  REFRACTA_VIEW_SIDE_PARAMS)
{
  float3 q = (float3)(0.0f);
#ifdef REFRACTA_SIDED_LOOKUPS
  float sidedWeights[8];
  const bool sided =
    refracta_view_sided_weights(st, dims, spacing, u, REFRACTA_VIEW_SIDE_ARGS, sidedWeights);
#endif
#if defined(REFRACTA_HAS_SINGLE) || defined(REFRACTA_MULTIPLE_DIRECTION)
  const float g = refracta_view_sample1(anisotropy, st);
#endif
#ifdef REFRACTA_HAS_SINGLE
#ifdef REFRACTA_RADIANCE_LOBES
  // S1 in lobes (the lights grouped by direction), each shaded about its own mean direction:
  // light from two sides is not shaded along the mean between them. `radiance` holds per voxel
  // each lobe's S1 and direction (6 floats a lobe), read with one set of corner weights.
  float w[8];
#ifdef REFRACTA_SIDED_LOOKUPS
  if (sided)
  {
    for (int k = 0; k < 8; ++k)
    {
      w[k] = sidedWeights[k];
    }
  }
  else
#endif
  {
    for (int k = 0; k < 8; ++k)
    {
      w[k] = ((k & 1) ? st->fx : 1.0f - st->fx) * ((k & 2) ? st->fy : 1.0f - st->fy) *
        ((k & 4) ? st->fz : 1.0f - st->fz);
    }
  }
  for (int lobe = 0; lobe < REFRACTA_RADIANCE_LOBES; ++lobe)
  {
    float3 s1 = (float3)(0.0f), mean = (float3)(0.0f);
    for (int k = 0; k < 8; ++k)
    {
      __global const float* at = radiance + 6 * (st->c[k] * REFRACTA_RADIANCE_LOBES + lobe);
      s1 += w[k] * vload3(0, at);
      mean += w[k] * vload3(1, at);
    }
    if (s1.x + s1.y + s1.z > 0.0f)
    {
      q += refracta_view_single(s1, mean, d, g); // w_o = -d (towards the camera)
    }
  }
#else
  const float3 s1 = REFRACTA_VIEW_LIGHT3(radiance);
  if (s1.x + s1.y + s1.z > 0.0f)
  {
    // w_o = -d (towards the camera).
    q += refracta_view_single(s1, REFRACTA_VIEW_LIGHT3(radianceDirection), d, g);
  }
#endif
  if (causticSub > 1) // a run-time choice: no kernel variant of its own
  {
    float3 focused = (float3)(0.0f);
    for (int k = 0; k < causticSub; ++k)
    {
      const float3 uk = u + (((float)k + 0.5f) / (float)causticSub - 0.5f) * du;
      focused += refracta_view_volume_caustic(
        dims, uk, d, g, causticBricks, causticRadiance, causticDirection, causticSub);
    }
    q += focused / (float)causticSub;
  }
#endif
#ifdef REFRACTA_HAS_MULTIPLE
#ifdef REFRACTA_MULTIPLE_DIRECTION
  // The multiply scattered light's flux over its fluence F / phi (length f, stored after S_ms in
  // the same buffer): the light taken as spread about F as a Henyey-Greenstein lobe of mean
  // cosine f, which the medium's p_HG(g) scatters into exactly p_HG(g f) about F (the family is
  // closed under convolution about one axis); exact for a collimated and an isotropic field.
  const float3 ms = REFRACTA_VIEW_LIGHT3(multiple);
  const float3 flux =
    REFRACTA_VIEW_LIGHT3(multiple + 3 * ((size_t)dims.x * (size_t)dims.y * (size_t)dims.z));
  const float f = fmin(length(flux), 1.0f);
  q += refracta_view_single(ms, flux, d, f * g);
#else
  q += REFRACTA_INV_4PI * REFRACTA_VIEW_LIGHT3(multiple);
#endif
#endif
  return q;
}
#undef REFRACTA_VIEW_LIGHT3

// The grid's fields a step reads (refracta_view_step_medium's arguments).
#define REFRACTA_VIEW_MEDIUM_PARAMS                                                               \
  int4 dims, __global const float *extinction, __global const float *emission,                   \
    __global const float *anisotropy, __global const float *radiance,                            \
    __global const float *radianceDirection, __global const float *multiple,                     \
    __global const int *causticBricks, __global const float *causticRadiance,                    \
    __global const float *causticDirection, int causticSub, float4 spacing,                     \
    REFRACTA_VIEW_SIDE_PARAMS
#define REFRACTA_VIEW_MEDIUM_ARGS                                                                 \
  dims, extinction, emission, anisotropy, radiance, radianceDirection, multiple, causticBricks,  \
    causticRadiance, causticDirection, causticSub, spacing, REFRACTA_VIEW_SIDE_ARGS

// The grid's medium at a step's midpoint (stencil st at voxel coordinates u; du the step in voxel
// units, d the ray's unit direction): its extinction *sigma and emission *gridEmission, and the
// step's source q = emission + scattered light (refracta_view_source) as the return value. The
// extinction and emission come from one float4 gather of the packed (sigma, emission) layout of
// an emitting grey medium, else one per field. Shared by refracta_view_march and the lane kernel
// (view_lanes.cl).
inline float3 refracta_view_step_medium(const refracta_view_stencil* st, float3 u, float3 du,
  float3 d, REFRACTA_VIEW_MEDIUM_PARAMS, float3* sigma, float3* gridEmission)
{
#ifdef REFRACTA_PACKED_MEDIUM
  const float4 packed = refracta_view_sample4(extinction, st);
  *sigma = (float3)(packed.x);
  *gridEmission = packed.yzw;
#else
  *sigma = refracta_view_sample3(extinction, st);
#ifdef REFRACTA_HAS_EMISSION
  *gridEmission = refracta_view_sample3(emission, st);
#else
  *gridEmission = (float3)(0.0f);
#endif
#endif
  return *gridEmission +
    refracta_view_source(st, u, du, d, dims, anisotropy, radiance, radianceDirection, multiple,
      causticBricks, causticRadiance, causticDirection, causticSub, spacing,
      REFRACTA_VIEW_SIDE_ARGS);
}

// What a source counts at a step: sources are physical radiance per length; what reaches the
// camera (in n = 1) is the basic radiance L / n^2, conserved along the ray, so a source at index
// n counts 1 / n^2 (n sampled at the stencil where it varies, a constant where it is uniform).
inline float refracta_view_source_weight(
  const refracta_view_stencil* st, __global const float* refractiveIndex)
{
#ifdef REFRACTA_INDEX_WEIGHT
  const float nMid = refracta_view_sample1(refractiveIndex, st);
  return 1.0f / (nMid * nMid);
#elif defined(REFRACTA_SOURCE_SCALE)
  return REFRACTA_SOURCE_SCALE;
#else
  return 1.0f;
#endif
}

// The surfaces' arguments, passed on to the helpers below.
#ifdef REFRACTA_HAS_SURFACES
#define REFRACTA_VIEW_SURFACES nodes, nodeCount, triangles, toSurface0, toSurface1, toSurface2
#endif
#define REFRACTA_VIEW_LEG_PARAMS                                                                  \
  const int4 dims, const float4 spacing, __global const float *extinction,                       \
    __global const float *emission, __global const float *anisotropy,                            \
    __global const float *refractiveIndex, __global const float *gradient,                       \
    __global const float *radiance, __global const float *radianceDirection,                     \
    __global const float *multiple, const float stepLength, const int maxSteps,                  \
    const float cutoff, __global const uchar *occupancy, const int4 cellDims,                    \
    const int4 activeLo, const int4 activeHi, const uint skipMask,                               \
    __global const float4 *nodes, const int nodeCount, __global const float4 *triangles,         \
    const float4 toSurface0, const float4 toSurface1, const float4 toSurface2,                   \
    __global const float4 *bodies, __global const int *causticBricks,                             \
    __global const float *causticRadiance, __global const float *causticDirection,               \
    const int causticSub, __global const uchar *cutLinks, __global const int *triInfo
#define REFRACTA_VIEW_LEG_ARGS                                                                    \
  dims, spacing, extinction, emission, anisotropy, refractiveIndex, gradient, radiance,          \
    radianceDirection, multiple, stepLength, maxSteps, cutoff, occupancy, cellDims, activeLo,    \
    activeHi, skipMask, nodes, nodeCount, triangles, toSurface0, toSurface1, toSurface2, bodies, \
    causticBricks, causticRadiance, causticDirection, causticSub, cutLinks, triInfo

// One leg of a view path: from `origin` in unit direction d (grid-local) until the ray meets a
// surface, leaves the box (then it sees the background, or a surface outside the box), reaches
// `limit`, falls below the cutoff or runs out of steps. The primary ray is one leg; at a
// dielectric surface the kernel starts new legs on both sides (below).
typedef struct
{
  float3 radiance;      // basic radiance gathered along the leg (sources, not the end)
  float3 transmittance; // along the leg
  float3 d;             // the direction at the end (at a surface hit: the incident direction)
  float3 surfacePoint;  // the hit, grid-local
  float surfaceU, surfaceV, surfaceDepth; // the hit's barycentrics, path length to it
  int surfaceTri;                         // the triangle met (BVH order) or -1
  uint count;                             // steps marched
  bool seesBackground;                    // left the box (or missed it) into the background
  bool stoppedEarly;                      // the cutoff or the step cap ended it
} refracta_view_leg;

inline refracta_view_leg refracta_view_march(
  REFRACTA_VIEW_LEG_PARAMS, const float3 origin, float3 d, float limit, const int body)
{
#ifdef REFRACTA_HAS_SURFACES
  // The surface the ray meets (-1: none yet), where, and the path length to it.
  int surfaceTri = -1;
  float surfaceU = 0.0f, surfaceV = 0.0f, surfaceDepth = INFINITY;
  float3 surfacePoint = origin;
  float th, uh, vh; // a query's hit
#ifndef REFRACTA_CURVED
  // Straight rays: the closest hit along the whole ray ends the path (a depth limit).
  surfaceTri = refracta_view_surface_hit(REFRACTA_VIEW_SURFACES, origin, d, limit, &th, &uh, &vh);
  if (surfaceTri >= 0)
  {
    surfaceU = uh;
    surfaceV = vh;
    surfaceDepth = limit = th;
    surfacePoint = origin + th * d;
  }
#endif
#endif

  bool stoppedEarly = false; // the cutoff or the step cap ended the ray before its end
  float3 lo, hi;
  refracta_domain(dims, spacing, &lo, &hi);
  float3 radianceSum = (float3)(0.0f);
  float3 transmittance = (float3)(1.0f);
  uint count = 0;
  bool seesBackground = true; // false when stopped by geometry, the cutoff or the step cap
  float t0, t1;
  const bool meetsBox = refracta_intersect_box(origin, d, lo, hi, &t0, &t1);
#if defined(REFRACTA_HAS_SURFACES) && defined(REFRACTA_CURVED)
  // Curved rays are straight until they enter the box: a surface on the way ends them there.
  surfaceTri = refracta_view_surface_hit(
    REFRACTA_VIEW_SURFACES, origin, d, meetsBox ? fmin(t0, limit) : limit, &th, &uh, &vh);
  if (surfaceTri >= 0)
  {
    surfaceU = uh;
    surfaceV = vh;
    surfaceDepth = limit = th;
    surfacePoint = origin + th * d;
  }
#endif
  if (meetsBox && t0 < limit)
  {
    float travelled = t0;
    float3 x = origin + t0 * d;
#ifdef REFRACTA_CURVED
    float n = refracta_sample1(refractiveIndex, dims, refracta_to_voxel(x, spacing));
    float3 v = n * d;
#else
    // Straight rays step in voxel coordinates: no division per step.
    const float3 uEntry = refracta_to_voxel(x, spacing);
    const float3 dVoxel = refracta_to_voxel(d, spacing);
#endif
#ifdef REFRACTA_SKIP
    const float3 cellExtent = (float)cellDims.w * spacing.xyz;
    float nextCheck = travelled; // no skip test before this path length (inside an occupied cell)
#endif
    for (int s = 0; s < maxSteps; ++s)
    {
#ifdef REFRACTA_SKIP
      if (travelled >= nextCheck)
      {
#ifdef REFRACTA_CURVED
        const float3 xs = x;
        const float3 ds = normalize(v);
        float b0, b1;
        const float toExit =
          refracta_intersect_box(xs, ds, lo, hi, &b0, &b1) ? fmax(b1, 0.0f) : 0.0f;
#else
        const float3 ds = d;
        const float tS = t0 + (float)s * stepLength;
        const float3 xs = origin + tS * d;
        const float toExit = fmax(t1 - tS, 0.0f);
#endif
        float recheck;
        float run = refracta_empty_run(xs, ds, lo, hi, cellExtent, cellDims, activeLo, activeHi,
          occupancy, skipMask, &recheck);
        nextCheck = travelled + recheck;
        // Only whole steps that end before the box exit and the depth limit are skipped: the
        // step that meets either is marched as without skipping.
        run = fmin(run, fmin(toExit, limit - travelled));
        int k = min((int)floor(run / stepLength), maxSteps - 1 - s);
#if defined(REFRACTA_HAS_SURFACES) && defined(REFRACTA_CURVED)
        // Never jump over a surface: stop short of it, the ordinary step meets it.
        if (k > 0 &&
          refracta_view_surface_hit(REFRACTA_VIEW_SURFACES, xs, ds, (float)k * stepLength, &th,
            &uh, &vh) >= 0)
        {
          k = (int)floor(th / stepLength);
        }
#endif
        if (k > 0)
        {
          s += k;
          travelled += (float)k * stepLength;
#ifdef REFRACTA_CURVED
          // Straight through the empty run (grad n = 0 there); n is re-read where the ray lands.
          x = xs + ((float)k * stepLength) * ds;
          n = refracta_sample1(refractiveIndex, dims, refracta_to_voxel(x, spacing));
          v = n * ds;
#endif
        }
      }
#endif
      bool leaves = false;
      float len;
      float3 chord; // unit direction of this step's chord
#ifdef REFRACTA_CURVED
      // Stormer-Verlet in the optical parameter t, dt = ds / n.
      const float dt = stepLength / n;
      const float3 accel = n * refracta_sample3(gradient, dims, refracta_to_voxel(x, spacing));
      const float3 vHalf = v + 0.5f * dt * accel;
      const float3 xNext = x + dt * vHalf;
      const float nNext = refracta_sample1(refractiveIndex, dims, refracta_to_voxel(xNext, spacing));
      const float3 accelNext =
        nNext * refracta_sample3(gradient, dims, refracta_to_voxel(xNext, spacing));
      float3 vNext = vHalf + 0.5f * dt * accelNext;
      const float speed = length(vNext);
      vNext = speed > 0.0f ? vNext * (nNext / speed) : nNext * d;
      const float3 step = xNext - x;
      len = length(step);
      chord = len > 0.0f ? step / len : d;
      // Clip the chord to the box: the exit point is where the ray leaves the medium.
      float e0, e1;
      if (any(xNext < lo) || any(xNext > hi))
      {
        leaves = true;
        if (refracta_intersect_box(x, chord, lo, hi, &e0, &e1))
        {
          len = clamp(e1, 0.0f, len);
        }
        else
        {
          len = 0.0f;
        }
      }
#else
      // Straight: exact positions from the entry parameter, no drift over many steps.
      const float tA = t0 + (float)s * stepLength;
      const float tB = fmin(tA + stepLength, t1);
      leaves = tB >= t1;
      len = fmax(tB - tA, 0.0f);
      chord = d;
#endif
      bool blocked = false;
      if (travelled + len >= limit)
      {
        len = fmax(limit - travelled, 0.0f);
        blocked = true;
      }
#if defined(REFRACTA_HAS_SURFACES) && defined(REFRACTA_CURVED)
      // This step's chord against the surfaces; a hit ends the ray there.
      if (len > 0.0f)
      {
        surfaceTri =
          refracta_view_surface_hit(REFRACTA_VIEW_SURFACES, x, len * chord, 1.0f, &th, &uh, &vh);
      }
      if (surfaceTri >= 0)
      {
        surfaceU = uh;
        surfaceV = vh;
        len *= th;
        surfaceDepth = travelled + len;
        surfacePoint = x + len * chord;
        d = chord; // the direction in which the ray meets the surface
        blocked = true;
      }
#endif
#ifdef REFRACTA_CURVED
      const float3 u = refracta_to_voxel(x + (0.5f * len) * chord, spacing);
#else
      const float3 u = uEntry + ((float)s * stepLength + 0.5f * len) * dVoxel;
#endif
      const refracta_view_stencil st = refracta_view_make_stencil(dims, u);
      float3 sigma, gridEmission;
      float3 q = refracta_view_step_medium(&st, u, refracta_to_voxel(len * chord, spacing), chord,
        REFRACTA_VIEW_MEDIUM_ARGS, &sigma, &gridEmission);
#ifdef REFRACTA_DIELECTRIC
      if (body >= 0)
      {
        q = refracta_view_body_medium(bodies, body, q, gridEmission, &sigma);
      }
#endif
      q *= refracta_view_source_weight(&st, refractiveIndex);
      refracta_integrate_step(sigma, q, len, &radianceSum, &transmittance);
      travelled += len;
      ++count;
      if (blocked)
      {
        seesBackground = false;
        break;
      }
      if (leaves)
      {
#ifdef REFRACTA_CURVED
        d = normalize(vNext);
#if defined(REFRACTA_HAS_SURFACES)
        // Straight again outside the box: a surface there is seen instead of the background.
        const float3 exitPoint = x + len * chord;
        surfaceTri = refracta_view_surface_hit(
          REFRACTA_VIEW_SURFACES, exitPoint, d, limit - travelled, &th, &uh, &vh);
        if (surfaceTri >= 0)
        {
          surfaceU = uh;
          surfaceV = vh;
          surfaceDepth = travelled + th;
          surfacePoint = exitPoint + th * d;
        }
#endif
#endif
        break;
      }
      if (fmax(transmittance.x, fmax(transmittance.y, transmittance.z)) < cutoff)
      {
        seesBackground = false;
        stoppedEarly = true;
        break;
      }
#ifdef REFRACTA_CURVED
      x = xNext;
      v = vNext;
      n = nNext;
#endif
      if (s + 1 == maxSteps)
      {
        seesBackground = false; // trapped (e.g. total internal reflection): no background
        stoppedEarly = true;
      }
    }
  }
  if (limit < INFINITY)
  {
    // Opaque geometry ends the ray, before the medium or after it left the box: it shows there
    // (the compositing's T pixel_before), the background does not.
    seesBackground = false;
  }
  refracta_view_leg leg;
  leg.radiance = radianceSum;
  leg.transmittance = transmittance;
  leg.d = d;
  leg.count = count;
  leg.seesBackground = seesBackground;
  leg.stoppedEarly = stoppedEarly;
#ifdef REFRACTA_HAS_SURFACES
  leg.surfaceTri = surfaceTri;
  leg.surfaceU = surfaceU;
  leg.surfaceV = surfaceV;
  leg.surfaceDepth = surfaceDepth;
  leg.surfacePoint = surfacePoint;
#else
  leg.surfaceTri = -1;
  leg.surfaceU = leg.surfaceV = 0.0f;
  leg.surfaceDepth = INFINITY;
  leg.surfacePoint = origin;
#endif
  return leg;
}

