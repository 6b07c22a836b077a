// photon_trace.cl: adaptive curved-path photon marching (Sun et al. 2008, sections 4.4 and 5.3;
// conventions of Documentation/Physics.md): the photon's state, its pieces and steps; the kernels
// are in photon_march.cl, photon generation in photon_generate.cl. Prepend refracta_atomics.cl,
// refracta_common.cl and photon_tallies.cl (the books' layout).
//
// photon_march: one work-item per photon, marching it to termination. Each step advances x and
// v = n dx/ds along the ray equation (x' = v / n, v' = grad n) with a midpoint (RK2) update,
// step = clamp(octree step, REFRACTA_MIN_STEP, REFRACTA_MAX_STEP or REFRACTA_CAP_STEP), |dv| bounded by REFRACTA_MAX_TURN * n and
// |v| renormalised to n, halved while the gradient changes fast over it (REFRACTA_STEP_TOLERANCE,
// at most REFRACTA_MAX_HALVINGS times). The chord of the step is walked voxel by voxel (3D DDA, the paper's line
// rasterisation): in each piece sigma_t and the albedo are sampled at the piece's midpoint,
// the power lost over the piece, P (1 - exp(-sigma_t l)), is split into absorbed and scattered,
// and the scattered part is deposited into that voxel's Radiance accumulator (with the piece's
// direction weighted by it into the RadianceDirection accumulator): `deposits` holds six cl_long
// per voxel, deposits[6 v + c] the scattered power (RGB) and deposits[6 v + 3 + c] the direction
// sums (xyz), fixed point; with S1 in lobes (REFRACTA_LOBES = K > 1) K more blocks of six per
// voxel follow, a photon from a light of lobe k (photonPower.w) depositing into block 1 + k
// instead (the host sums them into the first block, radiance_sum_lobes). Termination: the photon
// leaves the domain (escaped), Russian roulette below REFRACTA_ROULETTE x its initial power (killed;
// survivors are boosted by 1/q and the boost is tallied so the books close), the step cap
// REFRACTA_MAX_STEPS (its power is tallied as remaining), or a non-finite state (never expected; counted).
//
// Variants (-D, 0 or 1): REFRACTA_REFRACT (curved rays with n and grad n lookups; 0: straight rays, one
// step to the exit), REFRACTA_ADAPTIVE (octree step; 0: REFRACTA_FIXED_STEP), REFRACTA_EXTINCTION (anything attenuates; 0:
// no piece walk at all), REFRACTA_DEPOSIT (anything scatters; 0: no radiance accumulation),
// REFRACTA_GREY_EXTINCTION and REFRACTA_GREY_ALBEDO (the medium's sigma_t, or albedo, is the same
// in every channel and `extinction`, or `albedo`, holds one value per voxel instead of three: a
// third of the gathers and of the cache footprint).
// Lengths (REFRACTA_MIN_STEP, REFRACTA_MAX_STEP, REFRACTA_CAP_STEP, REFRACTA_FIXED_STEP) are in voxels (the smallest
// spacing; the kernel scales them, so that one program serves every grid); REFRACTA_EXT_STEP_LIMIT is an
// optical depth (0: off); REFRACTA_ROULETTE a fraction of the initial power; REFRACTA_FIXED_SCALE the
// fixed-point scale of refracta_atomics.cl.
//
// Surfaces (REFRACTA_SURFACES 1; prepend refracta_surfaces.cl): opaque triangles of a
// vtkRefractaSurfaceSet in a BVH (surface frame; `frame` maps grid-local points to it). Photons
// then also fly outside the medium's box, in straight lines, between the surfaces and the box
// (photon_surface_event): inside the box every curved step's chord (straight rays: every flight)
// is tested against the BVH; a hit ends the chord's voxel walk there, adds the photon's power to
// the hit texel's irradiance accumulator, books power x (1 - albedo) as absorbed by the surface and
// keeps power x albedo, which goes on with Russian roulette on the albedo (survival probability
// max(albedo), survivors boosted, books kept) in a cosine-weighted direction about the normal on
// the incoming side, from a point `surfaceEpsilon` off the surface. A photon that leaves
// the box without meeting a surface escapes.
//
// Analog scattering (REFRACTA_ANALOG 1, only with REFRACTA_SURFACES and REFRACTA_DEPOSIT; see
// vtkPhotonTracer::AnalogScattering): the lattice, which knows no surfaces, is replaced by the
// photons themselves. A piece still deposits its expected scattered power P (1 - T) a (order 0,
// a photon straight from a light, through glass or not: `deposits`, S1 and its direction; order
// >= 1, a photon that has scattered in the medium or been reflected by a surface since:
// `multiple`, S_ms), books P (1 - T) (1 - a) as absorbed, and then goes on either unscattered
// (power P T / (1 - q)) or scattered in the piece (power P (1 - T) a / q, at an exponentially
// distributed point, in a Henyey-Greenstein direction, order + 1), with
// q = sum_c P (1 - T_c) a_c / sum_c P (T_c + (1 - T_c) a_c): the choice keeps the photon's total
// power, and any per-channel difference (coloured media) goes to the roulette books (killed /
// gained), so the books stay exact per photon and nothing goes to `scattered`.
// A surface's diffuse reflection sets the order to 1 (diffuse light, whose flux over its fluence
// shades it; without analog scattering it starts a new beam, order 0).
// The analog machinery also runs without surfaces (the kernels are built with REFRACTA_SURFACES
// and an empty surface set) for the first-collision split (vtkPhotonTracer::ScatteringOrders k):
// a photon scatters analogically while its order is below REFRACTA_ANALOG_ORDERS = k; at order k
// it still deposits into `multiple`, but what it scatters is also handed to the lattice (books:
// `scattered`; the accumulators after S_ms's in `multiple`: 3 per voxel for the source, then 3
// for its direction sums) and it flies on with the unscattered part only, as without analog
// scattering; the lattice then carries the orders above k from that smoother source. `multiple`
// starts with six per voxel, S_ms and its direction sums (weighted by the deposit's channel sum),
// as `deposits` does: the flux over the fluence that shades S_ms.
//
// Glass bodies (REFRACTA_INTERFACES): a dielectric surface with an inside medium (the `bodies`
// table of refracta_surfaces.cl) fills its inside with that homogeneous medium. A photon carries
// the body it is in (`body`, -1: the grid): set when it is refracted into such a surface's inside,
// cleared when refracted out, found at its start by its first hit along its direction (leaving a
// body's surface from inside: in that body). Inside a body a piece's extinction and albedo, and the
// analog scattering's anisotropy, are the body's, not the grid's trilinear samples (which blend
// the materials of the voxels the surface cuts); deposits still go to the voxel the piece is in.
//
// Volume caustic (with REFRACTA_INTERFACES, where photons can be caustic; a run-time choice by the
// subdivision argument, so it adds no kernel variant; vtkPhotonTracer::VolumeCausticSubdivision):
// a caustic photon's S1 in a voxel with a brick goes into the brick's c^3 fine voxels instead
// (photon_deposit_volume_caustic); the pilot march (c = 1, every voxel its own brick) only counts
// caustic pieces per voxel; c = 0: none.
//
// Tallies (fixed point, REFRACTA_FIXED_SCALE): tallies[3 * T + c] for the books T =
// PHOTON_TALLY_EMITTED ... PHOTON_TALLY_GAINED; counters: PHOTON_COUNTER_MARCHED ...
// PHOTON_COUNTER_PIECES; the outcome of a photon is the index of its counter (escaped, roulette,
// step cap, invalid, surface). The layout is defined once, in photon_tallies.cl.

#ifndef REFRACTA_REFRACT
#define REFRACTA_REFRACT 1
#endif
#ifndef REFRACTA_ADAPTIVE
#define REFRACTA_ADAPTIVE 1
#endif
#ifndef REFRACTA_EXTINCTION
#define REFRACTA_EXTINCTION 1
#endif
#ifndef REFRACTA_DEPOSIT
#define REFRACTA_DEPOSIT 1
#endif
#ifndef REFRACTA_MIN_STEP
#define REFRACTA_MIN_STEP 1.0f
#endif
#ifndef REFRACTA_MAX_STEP
#define REFRACTA_MAX_STEP 64.0f
#endif
#ifndef REFRACTA_CAP_STEP
#define REFRACTA_CAP_STEP 8.0f
#endif
#ifndef REFRACTA_FIXED_STEP
#define REFRACTA_FIXED_STEP 1.0f
#endif
#ifndef REFRACTA_MAX_STEPS
#define REFRACTA_MAX_STEPS 10000
#endif
#ifndef REFRACTA_MAX_INTERFACES
#define REFRACTA_MAX_INTERFACES 64
#endif
#ifndef REFRACTA_EXT_STEP_LIMIT
#define REFRACTA_EXT_STEP_LIMIT 0.0f
#endif
#ifndef REFRACTA_LOBES
#define REFRACTA_LOBES 1 /* S1's lobes: > 1, `deposits` holds a block per lobe after S1's */
#endif
#ifndef REFRACTA_ROULETTE
#define REFRACTA_ROULETTE 0.001f
#endif
#ifndef REFRACTA_MAX_TURN
#define REFRACTA_MAX_TURN 0.5f
#endif
#ifndef REFRACTA_SURFACES
#define REFRACTA_SURFACES 0
#endif
#ifndef REFRACTA_ANALOG_ORDERS
#define REFRACTA_ANALOG_ORDERS 0x7fffffff
#endif
#ifndef REFRACTA_ANALOG
#define REFRACTA_ANALOG 0
#endif
#ifndef REFRACTA_SKIP_DIRECT
#define REFRACTA_SKIP_DIRECT 0 /* 1: direct surface light left to light rays (photon_surfaces.cl) */
#endif
#ifndef REFRACTA_SIDED_DEPOSITS
#define REFRACTA_SIDED_DEPOSITS 0 /* 1: opaque surfaces cut the grid (photon_sided_voxel) */
#endif
#ifndef REFRACTA_STEP_TOLERANCE
#define REFRACTA_STEP_TOLERANCE 0.02f
#endif
#ifndef REFRACTA_MAX_HALVINGS
#define REFRACTA_MAX_HALVINGS 6
#endif

// Per-photon state and private tallies.
typedef struct
{
  float3 power;
  float threshold;
  float3 absorbed;
  float3 scattered;
  float3 killed;
  float3 gained;
  float3 surface; // absorbed by surfaces
  uint rng;
  uint pieces;
  uint hits; // surface hits
  uint interfaces; // dielectric interface events (REFRACTA_MAX_INTERFACES ends a trapped photon)
  int caustic;     // met a dielectric interface since the light or its last diffuse event
  int dead;
  int lobe;                                // S1's lobe of its light (REFRACTA_LOBES)
  int order;                               // scatterings since the light or the last surface
  int collided;                            // analog: scattered in the last piece
  float collisionDistance;                 // analog: from the start of that piece (world units)
  float3 collisionPoint;                   // analog: where (grid-local)
  __global const float* anisotropy;        // analog: g per voxel
  volatile __global long* multiple;        // analog: S_ms accumulators (order >= 1)
  int body;                                // the glass body it is in, or -1 (the grid)
  __global const float4* bodies;           // the bodies' media (refracta_surfaces.cl)
  __global const int* causticBricks;       // volume caustic: brick of each voxel, or -1
  volatile __global long* causticFine;     // volume caustic: PHOTON_FINE_LONGS per fine voxel
                                           // (the pilot, c = 1: one uint per voxel)
  int causticSub;                          // volume caustic: c, bricks of c^3 fine voxels
  // Sided deposits (REFRACTA_SIDED_DEPOSITS): the voxels near opaque triangles (bit
  // REFRACTA_CUT_NEAR of cutLinks, vtkRefractaGridCuts), the surfaces (BVH, triangles, their
  // info), the grid-local -> surface frame rows and the grid's spacing.
  __global const uchar* cutLinks;
  __global const float4* sideNodes;
  int sideNodeCount;
  __global const float4* sideTriangles;
  __global const int* sideInfo;
  float4 sideFrame0, sideFrame1, sideFrame2;
  float4 sideSpacing;
} photon_state;

// The volume caustic's fine accumulators per fine voxel: S1 (3), direction sums (3), two longs of
// padding (64 bytes: one cache line per fine voxel; vtkPhotonTracerVolumeCaustic.cxx reads the
// same layout).
#define PHOTON_FINE_LONGS 8

inline void photon_set_volume_caustic(
  photon_state* ps, __global const int* bricks, volatile __global long* fine, int subdivision)
{
  ps->causticBricks = bricks;
  ps->causticFine = fine;
  ps->causticSub = subdivision;
}

// The sided deposits' view of the scene (photon_sided_voxel): the voxels near opaque triangles,
// the surfaces in their frame and the grid's spacing.
inline void photon_set_sides(photon_state* ps, __global const uchar* cutLinks,
  __global const float4* nodes, int nodeCount, __global const float4* triangles,
  __global const int* info, float4 frame0, float4 frame1, float4 frame2, float4 spacing)
{
  ps->cutLinks = cutLinks;
  ps->sideNodes = nodes;
  ps->sideNodeCount = nodeCount;
  ps->sideTriangles = triangles;
  ps->sideInfo = info;
  ps->sideFrame0 = frame0;
  ps->sideFrame1 = frame1;
  ps->sideFrame2 = frame2;
  ps->sideSpacing = spacing;
}

// A 3D DDA over unit cells along a + t du (t in [0, 1]) from `cell`: each axis's step (-1, 0, 1),
// the t between its cell faces and the t of its next face.
inline void photon_dda_start(
  float3 a, float3 du, int3 cell, int3* stepDir, float3* tDelta, float3* tNext)
{
  *stepDir = (int3)(du.x > 0.0f ? 1 : (du.x < 0.0f ? -1 : 0),
    du.y > 0.0f ? 1 : (du.y < 0.0f ? -1 : 0), du.z > 0.0f ? 1 : (du.z < 0.0f ? -1 : 0));
  *tDelta = fabs((float3)(1.0f) / du);
  float3 next;
  next.x = du.x > 0.0f ? ((float)(cell.x + 1) - a.x) / du.x
                       : (du.x < 0.0f ? ((float)cell.x - a.x) / du.x : INFINITY);
  next.y = du.y > 0.0f ? ((float)(cell.y + 1) - a.y) / du.y
                       : (du.y < 0.0f ? ((float)cell.y - a.y) / du.y : INFINITY);
  next.z = du.z > 0.0f ? ((float)(cell.z + 1) - a.z) / du.z
                       : (du.z < 0.0f ? ((float)cell.z - a.z) / du.z : INFINITY);
  *tNext = fmax(next, (float3)(0.0f));
}

#if REFRACTA_INTERFACES
// Volume caustic (vtkPhotonTracer::VolumeCausticSubdivision; Physics.md "Volume caustics"): a
// caustic photon (ps->caustic: refracted or reflected by an interface since its light, not yet
// scattered) in a voxel that has a brick deposits its piece's S1 share `sc` (and the direction
// sums) into the brick's c^3 fine voxels instead of the voxel: each fine voxel the piece crosses
// gets the share of the piece's length inside it (a 3D DDA over the brick).
// `from` and `to` are the piece's ends in voxel units (voxel i spans [i, i + 1)), `cell` the
// voxel. Returns false (deposit in the voxel as usual) for other photons and voxels, and when the
// run has no volume caustic (subdivision 0).
inline bool photon_deposit_volume_caustic(photon_state* ps, size_t voxel, int3 cell, float3 from,
  float3 to, float3 sc, float w, float3 direction)
{
  if (!ps->caustic || ps->causticSub == 0)
  {
    return false;
  }
  const int brick = ps->causticBricks[voxel];
  if (brick < 0)
  {
    return false;
  }
  const int c = ps->causticSub;
  if (c == 1)
  {
    // The pilot (every voxel its own brick): only count the caustic pieces, one uint per voxel.
    atomic_inc((volatile __global uint*)ps->causticFine + brick);
    return true;
  }
  const float3 f0 = (from - convert_float3(cell)) * (float)c;
  const float3 df = (to - convert_float3(cell)) * (float)c - f0;
  int3 fine = clamp(convert_int3_rtn(f0), (int3)(0), (int3)(c - 1));
  int3 stepDir;
  float3 tDelta, tNext;
  photon_dda_start(f0, df, fine, &stepDir, &tDelta, &tNext);
  const size_t first = (size_t)brick * (size_t)(c * c * c);
  float t = 0.0f;
  // The piece lies in one voxel: it crosses at most 3 c fine voxels (+1 for rounding).
  for (int it = 0; it < 3 * c + 1; ++it)
  {
    const float tEnd = fmin(fmin(fmin(tNext.x, tNext.y), tNext.z), 1.0f);
    // The last fine voxel takes what rounding left, so the shares sum to the piece's deposit.
    const float share = tEnd >= 1.0f ? 1.0f - t : tEnd - t;
    if (share > 0.0f)
    {
      volatile __global long* acc =
        ps->causticFine + PHOTON_FINE_LONGS * (first + (size_t)((fine.z * c + fine.y) * c + fine.x));
      refracta_atomic_add_fixed(acc, share * sc.x);
      refracta_atomic_add_fixed(acc + 1, share * sc.y);
      refracta_atomic_add_fixed(acc + 2, share * sc.z);
      refracta_atomic_add_fixed(acc + 3, share * w * direction.x);
      refracta_atomic_add_fixed(acc + 4, share * w * direction.y);
      refracta_atomic_add_fixed(acc + 5, share * w * direction.z);
      t = tEnd;
    }
    if (tEnd >= 1.0f)
    {
      break;
    }
    if (tNext.x <= tNext.y && tNext.x <= tNext.z)
    {
      fine.x = clamp(fine.x + stepDir.x, 0, c - 1);
      tNext.x += tDelta.x;
    }
    else if (tNext.y <= tNext.z)
    {
      fine.y = clamp(fine.y + stepDir.y, 0, c - 1);
      tNext.y += tDelta.y;
    }
    else
    {
      fine.z = clamp(fine.z + stepDir.z, 0, c - 1);
      tNext.z += tDelta.z;
    }
  }
  return true;
}
#endif

// Initial values of the fields added for analog scattering.
inline void photon_init_analog(photon_state* ps, __global const float* anisotropy,
  volatile __global long* multiple, int order)
{
  ps->order = order;
  ps->collided = 0;
  ps->collisionDistance = 0.0f;
  ps->collisionPoint = (float3)(0.0f);
  ps->anisotropy = anisotropy;
  ps->multiple = multiple;
}

// Adds a finished photon's books to the fixed-point tallies (order: emitted, absorbed, escaped,
// scattered, remaining, roulette-killed, roulette-gained, surface; RGB each) and its counters.
// What power it still carries is escaped (outcome 2), gone with roulette (3) or remaining (4, 5);
// a photon that ended on a surface (8) carries none.
inline void photon_finish(volatile __global long* tallies, volatile __global long* counters,
  float3 emitted, const photon_state* ps, int outcome, int steps)
{
  const float3 none = (float3)(0.0f);
  const float3 escaped = outcome == PHOTON_COUNTER_ESCAPED ? ps->power : none;
  const float3 remaining =
    (outcome == PHOTON_COUNTER_STEP_CAP || outcome == PHOTON_COUNTER_INVALID) ? ps->power : none;
  const float3 books[PHOTON_TALLY_BOOKS] = { emitted, ps->absorbed, escaped, ps->scattered, remaining, ps->killed,
    ps->gained, ps->surface };
  for (int t = 0; t < PHOTON_TALLY_BOOKS; ++t)
  {
    refracta_atomic_add_fixed(tallies + 3 * t + 0, books[t].x);
    refracta_atomic_add_fixed(tallies + 3 * t + 1, books[t].y);
    refracta_atomic_add_fixed(tallies + 3 * t + 2, books[t].z);
  }
  atom_add(counters + PHOTON_COUNTER_MARCHED, 1L);
  atom_add(counters + outcome, 1L);
  atom_add(counters + PHOTON_COUNTER_STEPS, (long)steps);
  atom_add(counters + PHOTON_COUNTER_PIECES, (long)ps->pieces);
  if (ps->hits > 0u)
  {
    atom_add(counters + PHOTON_COUNTER_SURFACE_HITS, (long)ps->hits);
  }
}

#if REFRACTA_ANALOG
// Analog scattering after a piece: ps->power holds the unscattered part U, `sc` the scattered
// part S. Scatter with probability q = sum(S) / sum(U + S) (power S / q, at a distance in the
// piece drawn from exp(-sigma s) truncated to its length, sigma the channels' mean extinction) or
// go on (U / (1 - q)); the per-channel change of the power is booked as roulette gain or loss.
inline void photon_choose_branch(photon_state* ps, float3 sc, float3 sigmaT, float length)
{
  const float3 before = ps->power + sc;
  const float ss = sc.x + sc.y + sc.z;
  const float total = before.x + before.y + before.z;
  if (!(ss > 0.0f) || !(total > 0.0f))
  {
    return;
  }
  const float q = fmin(ss / total, 1.0f);
  float3 after;
  if (refracta_rng_uniform(&ps->rng) < q)
  {
    after = sc / q;
    ps->collided = 1;
    const float sigma = (sigmaT.x + sigmaT.y + sigmaT.z) / 3.0f;
    const float u = refracta_rng_uniform(&ps->rng);
    const float tau = sigma * length;
    ps->collisionDistance = tau > 1e-6f
      ? fmin(-log1p(u * expm1(-tau)) / sigma, length)
      : u * length;
  }
  else
  {
    after = ps->power / (1.0f - q);
  }
  ps->gained += fmax(after - before, (float3)(0.0f));
  ps->killed += fmax(before - after, (float3)(0.0f));
  ps->power = after;
}

// The first-collision split at order REFRACTA_ANALOG_ORDERS: the scattered part `sc` (weight w
// = its channel sum) of the piece in `voxel` becomes the lattice's source (after the S_ms
// accumulators in `multiple`: the source, then its direction sums) and leaves the photon's books
// as handed on; the photon goes on with the unscattered part.
inline void photon_hand_to_lattice(
  photon_state* ps, float3 sc, float w, float3 direction, size_t voxel, int4 dims)
{
  ps->scattered += sc;
  if (!(w > 0.0f))
  {
    return;
  }
  const size_t voxels = (size_t)dims.x * (size_t)dims.y * (size_t)dims.z;
  volatile __global long* source = ps->multiple + 6 * voxels + 3 * voxel;
  volatile __global long* sourceDirection = ps->multiple + 9 * voxels + 3 * voxel;
  refracta_atomic_add_fixed(source, sc.x);
  refracta_atomic_add_fixed(source + 1, sc.y);
  refracta_atomic_add_fixed(source + 2, sc.z);
  refracta_atomic_add_fixed(sourceDirection, w * direction.x);
  refracta_atomic_add_fixed(sourceDirection + 1, w * direction.y);
  refracta_atomic_add_fixed(sourceDirection + 2, w * direction.z);
}

// A direction drawn from the Henyey-Greenstein phase function about unit d.
inline float3 photon_sample_hg(float3 d, float g, uint* rng)
{
  const float u1 = refracta_rng_uniform(rng);
  const float u2 = refracta_rng_uniform(rng);
  float c;
  if (fabs(g) < 1e-3f)
  {
    c = 1.0f - 2.0f * u1;
  }
  else
  {
    const float k = (1.0f - g * g) / (1.0f - g + 2.0f * g * u1);
    c = (1.0f + g * g - k * k) / (2.0f * g);
  }
  c = clamp(c, -1.0f, 1.0f);
  const float s = sqrt(fmax(0.0f, 1.0f - c * c));
  const float phi = 2.0f * REFRACTA_PI * u2;
  const float3 helper = fabs(d.x) < 0.9f ? (float3)(1.0f, 0.0f, 0.0f) : (float3)(0.0f, 1.0f, 0.0f);
  const float3 e1 = normalize(cross(d, helper));
  const float3 e2 = cross(d, e1);
  return normalize(s * cos(phi) * e1 + s * sin(phi) * e2 + c * d);
}
#endif

// sigma_t and the albedo at u (voxel units), RGB, from one value per voxel in a grey medium.
#if REFRACTA_GREY_EXTINCTION
#define photon_extinction_at(field, dims, u) ((float3)(refracta_sample1((field), (dims), (u))))
#else
#define photon_extinction_at(field, dims, u) refracta_sample3((field), (dims), (u))
#endif
#if REFRACTA_GREY_ALBEDO
#define photon_albedo_at(field, dims, u) ((float3)(refracta_sample1((field), (dims), (u))))
#else
#define photon_albedo_at(field, dims, u) refracta_sample3((field), (dims), (u))
#endif

#if REFRACTA_SIDED_DEPOSITS
// Whether an opaque surface separates voxel coordinates a and b (centres at integers).
inline bool photon_separated(const photon_state* ps, float3 a, float3 b)
{
  return refracta_opaque_between(ps->sideNodes, ps->sideNodeCount, ps->sideTriangles,
    ps->sideInfo, ps->sideFrame0, ps->sideFrame1, ps->sideFrame2, a * ps->sideSpacing.xyz,
    b * ps->sideSpacing.xyz);
}

// The voxel that a piece in voxel `voxel` (at voxel coordinates `cell`) deposits into: its own,
// unless an opaque surface separates the piece's midpoint `mid` from the voxel's centre (asked
// only of voxels near opaque triangles, REFRACTA_CUT_NEAR); then the nearest of the 26 voxels
// around it whose centre no opaque surface separates from `mid` (its own voxel where there is
// none: a closed body thinner than a voxel). Light on one side of a wall thus lands in a voxel
// whose centre is on that side, whatever the wall's shape.
inline size_t photon_sided_voxel(const photon_state* ps, int4 dims, int3 cell, float3 mid,
  size_t voxel)
{
  if (!(ps->cutLinks[voxel] & REFRACTA_CUT_NEAR) ||
    !photon_separated(ps, mid, convert_float3(cell)))
  {
    return voxel;
  }
  // The 27 voxels around its own (the eight centres around `mid` among them), nearest first.
  int tried = 1 << 13; // bit k: neighbour (k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1) tried; 13: itself
  for (int round = 0; round < 26; ++round)
  {
    int pick = -1;
    float nearest = INFINITY;
    for (int k = 0; k < 27; ++k)
    {
      const int3 to = cell + (int3)(k % 3 - 1, (k / 3) % 3 - 1, k / 9 - 1);
      const bool inGrid =
        all(to >= (int3)(0)) && to.x < dims.x && to.y < dims.y && to.z < dims.z;
      const float3 offset = convert_float3(to) - mid;
      const float d = dot(offset, offset);
      if (!((tried >> k) & 1) && inGrid && d < nearest)
      {
        nearest = d;
        pick = k;
      }
    }
    if (pick < 0)
    {
      break;
    }
    tried |= 1 << pick;
    const int3 to = cell + (int3)(pick % 3 - 1, (pick / 3) % 3 - 1, pick / 9 - 1);
    if (!photon_separated(ps, mid, convert_float3(to)))
    {
      return refracta_voxel_index(dims, to.x, to.y, to.z);
    }
  }
  return voxel;
}
#endif

#if REFRACTA_EXTINCTION
// One piece of a voxel (sigma_t and the albedo sampled at its midpoint `mid`): attenuate, split the
// loss, deposit the scattered part in `voxel`, then roulette.
// `cell` is the voxel, `from` and `to` the piece's ends in voxel units (for the volume caustic).
inline void photon_piece(photon_state* ps, float3 mid, float length, float3 direction,
  size_t voxel, int3 cell, float3 from, float3 to, __global const float* extinction,
  __global const float* albedo, int4 dims, volatile __global long* deposits)
{
#if REFRACTA_INTERFACES
  const bool inBody = ps->body >= 0;
  const float3 sigmaT =
    inBody ? ps->bodies[3 * ps->body].xyz : photon_extinction_at(extinction, dims, mid);
#else
  const float3 sigmaT = photon_extinction_at(extinction, dims, mid);
#endif
  const float3 lost = ps->power * (-expm1(-sigmaT * length));
  ps->power = fmax(ps->power - lost, (float3)(0.0f));
  ps->pieces++;
#if REFRACTA_DEPOSIT
#if REFRACTA_INTERFACES
  const float3 a = inBody ? ps->bodies[3 * ps->body + 1].xyz : photon_albedo_at(albedo, dims, mid);
  const float3 sc = lost * clamp(a, 0.0f, 1.0f);
#else
  const float3 sc = lost * clamp(photon_albedo_at(albedo, dims, mid), 0.0f, 1.0f);
#endif
  ps->absorbed += lost - sc;
  const float w = sc.x + sc.y + sc.z;
#if REFRACTA_SIDED_DEPOSITS
  const size_t target = photon_sided_voxel(ps, dims, cell, mid, voxel);
#else
  const size_t target = voxel;
#endif
#if REFRACTA_ANALOG
  if (ps->order > 0)
  {
    if (w > 0.0f)
    {
      // S_ms's direction sums follow it (its flux over its fluence, the view pass's phase
      // function for the multiply scattered light), in the same cache line (six per voxel, as
      // `deposits`).
      volatile __global long* acc = ps->multiple + 6 * target;
      refracta_atomic_add_fixed(acc + 3, w * direction.x);
      refracta_atomic_add_fixed(acc + 4, w * direction.y);
      refracta_atomic_add_fixed(acc + 5, w * direction.z);
      refracta_atomic_add_fixed(acc, sc.x);
      refracta_atomic_add_fixed(acc + 1, sc.y);
      refracta_atomic_add_fixed(acc + 2, sc.z);
    }
  }
  else
#else
  ps->scattered += sc;
#endif
#if REFRACTA_INTERFACES
  if (w > 0.0f && !photon_deposit_volume_caustic(ps, voxel, cell, from, to, sc, w, direction))
#else
  if (w > 0.0f)
#endif
  {
    // One voxel's six accumulators share a cache line (the first touch of a voxel's line is most
    // of a deposit's cost on a CPU: two lines per piece cost 12% more of the default scene's pass).
#if REFRACTA_LOBES > 1
    // S1 in lobes: into the block of the photon's lobe (the blocks after the first,
    // vtkRefractaLightingVolume::RadianceLobeName), which the host sums into the first
    // (radiance_sum_lobes) before anything reads it.
    volatile __global long* acc = deposits + 6 * ((size_t)(1 + ps->lobe) * ((size_t)dims.x *
      (size_t)dims.y * (size_t)dims.z) + target);
#else
    volatile __global long* acc = deposits + 6 * target;
#endif
    refracta_atomic_add_fixed(acc, sc.x);
    refracta_atomic_add_fixed(acc + 1, sc.y);
    refracta_atomic_add_fixed(acc + 2, sc.z);
    refracta_atomic_add_fixed(acc + 3, w * direction.x);
    refracta_atomic_add_fixed(acc + 4, w * direction.y);
    refracta_atomic_add_fixed(acc + 5, w * direction.z);
  }
#if REFRACTA_ANALOG
  if (ps->order >= REFRACTA_ANALOG_ORDERS)
  {
    photon_hand_to_lattice(ps, sc, w, direction, target, dims);
  }
  else
  {
    photon_choose_branch(ps, sc, sigmaT, length);
  }
#endif
#else
  ps->absorbed += lost;
#endif
  const float m = fmax(ps->power.x, fmax(ps->power.y, ps->power.z));
  if (m < ps->threshold)
  {
    const float q = m / ps->threshold;
    if (refracta_rng_uniform(&ps->rng) >= q)
    {
      ps->killed += ps->power;
      ps->power = (float3)(0.0f);
      ps->dead = 1;
    }
    else
    {
      const float3 boosted = ps->power / q;
      ps->gained += boosted - ps->power;
      ps->power = boosted;
    }
  }
}

// Walks the chord x0 -> x0 + t1 * (x1 - x0) (grid-local, t1 in [0, 1]) voxel by voxel. With
// REFRACTA_NODE_CUTS (the host sets it where sigma_t bends steeply at nodes: vtkPhotonTracer's
// GetUsedNodePlaneCuts()) each voxel is cut at its node's planes: the cells of the walk are half
// voxels (cell c spans [c, c + 1) in half voxels from the grid's lower face; voxel c >> 1 owns it
// and gets its deposits). The trilinear sigma_t has its kinks there, so each cut sees sigma_t
// smooth along it and its midpoint sample integrates it (exactly where sigma_t is linear along it,
// as along an axis). One midpoint per voxel sees the nearest node's sigma_t over the whole voxel:
// at a dense body's face light entered half a voxel deeper than in the trilinear medium the view
// pass and the reference renderer see (the accuracy benchmark's dense cube read 1.5% dark with the
// smoothing kept off the surface; Physics.md, "Dense surfaces").
#if REFRACTA_NODE_CUTS
#define PHOTON_CUT_SHIFT 1
#else
#define PHOTON_CUT_SHIFT 0
#endif
inline void photon_walk(photon_state* ps, float3 x0, float3 x1, float t1, int4 dims,
  float4 spacing, __global const float* extinction, __global const float* albedo,
  volatile __global long* deposits)
{
  const float cells = (float)(1 << PHOTON_CUT_SHIFT); // walk cells per voxel along an axis
  const float3 a = cells * (refracta_to_voxel(x0, spacing) + 0.5f);
  const float3 du = cells * (refracta_to_voxel(x1, spacing) + 0.5f) - a;
  const float worldLength = length(x1 - x0);
  if (!(worldLength > 0.0f) || !(t1 > 0.0f))
  {
    return;
  }
  const float3 direction = (x1 - x0) / worldLength;
  const int3 hiCell = (int3)((dims.x << PHOTON_CUT_SHIFT) - 1, (dims.y << PHOTON_CUT_SHIFT) - 1,
    (dims.z << PHOTON_CUT_SHIFT) - 1);
  int3 cell = clamp(convert_int3_rtn(a), (int3)(0), hiCell);
  int3 stepDir;
  float3 tDelta, tNext;
  photon_dda_start(a, du, cell, &stepDir, &tDelta, &tNext);
  float t = 0.0f;
  // A chord of length L cells crosses at most L_x + L_y + L_z + 3 cells: never a hang.
  const int guard = (int)(fabs(du.x) + fabs(du.y) + fabs(du.z)) + 8;
  for (int it = 0; it < guard && !ps->dead; ++it)
  {
    const float tEnd = fmin(fmin(fmin(tNext.x, tNext.y), tNext.z), t1);
    if (tEnd > t)
    {
      const float3 from = (a + du * t) / cells;
      const float3 to = (a + du * tEnd) / cells;
      const int3 voxel = cell >> PHOTON_CUT_SHIFT;
      const float3 mid = (a + du * (0.5f * (t + tEnd))) / cells - 0.5f;
      photon_piece(ps, mid, (tEnd - t) * worldLength, direction,
        refracta_voxel_index(dims, voxel.x, voxel.y, voxel.z), voxel, from, to, extinction, albedo,
        dims, deposits);
#if REFRACTA_ANALOG
      if (ps->collided)
      {
        // The rest of the chord belongs to the scattered photon's next event.
        ps->collisionPoint = x0 + t * (x1 - x0) + ps->collisionDistance * direction;
        break;
      }
#endif
      t = tEnd;
    }
    if (tEnd >= t1)
    {
      break;
    }
    if (tNext.x <= tNext.y && tNext.x <= tNext.z)
    {
      cell.x += stepDir.x;
      tNext.x += tDelta.x;
    }
    else if (tNext.y <= tNext.z)
    {
      cell.y += stepDir.y;
      tNext.y += tDelta.y;
    }
    else
    {
      cell.z += stepDir.z;
      tNext.z += tDelta.z;
    }
    if (any(cell < (int3)(0)) || any(cell > hiCell))
    {
      break; // rounding at the domain's face: the rest of the chord is outside
    }
  }
}
#endif

#if REFRACTA_REFRACT
// Step length at x for unit direction d (world units).
inline float photon_step(float3 x, float3 d, __global const uchar* octree,
  __global const float* extinction, int4 dims, float4 spacing)
{
  const float minSpacing = fmin(fmin(spacing.x, spacing.y), spacing.z);
#if REFRACTA_ADAPTIVE
  const float3 u = refracta_to_voxel(x, spacing);
  const int3 c = clamp(convert_int3_rte(u), (int3)(0), (int3)(dims.x - 1, dims.y - 1, dims.z - 1));
  const uchar code = octree[refracta_voxel_index(dims, c.x, c.y, c.z)];
  const int level = code & 0x1f;
  const int3 lo = (c >> level) << level;
  const float3 blo = (convert_float3(lo) - 0.5f) * spacing.xyz;
  const float3 bhi = (convert_float3(lo + (1 << level)) - 0.5f) * spacing.xyz;
  const float3 inv = (float3)(1.0f) / d;
  const float3 tmax = fmax((blo - x) * inv, (bhi - x) * inv);
  const float exitT = fmax(fmin(fmin(tmax.x, tmax.y), tmax.z), 0.0f);
  float h = clamp(exitT + 1e-3f * minSpacing, REFRACTA_MIN_STEP * minSpacing,
    ((code & 0x80) ? REFRACTA_CAP_STEP : REFRACTA_MAX_STEP) * minSpacing);
#else
  float h = REFRACTA_FIXED_STEP * minSpacing;
#endif
#if REFRACTA_EXTINCTION
  if (REFRACTA_EXT_STEP_LIMIT > 0.0f)
  {
    const float3 st = photon_extinction_at(extinction, dims, refracta_to_voxel(x, spacing));
    const float m = fmax(st.x, fmax(st.y, st.z));
    if (m > 0.0f)
    {
      h = fmax(fmin(h, REFRACTA_EXT_STEP_LIMIT / m), REFRACTA_ADAPTIVE ? REFRACTA_MIN_STEP * minSpacing : 0.0f);
    }
  }
#endif
  return h;
}

// dv bounded to REFRACTA_MAX_TURN * n: a steep index step turns a ray over several steps, never at once.
inline float3 photon_bounded(float3 dv, float n)
{
  const float m = length(dv);
  const float limit = REFRACTA_MAX_TURN * n;
  return m > limit ? dv * (limit / m) : dv;
}

// One adaptive step of the ray equation from (x, v): its length from the octree (photon_step),
// then a midpoint (RK2) update of x' = v / n, v' = grad n with the velocity change bounded and
// |v| renormalised to n, the step halved while its local error is too large (below). Shared by
// photon_march and photon_march_chunk.
//
// Step control near steep index changes. The octree knows how much n varies in a node, not how
// fast grad n changes, and a step of MinimumStep (1 voxel) across an interface one voxel wide
// samples grad n at two points. The gradient (central differences, trilinear) then integrates to
// much less than the index drop the step sees (trilinear n), and renormalising |v| to the smaller n
// shrinks the momentum along the interface: light within a degree or two of the critical angle
// leaks through (15-55% at 42-43 degrees through a one-voxel 1.5/1 interface). Two local error
// estimates, both zero where grad n is uniform, are compared with REFRACTA_STEP_TOLERANCE * n:
// the change of the gradient over the step, h max(|g(mid) - g(x)|, |g(end) - g(mid)|), and the
// drift of the invariant |v| = n before renormalisation; while either is larger the step is halved,
// at most REFRACTA_MAX_HALVINGS times (below MinimumStep).
inline void photon_advance(float3 x, float3 v, __global const uchar* octree,
  __global const float* extinction, __global const float* refractiveIndex,
  __global const float* gradient, int4 dims, float4 spacing, float3* x1, float3* v1)
{
  const float n0 = refracta_sample1(refractiveIndex, dims, refracta_to_voxel(x, spacing));
  const float3 dir = v / length(v);
#if REFRACTA_INTERFACES
  // Across a dielectric interface n jumps, and trilinear lookups blend the jump within a voxel of
  // it while grad n (which never holds the jump) is 0 there: only v's direction carries
  // information, so |v| is put back on the local n for the step control's test |v| = n.
  v = dir * n0;
#endif
  float h = photon_step(x, dir, octree, extinction, dims, spacing);
  const float3 g0 = refracta_sample3(gradient, dims, refracta_to_voxel(x, spacing));
  float3 v2;
  float n1;
  for (int halving = 0;; ++halving)
  {
    const float3 xm = x + (0.5f * h / n0) * v;
    const float3 vm = v + photon_bounded(0.5f * h * g0, n0);
    const float3 um = refracta_to_voxel(xm, spacing);
    const float nm = refracta_sample1(refractiveIndex, dims, um);
    const float3 gm = refracta_sample3(gradient, dims, um);
    *x1 = x + (h / nm) * vm;
    v2 = v + photon_bounded(h * gm, nm);
    const float3 u1 = refracta_to_voxel(*x1, spacing);
    n1 = refracta_sample1(refractiveIndex, dims, u1);
    if (halving >= REFRACTA_MAX_HALVINGS)
    {
      break;
    }
    const float3 g1 = refracta_sample3(gradient, dims, u1);
    const float error = fmax(h * fmax(length(gm - g0), length(g1 - gm)), fabs(length(v2) - n1));
    if (!(error > REFRACTA_STEP_TOLERANCE * n0))
    {
      break;
    }
    h *= 0.5f;
  }
  const float speed = length(v2);
  *v1 = speed > 1e-6f * n1 ? v2 * (n1 / speed) : dir * n1;
}

// One curved step of a photon at (x, v): advance, walk the chord's voxels (clipped to the box),
// and say how the photon ends: -1 it goes on, 2 escaped, 3 roulette, 4 step cap, 5 invalid state.
inline int photon_curved_step(photon_state* ps, float3* x, float3* v, int* steps, float3 lo,
  float3 hi, __global const uchar* octree, __global const float* extinction,
  __global const float* albedo, __global const float* refractiveIndex,
  __global const float* gradient, int4 dims, float4 spacing, volatile __global long* deposits)
{
  if (*steps >= REFRACTA_MAX_STEPS)
  {
    return PHOTON_COUNTER_STEP_CAP;
  }
  float3 x1, v1;
  photon_advance(*x, *v, octree, extinction, refractiveIndex, gradient, dims, spacing, &x1, &v1);
  ++*steps;
  if (!all(isfinite(x1)) || !all(isfinite(v1)))
  {
    return PHOTON_COUNTER_INVALID;
  }
  const bool inBox = all(x1 >= lo) && all(x1 <= hi);
  float tExit = 1.0f;
  if (!inBox)
  {
    float e0;
    float e1;
    tExit = refracta_intersect_box(*x, x1 - *x, lo, hi, &e0, &e1) ? clamp(e1, 0.0f, 1.0f) : 0.0f;
  }
#if REFRACTA_EXTINCTION
  photon_walk(ps, *x, x1, tExit, dims, spacing, extinction, albedo, deposits);
  if (ps->dead)
  {
    return PHOTON_COUNTER_ROULETTE;
  }
#endif
  if (!inBox)
  {
    return PHOTON_COUNTER_ESCAPED;
  }
  *x = x1;
  *v = v1;
  return -1;
}
#endif

