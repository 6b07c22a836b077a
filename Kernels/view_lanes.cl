// view_lanes.cl: the view pass on a CPU, eight rays per work-item in SIMD lanes.
// Prepend refracta_common.cl, view_pass.cl and view_pixel.cl (the general kernel's helpers);
// compiled only with -DREFRACTA_VIEW_LANES. Documentation/Reference.md, "Rendering" (the
// eight-lane kernel).
//
// What it computes is refracta_view_pass's image for the variants it serves (no surfaces; straight
// or curved rays, any medium, lighting volume, volume caustic, refractive index weight,
// environment, depth limit, with or without empty-space skipping): each ray takes the same steps
// at the same positions (curved rays: the same Stormer-Verlet steps, box clipping and exit
// direction) and evaluates the medium and its sources with the general kernel's own function
// (refracta_view_step_medium) and the same trilinear samples, with the same exact step
// integration, cutoff, step cap, depth limit and background; the image differs from the general
// kernel's by float rounding only (test RefractaRendering.ViewPassLaneMarching).
//
// Why a kernel of its own: PoCL runs a work-group as a loop over its work-items and leaves it to
// LLVM's loop vectoriser to put them in SIMD lanes, which it cannot do for work-items whose march
// loops end at different steps: the general kernel runs one ray per core at a time in scalar code
// (about 200 instructions per step, its loads one after another). Here a work-item marches the
// eight neighbouring pixels pi = 8 g .. 8 g + 7 of a row in the lanes of float8 values: the
// stencils, the step integration, a curved ray's integrator and the rays' bookkeeping are
// computed once for eight rays, and the eight rays' loads are independent, so that the core
// overlaps their cache misses. The fields are still read and interpolated per lane, at the lane's
// stencil (for the packed grey medium of an emission-absorption volume with vload4s of its float4
// corners, else by refracta_view_step_medium and refracta_view_sample1/3); only the values are
// moved into the lanes. A curved ray's end-of-step samples of n and grad n are its next step's
// start-of-step samples (the general kernel reads the same point twice). A work-item runs until
// its last ray ends; rays that ended earlier are masked (their lanes compute but change
// nothing). Work-groups of 1 x 8 items cover 8 x 8 pixels, the general kernel's tile. The host
// uses this kernel on CPU devices only: a GPU already runs each ray in a lane of its own.

#ifdef REFRACTA_VIEW_LANES

#define REFRACTA_LANES_LANES 8

// A per-lane step for the eight lanes: MACRO(s0) .. MACRO(s7) (a vector component cannot be
// indexed by a variable in OpenCL C).
#define REFRACTA_LANES_FOR_LANES(MACRO)                                                           \
  MACRO(s0) MACRO(s1) MACRO(s2) MACRO(s3) MACRO(s4) MACRO(s5) MACRO(s6) MACRO(s7)

// The lanes' values of a per-lane vector: component C of NAMEs0 .. NAMEs7 as a float8.
#define REFRACTA_LANES_COMPONENT(NAME, C)                                                         \
  ((float8)(NAME##s0.C, NAME##s1.C, NAME##s2.C, NAME##s3.C, NAME##s4.C, NAME##s5.C, NAME##s6.C,    \
    NAME##s7.C))

// The trilinear stencils of eight lanes at voxel coordinates (ux, uy, uz): each lane's first
// corner, the offsets to the next corner along x, y, z (0 on a clamped edge) and the weights, as
// refracta_make_stencil computes them for one point.
typedef struct
{
  int8 base, offX, offY, offZ;
  float8 fx, fy, fz;
} refracta_lanes_stencil;

inline refracta_lanes_stencil refracta_lanes_make_stencil(
  float8 ux, float8 uy, float8 uz, int4 dims)
{
  const float8 cx = clamp(ux, (float8)(0.0f), (float8)((float)(dims.x - 1)));
  const float8 cy = clamp(uy, (float8)(0.0f), (float8)((float)(dims.y - 1)));
  const float8 cz = clamp(uz, (float8)(0.0f), (float8)((float)(dims.z - 1)));
  const int8 i0 = convert_int8(cx), j0 = convert_int8(cy), k0 = convert_int8(cz); // floor: >= 0
  const int strideY = dims.x, strideZ = dims.x * dims.y;
  refracta_lanes_stencil s;
  s.fx = cx - convert_float8(i0);
  s.fy = cy - convert_float8(j0);
  s.fz = cz - convert_float8(k0);
  s.base = i0 + strideY * j0 + strideZ * k0;
  s.offX = min(i0 + 1, dims.x - 1) - i0;
  s.offY = (min(j0 + 1, dims.y - 1) - j0) * strideY;
  s.offZ = (min(k0 + 1, dims.z - 1) - k0) * strideZ;
  return s;
}

// Lane L's stencil (L one of s0 .. s7) in the general kernel's form (refracta_view_stencil).
#define REFRACTA_LANES_VIEW_STENCIL(LS, L)                                                        \
  refracta_view_stencil_at((size_t)(LS).base.L, (size_t)(LS).offX.L, (size_t)(LS).offY.L,         \
    (size_t)(LS).offZ.L, (LS).fx.L, (LS).fy.L, (LS).fz.L)

// refracta_step_weight (view_pass.cl) for eight lanes: w = (1 - exp(-tau)) / tau by its series
// (REFRACTA_STEP_WEIGHT_SERIES) for tau <= 1/2 and with the library's exp and expm1 beyond (called
// only when a lane needs them), and the step's transmittance.
inline float8 refracta_lanes_step_weight(float8 tau, float8* stepTransmittance)
{
  const float8 t = -tau;
  REFRACTA_STEP_WEIGHT_SERIES(float8, t, w);
  float8 stepT = fma(t, w, (float8)(1.0f));
  const int8 thick = tau > 0.5f;
  if (any(thick))
  {
    w = select(w, -expm1(t) / tau, thick);
    stepT = select(stepT, exp(t), thick);
  }
  *stepTransmittance = stepT;
  return w;
}

#ifdef REFRACTA_CURVED
// grad n (and, with `withIndex`, n) at grid-local positions p of the lanes in `on`, each lane's
// samples as refracta_view_march reads them (refracta_sample3 / refracta_sample1: the same
// stencil and interpolation); other lanes get grad n = 0 and n = 1.
inline void refracta_lanes_index_fields(int8 on, float8 px, float8 py, float8 pz, int4 dims,
  float4 spacing, __global const float* gradient, __global const float* refractiveIndex,
  bool withIndex, float8* n, float8* gx, float8* gy, float8* gz)
{
  const refracta_lanes_stencil ls =
    refracta_lanes_make_stencil(px / spacing.x, py / spacing.y, pz / spacing.z, dims);
#define REFRACTA_LANES_INDEX(L)                                                                   \
  float3 g##L = (float3)(0.0f);                                                                    \
  float2 n##L = (float2)(1.0f);                                                                    \
  if (on.L)                                                                                        \
  {                                                                                                \
    const refracta_view_stencil st = REFRACTA_LANES_VIEW_STENCIL(ls, L);                           \
    g##L = refracta_view_sample3(gradient, &st);                                                   \
    if (withIndex)                                                                                 \
    {                                                                                              \
      n##L.x = refracta_view_sample1(refractiveIndex, &st);                                        \
    }                                                                                              \
  }
  REFRACTA_LANES_FOR_LANES(REFRACTA_LANES_INDEX)
#undef REFRACTA_LANES_INDEX
  *n = REFRACTA_LANES_COMPONENT(n, x);
  *gx = REFRACTA_LANES_COMPONENT(g, x);
  *gy = REFRACTA_LANES_COMPONENT(g, y);
  *gz = REFRACTA_LANES_COMPONENT(g, z);
}

// The exit parameter of rays from (ox, oy, oz) along (dx, dy, dz) from the box [lo, hi]
// (refracta_intersect_box lane by lane): *hit where they meet it.
inline float8 refracta_lanes_box_exit(float8 ox, float8 oy, float8 oz, float8 dx, float8 dy,
  float8 dz, float3 lo, float3 hi, int8* hit)
{
  const float8 ix = 1.0f / dx, iy = 1.0f / dy, iz = 1.0f / dz;
  const float8 ax = (lo.x - ox) * ix, bx = (hi.x - ox) * ix;
  const float8 ay = (lo.y - oy) * iy, by = (hi.y - oy) * iy;
  const float8 az = (lo.z - oz) * iz, bz = (hi.z - oz) * iz;
  const float8 enter =
    fmax(fmax(fmin(ax, bx), fmin(ay, by)), fmax(fmin(az, bz), (float8)(0.0f)));
  const float8 leave = fmin(fmin(fmax(ax, bx), fmax(ay, by)), fmax(az, bz));
  *hit = leave >= enter;
  return leave;
}
#endif

#ifdef REFRACTA_SKIP
// Empty-space skipping for the lanes in `check` (view_skipping.cl), as refracta_view_march does
// it: from each lane's start point (sx, sy, sz) along its unit direction (dx, dy, dz), the run of
// empty macro cells ahead, clipped to `toExit` (the box exit) and the depth limit, is jumped over
// in whole steps (not counted as steps marched; *step and *travelled advance), and the next test
// waits until the ray has passed `recheck`. Returns the steps each lane jumped (0: none). Lane by
// lane in scalar code: a lane asks about once per macro cell it crosses.
inline int8 refracta_lanes_skip(int8 check, float8 sx, float8 sy, float8 sz, float8 dx, float8 dy,
  float8 dz, float8 toExit, float8 limit, float3 lo, float3 hi, float4 spacing, int4 cellDims,
  int4 activeLo, int4 activeHi, __global const uchar* occupancy, uint skipMask,
  float stepLength, int maxSteps, int8* step, float8* travelled, float8* nextCheck)
{
  const float3 cellExtent = (float)cellDims.w * spacing.xyz;
#define REFRACTA_LANES_JUMP(L)                                                                    \
  int jump##L = 0;                                                                                 \
  if (check.L)                                                                                     \
  {                                                                                                \
    float recheck;                                                                                 \
    const float run = refracta_empty_run((float3)(sx.L, sy.L, sz.L), (float3)(dx.L, dy.L, dz.L),  \
      lo, hi, cellExtent, cellDims, activeLo, activeHi, occupancy, skipMask, &recheck);            \
    (*nextCheck).L = (*travelled).L + recheck;                                                     \
    const float clipped = fmin(run, fmin(toExit.L, limit.L - (*travelled).L));                     \
    jump##L = max(min((int)floor(clipped / stepLength), maxSteps - 1 - (*step).L), 0);             \
  }
  REFRACTA_LANES_FOR_LANES(REFRACTA_LANES_JUMP)
#undef REFRACTA_LANES_JUMP
  const int8 jumps = (int8)(jumps0, jumps1, jumps2, jumps3, jumps4, jumps5, jumps6, jumps7);
  *step += jumps;
  *travelled += convert_float8(jumps) * stepLength;
  return jumps;
}
#endif

// The kernel's arguments are refracta_view_pass's (REFRACTA_VIEW_KERNEL_PARAMS, view_pixel.cl);
// those of the effects this variant does not have are unused.
__kernel __attribute__((reqd_work_group_size(1, 8, 1))) void refracta_view_pass_lanes(
  REFRACTA_VIEW_KERNEL_PARAMS)
{
  const int firstPixel = REFRACTA_LANES_LANES * (int)get_global_id(0);
  const int pj = (int)get_global_id(1);
  if (firstPixel >= width || pj >= height)
  {
    return;
  }
  float3 lo, hi;
  refracta_domain(dims, spacing, &lo, &hi);

  // Each lane's ray, set up as the general kernel sets up its one ray; a lane past the image's
  // right edge or a ray that meets no medium gets zeros and is not marched.
  float t0s[REFRACTA_LANES_LANES], t1s[REFRACTA_LANES_LANES], limits[REFRACTA_LANES_LANES];
  float ux[REFRACTA_LANES_LANES], uy[REFRACTA_LANES_LANES], uz[REFRACTA_LANES_LANES];
  float dx[REFRACTA_LANES_LANES], dy[REFRACTA_LANES_LANES], dz[REFRACTA_LANES_LANES];
  float ex[REFRACTA_LANES_LANES], ey[REFRACTA_LANES_LANES], ez[REFRACTA_LANES_LANES];
  int marching[REFRACTA_LANES_LANES];
#ifdef REFRACTA_SKIP
  float ox[REFRACTA_LANES_LANES], oy[REFRACTA_LANES_LANES], oz[REFRACTA_LANES_LANES];
#endif
#ifdef REFRACTA_CURVED
  float n0s[REFRACTA_LANES_LANES]; // n at the entry point
#endif
  for (int l = 0; l < REFRACTA_LANES_LANES; ++l)
  {
    const int pi = min(firstPixel + l, width - 1);
#ifdef REFRACTA_HAS_DEPTH_LIMIT
    limits[l] = depthLimit[(size_t)pi + (size_t)width * (size_t)pj];
#else
    limits[l] = INFINITY;
#endif
    float3 origin, d;
    refracta_view_camera_ray(eye, camU, camV, camW,
      2.0f * ((float)pi + 0.5f) / (float)width - 1.0f,
      2.0f * ((float)pj + 0.5f) / (float)height - 1.0f, &origin, &d);
    float t0, t1;
    const bool marches = refracta_intersect_box(origin, d, lo, hi, &t0, &t1) && t0 < limits[l] &&
      firstPixel + l < width;
#ifdef REFRACTA_CURVED
    // Curved rays integrate their position from the entry point (grid-local, not voxels).
    const float3 u = marches ? origin + t0 * d : (float3)(0.0f);
    n0s[l] =
      marches ? refracta_sample1(refractiveIndex, dims, refracta_to_voxel(u, spacing)) : 1.0f;
    const float3 v = marches ? n0s[l] * d : d;
#else
    const float3 u = marches ? refracta_to_voxel(origin + t0 * d, spacing) : (float3)(0.0f);
    const float3 v = marches ? refracta_to_voxel(d, spacing) : (float3)(0.0f);
#endif
    marching[l] = marches ? -1 : 0;
#ifdef REFRACTA_SKIP
    ox[l] = origin.x;
    oy[l] = origin.y;
    oz[l] = origin.z;
#endif
    t0s[l] = marches ? t0 : 0.0f;
    t1s[l] = marches ? t1 : 0.0f;
    ux[l] = u.x;
    uy[l] = u.y;
    uz[l] = u.z;
    dx[l] = v.x;
    dy[l] = v.y;
    dz[l] = v.z;
    ex[l] = d.x;
    ey[l] = d.y;
    ez[l] = d.z;
  }
  const float8 t0 = vload8(0, t0s), t1 = vload8(0, t1s), limit = vload8(0, limits);
  const float8 dirX = vload8(0, ex), dirY = vload8(0, ey), dirZ = vload8(0, ez); // unit, local
#ifdef REFRACTA_CURVED
  // Each lane's position x (grid-local), v = n dx/ds and n (Stormer-Verlet, view_pass.cl), and the
  // direction it leaves the box in (its background).
  float8 posX = vload8(0, ux), posY = vload8(0, uy), posZ = vload8(0, uz);
  float8 velX = vload8(0, dx), velY = vload8(0, dy), velZ = vload8(0, dz);
  float8 index = vload8(0, n0s);
  float8 exitX = dirX, exitY = dirY, exitZ = dirZ;
  // grad n at each lane's position where known: a step's end is the next step's start, so its
  // samples there serve twice (the general kernel reads the same point again: the same values).
  float8 gradX = 0.0f, gradY = 0.0f, gradZ = 0.0f;
  int8 gradKnown = 0;
#else
  // Straight rays: the entry point and the direction in voxel coordinates.
  const float8 u0x = vload8(0, ux), u0y = vload8(0, uy), u0z = vload8(0, uz);
  const float8 dvx = vload8(0, dx), dvy = vload8(0, dy), dvz = vload8(0, dz);
#endif
  int8 alive = vload8(0, marching);
  // A ray that meets no medium sees the background unless opaque geometry stops it first.
  int8 seesBackground = alive | (limit == INFINITY);

  float8 radianceR = 0.0f, radianceG = 0.0f, radianceB = 0.0f;
  float8 transR = 1.0f, transG = 1.0f, transB = 1.0f; // the path's transmittance
  float8 travelled = t0;
  int8 count = 0;
  int8 step = 0; // each lane's step index s: lanes skip different numbers of steps
#ifdef REFRACTA_SKIP
  float8 nextCheck = t0; // no skip test before this path length (inside an occupied cell)
  const float8 originX = vload8(0, ox), originY = vload8(0, oy), originZ = vload8(0, oz);
#endif
  while (any(alive)) // every lane ends within maxSteps steps
  {
#ifdef REFRACTA_SKIP
    const int8 check = alive & (travelled >= nextCheck);
    if (any(check))
    {
#ifdef REFRACTA_CURVED
      // From the lane's position along v / |v| (rays are straight in empty cells: grad n = 0
      // there); a lane that jumps lands on that line, where n and grad n are read again.
      const float8 speed = sqrt(velX * velX + velY * velY + velZ * velZ);
      const float8 sdx = velX / speed, sdy = velY / speed, sdz = velZ / speed;
      int8 inBox;
      const float8 exit =
        refracta_lanes_box_exit(posX, posY, posZ, sdx, sdy, sdz, lo, hi, &inBox);
      const int8 jumps = refracta_lanes_skip(check, posX, posY, posZ, sdx, sdy, sdz,
        select((float8)(0.0f), fmax(exit, 0.0f), inBox), limit, lo, hi, spacing, cellDims,
        activeLo, activeHi, occupancy, skipMask, stepLength, maxSteps, &step, &travelled,
        &nextCheck);
      const int8 jumped = jumps > 0;
      if (any(jumped))
      {
        const float8 run = convert_float8(jumps) * stepLength;
        posX = select(posX, posX + run * sdx, jumped);
        posY = select(posY, posY + run * sdy, jumped);
        posZ = select(posZ, posZ + run * sdz, jumped);
        float8 landed, gx, gy, gz;
        refracta_lanes_index_fields(jumped, posX, posY, posZ, dims, spacing, gradient,
          refractiveIndex, true, &landed, &gx, &gy, &gz);
        index = select(index, landed, jumped);
        velX = select(velX, landed * sdx, jumped);
        velY = select(velY, landed * sdy, jumped);
        velZ = select(velZ, landed * sdz, jumped);
        gradX = select(gradX, gx, jumped);
        gradY = select(gradY, gy, jumped);
        gradZ = select(gradZ, gz, jumped);
        gradKnown |= jumped;
      }
#else
      // From the step's start on the straight line, up to the box exit.
      const float8 tS = t0 + convert_float8(step) * stepLength;
      refracta_lanes_skip(check, originX + tS * dirX, originY + tS * dirY, originZ + tS * dirZ,
        dirX, dirY, dirZ, fmax(t1 - tS, 0.0f), limit, lo, hi, spacing, cellDims, activeLo,
        activeHi, occupancy, skipMask, stepLength, maxSteps, &step, &travelled, &nextCheck);
#endif
    }
#endif
    // The general kernel's step (view_pass.cl, refracta_view_march), lane by lane.
#ifdef REFRACTA_CURVED
    // Stormer-Verlet in the optical parameter t, dt = ds / n, re-normalised to |v| = n.
    const int8 unknown = alive & ~gradKnown;
    float8 unused, gX, gY, gZ;
    if (any(unknown))
    {
      refracta_lanes_index_fields(unknown, posX, posY, posZ, dims, spacing, gradient,
        refractiveIndex, false, &unused, &gX, &gY, &gZ);
      gradX = select(gradX, gX, unknown);
      gradY = select(gradY, gY, unknown);
      gradZ = select(gradZ, gZ, unknown);
    }
    const float8 dt = stepLength / index;
    const float8 halfX = velX + 0.5f * dt * (index * gradX);
    const float8 halfY = velY + 0.5f * dt * (index * gradY);
    const float8 halfZ = velZ + 0.5f * dt * (index * gradZ);
    const float8 nextX = posX + dt * halfX, nextY = posY + dt * halfY, nextZ = posZ + dt * halfZ;
    float8 indexNext;
    refracta_lanes_index_fields(alive, nextX, nextY, nextZ, dims, spacing, gradient,
      refractiveIndex, true, &indexNext, &gX, &gY, &gZ);
    float8 velNextX = halfX + 0.5f * dt * (indexNext * gX);
    float8 velNextY = halfY + 0.5f * dt * (indexNext * gY);
    float8 velNextZ = halfZ + 0.5f * dt * (indexNext * gZ);
    const float8 speed = sqrt(velNextX * velNextX + velNextY * velNextY + velNextZ * velNextZ);
    const int8 moving = speed > 0.0f;
    const float8 rescale = indexNext / speed;
    velNextX = select(indexNext * dirX, velNextX * rescale, moving);
    velNextY = select(indexNext * dirY, velNextY * rescale, moving);
    velNextZ = select(indexNext * dirZ, velNextZ * rescale, moving);
    const float8 stepX = nextX - posX, stepY = nextY - posY, stepZ = nextZ - posZ;
    float8 len = sqrt(stepX * stepX + stepY * stepY + stepZ * stepZ);
    const int8 hasLength = len > 0.0f;
    const float8 chordX = select(dirX, stepX / len, hasLength);
    const float8 chordY = select(dirY, stepY / len, hasLength);
    const float8 chordZ = select(dirZ, stepZ / len, hasLength);
    // Clip the chord to the box: the exit point is where the ray leaves the medium.
    const int8 leaves = (nextX < lo.x) | (nextY < lo.y) | (nextZ < lo.z) | (nextX > hi.x) |
      (nextY > hi.y) | (nextZ > hi.z);
    if (any(leaves & alive))
    {
      int8 hit;
      const float8 exit =
        refracta_lanes_box_exit(posX, posY, posZ, chordX, chordY, chordZ, lo, hi, &hit);
      len = select(len, select((float8)(0.0f), clamp(exit, 0.0f, len), hit), leaves);
    }
    const int8 blocked = travelled + len >= limit;
    len = select(len, fmax(limit - travelled, 0.0f), blocked);
    const float8 halfLen = 0.5f * len;
    const float8 mx = (posX + halfLen * chordX) / spacing.x;
    const float8 my = (posY + halfLen * chordY) / spacing.y;
    const float8 mz = (posZ + halfLen * chordZ) / spacing.z;
#else
    const float8 along = convert_float8(step) * stepLength;
    const float8 tA = t0 + along;
    const float8 tB = fmin(tA + stepLength, t1);
    const int8 leaves = tB >= t1;
    float8 len = fmax(tB - tA, 0.0f);
    const int8 blocked = travelled + len >= limit;
    len = select(len, fmax(limit - travelled, 0.0f), blocked);
    const float8 a = along + 0.5f * len;
    const float8 mx = fma(a, dvx, u0x), my = fma(a, dvy, u0y), mz = fma(a, dvz, u0z);
    const float8 chordX = dirX, chordY = dirY, chordZ = dirZ;
#endif
    const refracta_lanes_stencil ls = refracta_lanes_make_stencil(mx, my, mz, dims);
#if defined(REFRACTA_PACKED_MEDIUM) && !defined(REFRACTA_HAS_SINGLE) &&                         \
  !defined(REFRACTA_HAS_MULTIPLE) && !defined(REFRACTA_INDEX_WEIGHT)
    // Emission and absorption only: each lane's eight corners of (sigma, emission RGB),
    // interpolated as refracta_view_sample4 (the lanes of rays that ended read clamped corners).
#define REFRACTA_LANES_SAMPLE(L)                                                                  \
  float4 m##L;                                                                                     \
  {                                                                                                \
    const int c = ls.base.L, ox = ls.offX.L, oy = ls.offY.L, oz = ls.offZ.L;                       \
    const float fx = ls.fx.L;                                                                      \
    const float4 c00 = mix(vload4(c, extinction), vload4(c + ox, extinction), fx);                 \
    const float4 c10 = mix(vload4(c + oy, extinction), vload4(c + ox + oy, extinction), fx);       \
    const float4 c01 = mix(vload4(c + oz, extinction), vload4(c + ox + oz, extinction), fx);       \
    const float4 c11 =                                                                             \
      mix(vload4(c + oy + oz, extinction), vload4(c + ox + oy + oz, extinction), fx);              \
    m##L = mix(mix(c00, c10, ls.fy.L), mix(c01, c11, ls.fy.L), ls.fz.L);                           \
  }
    REFRACTA_LANES_FOR_LANES(REFRACTA_LANES_SAMPLE)
#undef REFRACTA_LANES_SAMPLE
    const float8 sigmaR = REFRACTA_LANES_COMPONENT(m, x);
    const float8 sigmaG = sigmaR, sigmaB = sigmaR;
    float8 qR = REFRACTA_LANES_COMPONENT(m, y);
    float8 qG = REFRACTA_LANES_COMPONENT(m, z);
    float8 qB = REFRACTA_LANES_COMPONENT(m, w);
#ifdef REFRACTA_SOURCE_SCALE
    qR *= REFRACTA_SOURCE_SCALE;
    qG *= REFRACTA_SOURCE_SCALE;
    qB *= REFRACTA_SOURCE_SCALE;
#endif
#else
    // Any other medium: each marching lane evaluates the step as the general kernel does, with
    // its own stencil (refracta_view_step_medium and the 1 / n^2 weight); ended lanes read nothing.
#define REFRACTA_LANES_MEDIUM(L)                                                                  \
  float3 sigma##L = (float3)(0.0f), q##L = (float3)(0.0f);                                         \
  if (alive.L)                                                                                     \
  {                                                                                                \
    const refracta_view_stencil st = REFRACTA_LANES_VIEW_STENCIL(ls, L);                           \
    const float3 d = (float3)(chordX.L, chordY.L, chordZ.L);                                       \
    float3 emitted;                                                                                \
    q##L = refracta_view_step_medium(&st, (float3)(mx.L, my.L, mz.L),                              \
             refracta_to_voxel(len.L * d, spacing), d, REFRACTA_VIEW_MEDIUM_ARGS, &sigma##L,       \
             &emitted) *                                                                           \
      refracta_view_source_weight(&st, refractiveIndex);                                           \
  }
    REFRACTA_LANES_FOR_LANES(REFRACTA_LANES_MEDIUM)
#undef REFRACTA_LANES_MEDIUM
    const float8 sigmaR = REFRACTA_LANES_COMPONENT(sigma, x);
    const float8 sigmaG = REFRACTA_LANES_COMPONENT(sigma, y);
    const float8 sigmaB = REFRACTA_LANES_COMPONENT(sigma, z);
    const float8 qR = REFRACTA_LANES_COMPONENT(q, x);
    const float8 qG = REFRACTA_LANES_COMPONENT(q, y);
    const float8 qB = REFRACTA_LANES_COMPONENT(q, z);
#endif
    // refracta_integrate_step (view_pass.cl) per channel, once where every lane's extinction is
    // grey; lanes that ended add nothing and keep their transmittance.
    float8 stepR, stepG, stepB;
    const float8 wR = refracta_lanes_step_weight(sigmaR * len, &stepR);
    float8 wG = wR, wB = wR;
    stepG = stepB = stepR;
    if (!all((sigmaR == sigmaG) & (sigmaG == sigmaB)))
    {
      wG = refracta_lanes_step_weight(sigmaG * len, &stepG);
      wB = refracta_lanes_step_weight(sigmaB * len, &stepB);
    }
    radianceR = select(radianceR, radianceR + transR * qR * (len * wR), alive);
    radianceG = select(radianceG, radianceG + transG * qG * (len * wG), alive);
    radianceB = select(radianceB, radianceB + transB * qB * (len * wB), alive);
    transR = select(transR, transR * stepR, alive);
    transG = select(transG, transG * stepG, alive);
    transB = select(transB, transB * stepB, alive);
    travelled = select(travelled, travelled + len, alive);
    count -= alive; // true is -1
    // The general kernel's ends: the box exit (sees the background), the depth limit, the cutoff
    // and the step cap (see nothing behind).
    const int8 opaque = fmax(transR, fmax(transG, transB)) < cutoff;
    const int8 capped = step + 1 == maxSteps;
    ++step;
    const int8 sees = ~(blocked | (~leaves & (opaque | capped)));
    seesBackground = select(seesBackground, sees, alive);
#ifdef REFRACTA_CURVED
    // A ray that leaves the box sees the background in the direction of its last velocity; one
    // that goes on moves to the step's end.
    const int8 exits = alive & leaves & ~blocked;
    if (any(exits))
    {
      const float8 inverse = rsqrt(velNextX * velNextX + velNextY * velNextY + velNextZ * velNextZ);
      exitX = select(exitX, velNextX * inverse, exits);
      exitY = select(exitY, velNextY * inverse, exits);
      exitZ = select(exitZ, velNextZ * inverse, exits);
    }
    posX = select(posX, nextX, alive);
    posY = select(posY, nextY, alive);
    posZ = select(posZ, nextZ, alive);
    velX = select(velX, velNextX, alive);
    velY = select(velY, velNextY, alive);
    velZ = select(velZ, velNextZ, alive);
    index = select(index, indexNext, alive);
    gradX = select(gradX, gX, alive);
    gradY = select(gradY, gY, alive);
    gradZ = select(gradZ, gZ, alive);
    gradKnown = alive;
#endif
    alive &= ~(blocked | leaves | opaque | capped);
  }

  float rs[REFRACTA_LANES_LANES], gs[REFRACTA_LANES_LANES], bs[REFRACTA_LANES_LANES];
  float trs[REFRACTA_LANES_LANES], tgs[REFRACTA_LANES_LANES], tbs[REFRACTA_LANES_LANES];
  int counts[REFRACTA_LANES_LANES], sees[REFRACTA_LANES_LANES];
  vstore8(radianceR, 0, rs);
  vstore8(radianceG, 0, gs);
  vstore8(radianceB, 0, bs);
  vstore8(transR, 0, trs);
  vstore8(transG, 0, tgs);
  vstore8(transB, 0, tbs);
  vstore8(count, 0, counts);
  // Opaque geometry ends a ray that left the box too: the background shows only without it.
  vstore8(seesBackground & (limit == INFINITY), 0, sees);
#ifdef REFRACTA_CURVED
  vstore8(exitX, 0, ex);
  vstore8(exitY, 0, ey);
  vstore8(exitZ, 0, ez);
#endif
  for (int l = 0; l < REFRACTA_LANES_LANES && firstPixel + l < width; ++l)
  {
    const int pi = firstPixel + l;
    const size_t pixel = (size_t)pi + (size_t)width * (size_t)pj;
    const float3 transmittance = (float3)(trs[l], tgs[l], tbs[l]);
    float3 radianceSum = (float3)(rs[l], gs[l], bs[l]);
    float3 seen = (float3)(0.0f);
    if (sees[l]) // in the direction the ray left the box in (or its own, when it missed it)
    {
      seen = transmittance *
        refracta_background((float3)(ex[l], ey[l], ez[l]), background, environment, envSize,
          envRight, envUp, envFront);
      radianceSum += seen;
    }
    // As refracta_view_pass writes its pixel.
    const float alpha = clamp(
      1.0f - (transmittance.x + transmittance.y + transmittance.z) * (1.0f / 3.0f), 0.0f, 1.0f);
    surfaceDepthOut[pixel] = INFINITY;
    vstore4((float4)(radianceSum, alpha), pixel, hdr);
    steps[pixel] = (uint)counts[l];
    vstore4((float4)(transmittance, 0.0f), pixel, transmittanceOut);
    vstore4((float4)(seen, 0.0f), pixel, backgroundOut);
  }
}

#endif
