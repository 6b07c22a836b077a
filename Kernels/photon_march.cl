// photon_march.cl: the photon marching kernels (photon_march: each photon to its end in one
// launch; photon_march_chunk: resumable, a bounded number of steps per launch). Prepend
// photon_trace.cl and photon_surfaces.cl; see photon_trace.cl's header for the march itself.
// Both take the volume caustic's brick map, fine accumulators and subdivision last (used with
// REFRACTA_INTERFACES only; photon_deposit_volume_caustic).

// A new photon of emitted power `power`: its roulette threshold, zero tallies, its random stream
// (`id`: the photon's stream, photonStream[slot], so the stream depends neither on launches or
// chunks nor on the slot the photon is marched in) and the analog-scattering
// state; its body is found once the surfaces are set. Returns false, counting the photon as
// missed, when it carries no power.
inline bool photon_start(photon_state* ps, const float3 power, const uint seed, const uint id,
  __global const float* anisotropy, volatile __global long* multiple,
  volatile __global long* counters)
{
  ps->power = power;
  const float p0 = fmax(power.x, fmax(power.y, power.z));
  if (!(p0 > 0.0f))
  {
    atom_add(counters + PHOTON_COUNTER_MISSED, 1L);
    return false;
  }
  ps->threshold = REFRACTA_ROULETTE * p0;
  ps->absorbed = ps->scattered = ps->killed = ps->gained = (float3)(0.0f);
  ps->surface = (float3)(0.0f);
  ps->rng = refracta_rng_seed(seed, id);
  ps->pieces = 0;
  ps->hits = 0;
  ps->interfaces = 0;
  ps->caustic = 0;
  ps->dead = 0;
  photon_init_analog(ps, anisotropy, multiple, 0);
  ps->body = -1;
  return true;
}

__kernel void photon_march(__global const float4* photonPos, __global const float4* photonDir,
  __global const float4* photonPower, __global const uint* photonStream, const uint count,
  __global const float* refractiveIndex, __global const float* gradient,
  __global const float* extinction, __global const float* albedo,
  __global const uchar* octree, const int4 dims, const float4 spacing,
  volatile __global long* deposits,
  volatile __global long* tallies, volatile __global long* counters, const uint seed,
  const uint first, __global const float4* surfaceNodes, const int surfaceNodeCount,
  __global const float4* surfaceTriangles, __global const int4* surfaceInfo,
  __global const float* surfaceAlbedo, volatile __global long* surfaceIrradiance,
  const float4 frame0, const float4 frame1, const float4 frame2, const float surfaceEpsilon,
  const long causticOffset,
  __global const float* anisotropy, volatile __global long* multiple,
  __global const float4* surfaceNormals, __global const float2* surfaceInterfaces,
  __global const float4* surfaceBodies, __global const uchar* cutLinks,
  __global const int* volumeCausticBricks,
  volatile __global long* volumeCausticFine, const int volumeCausticSubdivision)
{
  // Launched in chunks (for progress reports); the stream depends on the photon, not the chunk.
  const uint id = first + (uint)get_global_id(0);
  if (id >= count)
  {
    return;
  }
  photon_state ps;
  if (!photon_start(
        &ps, photonPower[id].xyz, seed, photonStream[id], anisotropy, multiple, counters))
  {
    return;
  }
  ps.lobe = (int)photonPower[id].w;
  ps.bodies = surfaceBodies;
  photon_set_sides(&ps, cutLinks, surfaceNodes, surfaceNodeCount, surfaceTriangles,
    (__global const int*)surfaceInfo, frame0, frame1, frame2, spacing);
  photon_set_volume_caustic(&ps, volumeCausticBricks, volumeCausticFine, volumeCausticSubdivision);
  const float3 emitted = ps.power;
  int steps = 0;
  int outcome = PHOTON_COUNTER_ESCAPED; // counter index: 2 escaped, 3 roulette, 4 step cap, 5 invalid
  float3 lo;
  float3 hi;
  refracta_domain(dims, spacing, &lo, &hi);
  float3 x = photonPos[id].xyz;
  const float3 d0 = normalize(photonDir[id].xyz);

#if REFRACTA_SURFACES
  photon_surfaces surf;
  photon_set_surfaces(&surf, surfaceNodes, surfaceNodeCount, surfaceTriangles, surfaceInfo,
    surfaceAlbedo, surfaceIrradiance, frame0, frame1, frame2, surfaceEpsilon, causticOffset,
    surfaceNormals, surfaceInterfaces, tallies, counters);
#if REFRACTA_INTERFACES
  ps.body = photon_start_body(&surf, &ps, x, d0);
#endif
  float3 v = photon_velocity(x, d0, lo, hi, refractiveIndex, dims, spacing);
  do
  {
    outcome = photon_surface_event(&ps, &x, &v, &steps, lo, hi, octree, extinction, albedo,
      refractiveIndex, gradient, dims, spacing, deposits, &surf);
  } while (outcome < 0);
#elif !REFRACTA_REFRACT
  // Straight ray: a single step from the start to the domain's exit.
  float t0;
  float t1;
  if (refracta_intersect_box(x, d0, lo, hi, &t0, &t1) && t1 > 0.0f)
  {
    steps = 1;
#if REFRACTA_EXTINCTION
    photon_walk(&ps, x + t0 * d0, x + t1 * d0, 1.0f, dims, spacing, extinction, albedo, deposits);
#endif
  }
#else
  float3 v = d0 * refracta_sample1(refractiveIndex, dims, refracta_to_voxel(x, spacing));
  do
  {
    outcome = photon_curved_step(&ps, &x, &v, &steps, lo, hi, octree, extinction, albedo,
      refractiveIndex, gradient, dims, spacing, deposits);
  } while (outcome < 0);
#endif
  if (ps.dead)
  {
    outcome = PHOTON_COUNTER_ROULETTE; // the straight walk's roulette
  }
  photon_finish(tallies, counters, emitted, &ps, outcome, steps);
}

// ---------------------------------------------------------------------------------------------
// photon_march_chunk (added for the interleaved photon/diffusion schedule of Bernabei et al.,
// section III-B): the same marching as photon_march, resumable. Each launch advances every
// photon by at most `chunkSteps` steps (curved rays: marcher steps; straight rays: segments of
// one voxel edge, since a straight ray is otherwise a single step to the exit; with surfaces:
// photon_surface_event's events) and keeps its state in `state` (PHOTON_STATE_FLOAT4S float4 per
// photon: x, v, power + roulette threshold, absorbed, scattered, killed, gained, emitted, surface
// + surface hits) and `status` (status 0 new / 1 marching / 2 done, steps, rng,
// pieces). Deposits go to the same fixed-point accumulators as photon_march (they replace the
// paper's Ray History Buffer and its OpenGL blending: the accumulation is atomic here); a
// finished photon adds its tallies and counters exactly as photon_march does, so a chunked run
// gives the same books and, step for step, the same deposits. `active` counts the photons still
// marching after the launch. One work-item per photon (offset `first`).
__kernel void photon_march_chunk(__global const float4* photonPos,
  __global const float4* photonDir, __global const float4* photonPower,
  __global const uint* photonStream, const uint count,
  __global const float* refractiveIndex, __global const float* gradient,
  __global const float* extinction, __global const float* albedo, __global const uchar* octree,
  const int4 dims, const float4 spacing, volatile __global long* deposits, volatile __global long* tallies,
  volatile __global long* counters, const uint seed, const uint first, __global float4* state,
  __global uint4* status, const uint chunkSteps, volatile __global int* active,
  __global const float4* surfaceNodes, const int surfaceNodeCount,
  __global const float4* surfaceTriangles, __global const int4* surfaceInfo,
  __global const float* surfaceAlbedo, volatile __global long* surfaceIrradiance,
  const float4 frame0, const float4 frame1, const float4 frame2, const float surfaceEpsilon,
  const long causticOffset,
  __global const float* anisotropy, volatile __global long* multiple,
  __global const float4* surfaceNormals, __global const float2* surfaceInterfaces,
  __global const float4* surfaceBodies, __global const uchar* cutLinks,
  __global const int* volumeCausticBricks,
  volatile __global long* volumeCausticFine, const int volumeCausticSubdivision)
{
  const uint id = first + (uint)get_global_id(0);
  if (id >= count)
  {
    return;
  }
  uint4 st = status[id];
  if (st.x == 2u)
  {
    return;
  }
  __global float4* s = state + PHOTON_STATE_FLOAT4S * (size_t)id;
  photon_state ps;
  float3 x, v, emitted;
  float3 lo;
  float3 hi;
  refracta_domain(dims, spacing, &lo, &hi);
  const bool fresh = st.x == 0u; // a new photon: its start body is found below
  if (fresh)
  {
    if (!photon_start(
        &ps, photonPower[id].xyz, seed, photonStream[id], anisotropy, multiple, counters))
    {
      status[id] = (uint4)(2u, 0u, 0u, 0u);
      return;
    }
    emitted = ps.power;
    x = photonPos[id].xyz;
    const float3 d0 = normalize(photonDir[id].xyz);
#if REFRACTA_SURFACES
    v = photon_velocity(x, d0, lo, hi, refractiveIndex, dims, spacing);
#elif REFRACTA_REFRACT
    v = d0 * refracta_sample1(refractiveIndex, dims, refracta_to_voxel(x, spacing));
#else
    // Straight ray: start at the box entry (photon_march's single step starts there too).
    float t0;
    float t1;
    if (refracta_intersect_box(x, d0, lo, hi, &t0, &t1) && t1 > 0.0f)
    {
      x = x + t0 * d0;
      v = d0;
    }
    else
    {
      v = (float3)(0.0f); // misses: escapes at once below
    }
#endif
    st = (uint4)(1u, 0u, ps.rng, 0u);
  }
  else
  {
    x = s[0].xyz;
    v = s[1].xyz;
    ps.power = s[2].xyz;
    ps.threshold = s[2].w;
    ps.absorbed = s[3].xyz;
    ps.scattered = s[4].xyz;
    ps.killed = s[5].xyz;
    ps.gained = s[6].xyz;
    emitted = s[7].xyz;
    ps.surface = s[8].xyz;
    ps.hits = as_uint(s[8].w);
    ps.interfaces = as_uint(s[3].w);
    ps.caustic = as_int(s[5].w);
    ps.rng = st.z;
    ps.pieces = st.w;
    photon_init_analog(&ps, anisotropy, multiple, as_int(s[4].w));
    ps.body = as_int(s[6].w);
  }
  ps.lobe = (int)photonPower[id].w;
  ps.bodies = surfaceBodies;
  photon_set_sides(&ps, cutLinks, surfaceNodes, surfaceNodeCount, surfaceTriangles,
    (__global const int*)surfaceInfo, frame0, frame1, frame2, spacing);
  photon_set_volume_caustic(&ps, volumeCausticBricks, volumeCausticFine, volumeCausticSubdivision);
  ps.dead = 0;
  int steps = (int)st.y;
  int outcome = -1; // -1 still marching; 2 escaped, 3 roulette, 4 step cap, 5 invalid, 8 surface
#if REFRACTA_SURFACES
  photon_surfaces surf;
  photon_set_surfaces(&surf, surfaceNodes, surfaceNodeCount, surfaceTriangles, surfaceInfo,
    surfaceAlbedo, surfaceIrradiance, frame0, frame1, frame2, surfaceEpsilon, causticOffset,
    surfaceNormals, surfaceInterfaces, tallies, counters);
#if REFRACTA_INTERFACES
  if (fresh)
  {
    ps.body = photon_start_body(&surf, &ps, x, normalize(photonDir[id].xyz));
  }
#endif
  for (uint c = 0; c < chunkSteps && outcome < 0; ++c)
  {
    outcome = photon_surface_event(&ps, &x, &v, &steps, lo, hi, octree, extinction, albedo,
      refractiveIndex, gradient, dims, spacing, deposits, &surf);
  }
#elif !REFRACTA_REFRACT
  {
    float t0;
    float t1;
    const float segment = fmin(spacing.x, fmin(spacing.y, spacing.z));
    if (!(length(v) > 0.0f) || !refracta_intersect_box(x, v, lo, hi, &t0, &t1) || !(t1 > 0.0f))
    {
      outcome = PHOTON_COUNTER_ESCAPED;
    }
    for (uint c = 0; c < chunkSteps && outcome < 0; ++c)
    {
      const float len = fmin(segment, t1);
      if (steps == 0)
      {
        steps = 1; // photon_march counts a straight ray as one step
      }
#if REFRACTA_EXTINCTION
      photon_walk(&ps, x, x + len * v, 1.0f, dims, spacing, extinction, albedo, deposits);
#endif
      x = x + len * v;
      t1 -= len;
      if (ps.dead)
      {
        outcome = PHOTON_COUNTER_ROULETTE;
      }
      else if (!(t1 > 1e-6f * segment))
      {
        outcome = PHOTON_COUNTER_ESCAPED;
      }
    }
  }
#else
  for (uint c = 0; c < chunkSteps && outcome < 0; ++c)
  {
    outcome = photon_curved_step(&ps, &x, &v, &steps, lo, hi, octree, extinction, albedo,
      refractiveIndex, gradient, dims, spacing, deposits);
  }
#endif
  if (outcome < 0)
  {
    s[0] = (float4)(x, 0.0f);
    s[1] = (float4)(v, 0.0f);
    s[2] = (float4)(ps.power, ps.threshold);
    s[3] = (float4)(ps.absorbed, as_float(ps.interfaces));
    s[4] = (float4)(ps.scattered, as_float(ps.order));
    s[5] = (float4)(ps.killed, as_float(ps.caustic));
    s[6] = (float4)(ps.gained, as_float(ps.body));
    s[7] = (float4)(emitted, 0.0f);
    s[8] = (float4)(ps.surface, as_float(ps.hits));
    status[id] = (uint4)(1u, (uint)steps, ps.rng, ps.pieces);
    atomic_inc(active);
    return;
  }
  status[id] = (uint4)(2u, (uint)steps, ps.rng, ps.pieces);
  photon_finish(tallies, counters, emitted, &ps, outcome, steps);
}
