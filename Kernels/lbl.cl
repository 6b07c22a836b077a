// lbl.cl: Lattice-Boltzmann lighting (Geist et al. 2004; Bernabei et al. section III-C), the
// multiple-scattering pass of Refracta. Prepend refracta_common.cl.
//
// State. f_i(r) (per RGB channel) is the power per unit volume travelling along lattice
// direction c_i that is about to cross voxel r. It is stored planar:
// f[(i * 3 + ch) * N + v], v = x + nx (y + ny z), N the number of voxels, so that a work-group of
// one x-row reads and writes contiguous memory.
//
// One lattice step (collision in voxel r, then streaming to r + c_i), per channel, with
// T_i = exp(-sigma_t * len_i) the probability of crossing the voxel uncollided along c_i
// (len_i = |c_i * spacing|), a the albedo and g the Henyey-Greenstein anisotropy:
//   out_i = T_i f_i                                   uncollided, keeps its direction
//         + a (1 - T_i) g+ f_i                        forward part of the scattering (g > 0)
//         + a (1 - T_opp(i)) g- f_opp(i)              backward part of the scattering (g < 0)
//         + w_i a (1 - |g|) sum_j (1 - T_j) f_j      isotropic part, w_i = 1 / Q
//         + q_i                                       source: S1 w_src,i (scattered out of the beam)
//   absorbed = (1 - a) sum_j (1 - T_j) f_j
// so sum_i out_i = sum_j f_j - absorbed + sum_i q_i exactly (column sums of the collision matrix
// are T + a (1 - T) = 1 - absorbed fraction). The paper's Theta matrix (eq. 5) routes the absorbed
// fraction into a rest density f_0 that is re-emitted isotropically one step later: it conserves
// f_0 + sum f_i, i.e. turns absorption into delayed scattering. Here the absorbed power leaves the
// lattice. The exponential T_i (instead of the paper's 1 - sigma_t) keeps every weight in [0, 1]
// for any optical depth per voxel; to first order in sigma_t len the two agree.
// Then out_i goes to f_i(r + c_i). Leaving the grid: vacuum (REFRACTA_LBL_BOUNDARY 0: the power escapes)
// or mirror (REFRACTA_LBL_BOUNDARY 1: it comes back into f_opp(i)(r)).
//
// Build options (-D): REFRACTA_LBL_Q (6 or 18 directions), REFRACTA_LBL_SX, _SY, _SZ (the grid's spacing
// over its largest, for the directions' unit vectors in the grid's frame), REFRACTA_LBL_NCLASS (number of distinct step lengths),
// REFRACTA_LBL_CLASSES (brace list: the length class of each direction), REFRACTA_LBL_BOUNDARY (0 vacuum,
// 1 mirror), REFRACTA_LBL_SOURCE_PHASE (0: the source is isotropic; 1: it is distributed over the
// directions by the HG phase function around the source direction), and for the blocked kernels
// REFRACTA_LBL_B (block edge b) and REFRACTA_LBL_SUBSTEPS (lattice steps per interface exchange, a power of two).
//
// Coefficients: coef[(c * 3 + ch) * N + v] = T for length class c; coef[(REFRACTA_LBL_NCLASS * 3 + ch) *
// N + v] = albedo; coef[(REFRACTA_LBL_NCLASS * 3 + 3) * N + v] = g. Source: src[ch * N + v] = S1 (power per
// unit volume per step), and with REFRACTA_LBL_SOURCE_PHASE src[(3 + a) * N + v] = the mean direction.

#ifndef REFRACTA_LBL_Q
#define REFRACTA_LBL_Q 6
#endif
#ifndef REFRACTA_LBL_NCLASS
#define REFRACTA_LBL_NCLASS 1
#endif
#ifndef REFRACTA_LBL_CLASSES
#define REFRACTA_LBL_CLASSES { 0, 0, 0, 0, 0, 0 }
#endif
#ifndef REFRACTA_LBL_BOUNDARY
#define REFRACTA_LBL_BOUNDARY 0
#endif
#ifndef REFRACTA_LBL_SOURCE_PHASE
#define REFRACTA_LBL_SOURCE_PHASE 0
#endif
#ifndef REFRACTA_LBL_SX
#define REFRACTA_LBL_SX 1.0f
#define REFRACTA_LBL_SY 1.0f
#define REFRACTA_LBL_SZ 1.0f
#endif

// Directions come in opposite pairs (2k, 2k + 1), so opp(i) = i ^ 1.
__constant int lbl_cx[18] = { 1, -1, 0, 0, 0, 0, 1, -1, 1, -1, 1, -1, 1, -1, 0, 0, 0, 0 };
__constant int lbl_cy[18] = { 0, 0, 1, -1, 0, 0, 1, -1, -1, 1, 0, 0, 0, 0, 1, -1, 1, -1 };
__constant int lbl_cz[18] = { 0, 0, 0, 0, 1, -1, 0, 0, 0, 0, 1, -1, -1, 1, 1, -1, -1, 1 };
__constant int lbl_class[REFRACTA_LBL_Q] = REFRACTA_LBL_CLASSES;

// Lattice direction i's unit vector in the grid's frame (c_i scaled by the spacing), as scalars:
// constants once the loop over i is unrolled.
#define LBL_EX(i) (lbl_cx[i] * REFRACTA_LBL_SX * lbl_inverse_length(i))
#define LBL_EY(i) (lbl_cy[i] * REFRACTA_LBL_SY * lbl_inverse_length(i))
#define LBL_EZ(i) (lbl_cz[i] * REFRACTA_LBL_SZ * lbl_inverse_length(i))
__attribute__((always_inline)) inline float lbl_inverse_length(int i)
{
  const float x = lbl_cx[i] * REFRACTA_LBL_SX, y = lbl_cy[i] * REFRACTA_LBL_SY,
              z = lbl_cz[i] * REFRACTA_LBL_SZ;
  return rsqrt(x * x + y * y + z * z);
}

// Number of voxels of a grid of dims (x, y, z).
inline size_t lbl_voxels(int4 dims)
{
  return (size_t)dims.x * (size_t)dims.y * (size_t)dims.z;
}

#define LBL_COEF_ALBEDO (REFRACTA_LBL_NCLASS * 3)
#define LBL_COEF_G (REFRACTA_LBL_NCLASS * 3 + 3)

// How voxel v's source is spread over the directions: w_i = lbl_source_weight(i, shape), sum 1.
// With REFRACTA_LBL_SOURCE_PHASE the HG phase about the source's direction, normalised over the
// directions (uniform without a direction, |d| <= 1e-6), else uniform. lbl_step evaluates w_i
// where it uses it rather than keep Q of them live.
typedef struct
{
  float X, Y, Z; // the source's unit direction in the grid's frame (0 without a direction)
  float G;       // the voxel's anisotropy
  float Scale;   // 1 / the phase summed over the directions (0 without a direction)
  float Uniform; // 1 / Q without a direction, else 0
} lbl_source_shape;

// The HG phase from the source's direction into lattice direction i up to its constant factor
// (1 - g^2) / (4 pi), which the normalisation removes: d^-3/2 with d = 1 + g^2 - 2 g cos in the
// form without cancellation near g = 1 (refracta_hg_phase's), by one reciprocal square root.
__attribute__((always_inline)) inline float lbl_source_phase(int i, const lbl_source_shape* s)
{
  // cos between the source direction and lattice direction i's unit vector (grid frame).
  const float c = LBL_EX(i) * s->X + LBL_EY(i) * s->Y + LBL_EZ(i) * s->Z;
  const float g = s->G;
  const float d = g >= 0.0f ? (1.0f - g) * (1.0f - g) + 2.0f * g * (1.0f - c)
                            : (1.0f + g) * (1.0f + g) - 2.0f * g * (1.0f + c);
  // d's least value is (1 - |g|)^2 (cos = +-1; rounding of cos could take d below it); the
  // second floor keeps d^-3/2 and the sum of Q of them finite for |g| within a float of 1.
  const float least = fmax((1.0f - fabs(g)) * (1.0f - fabs(g)), 1e-20f);
  const float r = native_rsqrt(fmax(d, least));
  return r * r * r;
}

__attribute__((always_inline)) inline lbl_source_shape lbl_source_shape_at(
  __global const float* src, size_t n, size_t v, float g)
{
  lbl_source_shape s;
  s.X = s.Y = s.Z = 0.0f;
  s.G = g;
  s.Scale = 0.0f;
  s.Uniform = 1.0f / (float)REFRACTA_LBL_Q;
#if REFRACTA_LBL_SOURCE_PHASE
  // Scalar arithmetic and no branch (no float3 builtins, whose vector results, and no early
  // return, which keep PoCL from vectorising the work-item loop).
  const float dx = src[3 * n + v], dy = src[4 * n + v], dz = src[5 * n + v];
  const float len = sqrt(dx * dx + dy * dy + dz * dz);
  const bool directed = len > 1e-6f;
  const float inv = directed ? 1.0f / len : 0.0f;
  s.X = dx * inv;
  s.Y = dy * inv;
  s.Z = dz * inv;
  float sum = 0.0f;
  #pragma unroll
  for (int i = 0; i < REFRACTA_LBL_Q; ++i)
  {
    sum += lbl_source_phase(i, &s);
  }
  s.Scale = directed ? 1.0f / sum : 0.0f;
  s.Uniform = directed ? 0.0f : s.Uniform;
#endif
  return s;
}

__attribute__((always_inline)) inline float lbl_source_weight(int i, const lbl_source_shape* s)
{
#if REFRACTA_LBL_SOURCE_PHASE
  return lbl_source_phase(i, s) * s->Scale + s->Uniform;
#else
  return s->Uniform;
#endif
}

// The weights of lbl_source_weight as an array (the blocked kernel's form).
__attribute__((always_inline)) inline void lbl_source_weights(
  __global const float* src, size_t n, size_t v, float g, float* w)
{
  const lbl_source_shape shape = lbl_source_shape_at(src, n, v, g);
  #pragma unroll
  for (int i = 0; i < REFRACTA_LBL_Q; ++i)
  {
    w[i] = lbl_source_weight(i, &shape);
  }
}

// x / Q correctly rounded. OpenCL lets '/' be 2.5 ulp off and NVIDIA's driver uses that: the
// isotropic share then errs one way in every voxel and step, and a lattice without absorption
// drifted by 1e-5 in 1000 steps. The product by the rounded 1/Q errs one way too (3e-8), so one
// Newton correction with the exact residual (fma) gives the rounded quotient.
__attribute__((always_inline)) inline float lbl_divide_by_q(float x)
{
  const float inverse = 1.0f / (float)REFRACTA_LBL_Q;
  const float q = x * inverse;
  return fma(fma(-q, (float)REFRACTA_LBL_Q, x), inverse, q);
}

// The isotropic share of the collision, w_i a (1 - |g|) sum_j (1 - T_j) f_j (see the header), from
// the collided sum.
__attribute__((always_inline)) inline float lbl_isotropic_share(float a, float g, float collided)
{
  return lbl_divide_by_q(a * (1.0f - fmax(g, 0.0f) - fmax(-g, 0.0f)) * collided);
}

// out_i of the collision (see the header) from f_i, f_opp(i), their T, the isotropic share and
// the source q w_i.
__attribute__((always_inline)) inline float lbl_collide_direction(float fi, float fo, float ti,
  float to, float a, float g, float iso, float qw)
{
  return ti * fi + a * fmax(g, 0.0f) * ((1.0f - ti) * fi) + a * fmax(-g, 0.0f) * ((1.0f - to) * fo) +
    iso + qw;
}

// Collision of one channel: fin -> out (see the header).
__attribute__((always_inline)) inline void lbl_collide(
  const float* fin, float* out, const float* t, float a, float g, float q, const float* wsrc)
{
  float sum = 0.0f;
  #pragma unroll
  for (int j = 0; j < REFRACTA_LBL_Q; ++j)
  {
    sum += (1.0f - t[lbl_class[j]]) * fin[j];
  }
  const float iso = lbl_isotropic_share(a, g, sum);
  #pragma unroll
  for (int i = 0; i < REFRACTA_LBL_Q; ++i)
  {
    out[i] = lbl_collide_direction(
      fin[i], fin[i ^ 1], t[lbl_class[i]], t[lbl_class[i ^ 1]], a, g, iso, q * wsrc[i]);
  }
}

// ---------------------------------------------------------------------------------------------
// Global (unblocked) step: one work-item per voxel, global (nx, ny, nz), local one x-row.
// fnext must start zeroed: entries nothing streams into (from outside the grid) stay zero; it has
// one scratch float past its Q * 3 * N state values.
__kernel void lbl_step(__global const float* fcur, __global float* fnext,
  __global const float* coef, __global const float* src, const int4 dims)
{
  const int x = get_global_id(0);
  const int y = get_global_id(1);
  const int z = get_global_id(2);
  if (x >= dims.x || y >= dims.y || z >= dims.z)
  {
    return;
  }
  const size_t n = lbl_voxels(dims);
  const size_t v = refracta_voxel_index(dims, x, y, z);
  const float g = coef[LBL_COEF_G * n + v];
  const lbl_source_shape shape = lbl_source_shape_at(src, n, v, g);
  // Two passes over the directions, the second reading f_i again (from the cache) and evaluating
  // w_i where it is used rather than keeping Q values of each live: measured 1.2x (D3Q18) to 1.3x
  // (D3Q6) faster a step than the one-pass form on PoCL, 2 cores (Benchmarks.md, "The lattice's
  // step"). First the collided sums of the three channels.
  float t[3][REFRACTA_LBL_NCLASS], a[3], iso[3];
  #pragma unroll
  for (int ch = 0; ch < 3; ++ch)
  {
    #pragma unroll
    for (int c = 0; c < REFRACTA_LBL_NCLASS; ++c)
    {
      t[ch][c] = coef[(c * 3 + ch) * n + v];
    }
    a[ch] = coef[(LBL_COEF_ALBEDO + ch) * n + v];
    float sum = 0.0f;
    #pragma unroll
    for (int j = 0; j < REFRACTA_LBL_Q; ++j)
    {
      sum += (1.0f - t[ch][lbl_class[j]]) * fcur[(size_t)(j * 3 + ch) * n + v];
    }
    iso[ch] = lbl_isotropic_share(a[ch], g, sum);
  }
  // Then each direction's three channels, streamed to r + c_i. Branch-free stores (so that the
  // work-item loop vectorises): a packet leaving the grid is written to its mirror entry
  // (REFRACTA_LBL_BOUNDARY 1) or to a scratch float past the state's end.
  #pragma unroll
  for (int i = 0; i < REFRACTA_LBL_Q; ++i)
  {
    const float w = lbl_source_weight(i, &shape);
    const int tx = x + lbl_cx[i], ty = y + lbl_cy[i], tz = z + lbl_cz[i];
    const bool inGrid = tx >= 0 && ty >= 0 && tz >= 0 && tx < dims.x && ty < dims.y && tz < dims.z;
    const long offset =
      (long)lbl_cx[i] + (long)dims.x * ((long)lbl_cy[i] + (long)dims.y * lbl_cz[i]);
    #pragma unroll
    for (int ch = 0; ch < 3; ++ch)
    {
      const float out = lbl_collide_direction(fcur[(size_t)(i * 3 + ch) * n + v],
        fcur[(size_t)((i ^ 1) * 3 + ch) * n + v], t[ch][lbl_class[i]], t[ch][lbl_class[i ^ 1]],
        a[ch], g, iso[ch], src[ch * n + v] * w);
      const size_t inside = (size_t)(i * 3 + ch) * n + v + (size_t)offset;
#if REFRACTA_LBL_BOUNDARY == 1
      const size_t outside = (size_t)((i ^ 1) * 3 + ch) * n + v;
#else
      const size_t outside = (size_t)REFRACTA_LBL_Q * 3 * n;
#endif
      fnext[inGrid ? inside : outside] = out;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Blocked steps (Bernabei et al. III-C, D3Q6 only): the grid is cut into blocks of REFRACTA_LBL_B^3
// voxels; one work-group of REFRACTA_LBL_B^3 work-items per block iterates REFRACTA_LBL_SUBSTEPS lattice steps in
// local memory. Density streaming out of the block is summed over the substeps per face voxel and
// written to the block's own outgoing interface (6 faces x b^2 x RGB); density streaming in is
// read from the neighbours' outgoing interfaces of the previous launch and injected as 1/m of it
// at each of the m substeps (m a power of two, so the split is exact and energy is conserved to
// the last bit). The host swaps the two interface buffers between launches (the alternation of
// Fig. 5): a launch reads one and writes the other, so no location is read and written by
// concurrent work-groups. With REFRACTA_LBL_SUBSTEPS = 1 this is step for step the global update; with
// m > 1 the transient differs, but the fixed point (the steady state) is the same: at the global
// fixed point each face passes the same flux at every substep, and m of them summed, then split
// by m, reproduces it.
#ifdef REFRACTA_LBL_B
#define LBL_B3 (REFRACTA_LBL_B * REFRACTA_LBL_B * REFRACTA_LBL_B)
#define LBL_INV_SUBSTEPS (1.0f / (float)REFRACTA_LBL_SUBSTEPS)

// Position of local voxel (lx, ly, lz) on the block face crossed by direction i.
inline int lbl_face_pos(int i, int lx, int ly, int lz)
{
  const int axis = i >> 1;
  return axis == 0 ? ly + REFRACTA_LBL_B * lz : (axis == 1 ? lx + REFRACTA_LBL_B * lz : lx + REFRACTA_LBL_B * ly);
}

// Linear index of the block that entry i of voxel (x, y, z) streams in from when that is another
// block inside the grid; -1 when it streams from the same block or from outside the grid.
inline int lbl_inbound_block(int i, int x, int y, int z, int4 dims, int4 nblocks)
{
  const int sx = x - lbl_cx[i], sy = y - lbl_cy[i], sz = z - lbl_cz[i];
  if (sx < 0 || sy < 0 || sz < 0 || sx >= dims.x || sy >= dims.y || sz >= dims.z)
  {
    return -1;
  }
  const int bx = sx / REFRACTA_LBL_B, by = sy / REFRACTA_LBL_B, bz = sz / REFRACTA_LBL_B;
  if (bx == x / REFRACTA_LBL_B && by == y / REFRACTA_LBL_B && bz == z / REFRACTA_LBL_B)
  {
    return -1;
  }
  return bx + nblocks.x * (by + nblocks.y * bz);
}

// Work layout: global (nbx, nby, nbz) * REFRACTA_LBL_B, local (REFRACTA_LBL_B, REFRACTA_LBL_B, REFRACTA_LBL_B).
__kernel __attribute__((reqd_work_group_size(REFRACTA_LBL_B, REFRACTA_LBL_B, REFRACTA_LBL_B))) void lbl_block(
  __global float* state, __global const float* coef, __global const float* src,
  __global const float* ifaceIn, __global float* ifaceOut, const int4 dims, const int4 nblocks)
{
  __local float bufA[REFRACTA_LBL_Q * 3 * LBL_B3];
  __local float bufB[REFRACTA_LBL_Q * 3 * LBL_B3];
  const int lx = get_local_id(0), ly = get_local_id(1), lz = get_local_id(2);
  const int bx = get_group_id(0), by = get_group_id(1), bz = get_group_id(2);
  const int x = bx * REFRACTA_LBL_B + lx, y = by * REFRACTA_LBL_B + ly, z = bz * REFRACTA_LBL_B + lz;
  const bool active = x < dims.x && y < dims.y && z < dims.z;
  const int lid = lx + REFRACTA_LBL_B * (ly + REFRACTA_LBL_B * lz);
  const int blk = bx + nblocks.x * (by + nblocks.y * bz);
  const size_t n = lbl_voxels(dims);
  const size_t v = active ? refracta_voxel_index(dims, x, y, z) : 0;

  float t[3][REFRACTA_LBL_NCLASS], a[3], q[3], wsrc[REFRACTA_LBL_Q];
  float g = 0.0f;
  float inflow[REFRACTA_LBL_Q][3], outAcc[REFRACTA_LBL_Q][3];
  bool inbound[REFRACTA_LBL_Q];
  #pragma unroll
  for (int i = 0; i < REFRACTA_LBL_Q; ++i)
  {
    inbound[i] = false;
    #pragma unroll
    for (int ch = 0; ch < 3; ++ch)
    {
      inflow[i][ch] = 0.0f;
      outAcc[i][ch] = 0.0f;
      bufA[(i * 3 + ch) * LBL_B3 + lid] = active ? state[(i * 3 + ch) * n + v] : 0.0f;
      bufB[(i * 3 + ch) * LBL_B3 + lid] = 0.0f;
    }
  }
  if (active)
  {
    g = coef[LBL_COEF_G * n + v];
    lbl_source_weights(src, n, v, g, wsrc);
    #pragma unroll
    for (int ch = 0; ch < 3; ++ch)
    {
      #pragma unroll
      for (int c = 0; c < REFRACTA_LBL_NCLASS; ++c)
      {
        t[ch][c] = coef[(c * 3 + ch) * n + v];
      }
      a[ch] = coef[(LBL_COEF_ALBEDO + ch) * n + v];
      q[ch] = src[ch * n + v];
    }
    #pragma unroll
    for (int i = 0; i < REFRACTA_LBL_Q; ++i)
    {
      const int nb = lbl_inbound_block(i, x, y, z, dims, nblocks);
      if (nb >= 0)
      {
        inbound[i] = true;
        const size_t base = ((size_t)(nb * 6 + i) * REFRACTA_LBL_B * REFRACTA_LBL_B + lbl_face_pos(i, lx, ly, lz)) * 3;
        #pragma unroll
        for (int ch = 0; ch < 3; ++ch)
        {
          inflow[i][ch] = ifaceIn[base + ch] * LBL_INV_SUBSTEPS;
        }
      }
    }
  }
  barrier(CLK_LOCAL_MEM_FENCE);

  for (int s = 0; s < REFRACTA_LBL_SUBSTEPS; ++s)
  {
    __local float* cur = (s & 1) ? bufB : bufA;
    __local float* nxt = (s & 1) ? bufA : bufB;
    if (active)
    {
      #pragma unroll
      for (int ch = 0; ch < 3; ++ch)
      {
        float fin[REFRACTA_LBL_Q], out[REFRACTA_LBL_Q];
        #pragma unroll
        for (int i = 0; i < REFRACTA_LBL_Q; ++i)
        {
          // Entries streaming in from a neighbour block come from the interface, 1/m per substep.
          fin[i] = inbound[i] ? inflow[i][ch] : cur[(i * 3 + ch) * LBL_B3 + lid];
        }
        lbl_collide(fin, out, t[ch], a[ch], g, q[ch], wsrc);
        #pragma unroll
        for (int i = 0; i < REFRACTA_LBL_Q; ++i)
        {
          const int tx = x + lbl_cx[i], ty = y + lbl_cy[i], tz = z + lbl_cz[i];
          const int ux = lx + lbl_cx[i], uy = ly + lbl_cy[i], uz = lz + lbl_cz[i];
          if (tx < 0 || ty < 0 || tz < 0 || tx >= dims.x || ty >= dims.y || tz >= dims.z)
          {
#if REFRACTA_LBL_BOUNDARY == 1
            nxt[((i ^ 1) * 3 + ch) * LBL_B3 + lid] = out[i];
#endif
          }
          else if (ux < 0 || uy < 0 || uz < 0 || ux >= REFRACTA_LBL_B || uy >= REFRACTA_LBL_B || uz >= REFRACTA_LBL_B)
          {
            outAcc[i][ch] += out[i];
          }
          else
          {
            nxt[(i * 3 + ch) * LBL_B3 + ux + REFRACTA_LBL_B * (uy + REFRACTA_LBL_B * uz)] = out[i];
          }
        }
      }
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }

  if (active)
  {
    __local float* last = ((REFRACTA_LBL_SUBSTEPS - 1) & 1) ? bufA : bufB;
    #pragma unroll
    for (int i = 0; i < REFRACTA_LBL_Q; ++i)
    {
      #pragma unroll
      for (int ch = 0; ch < 3; ++ch)
      {
        // Entries fed by the interface are rewritten by lbl_block_state_interface.
        state[(i * 3 + ch) * n + v] = inbound[i] ? 0.0f : last[(i * 3 + ch) * LBL_B3 + lid];
      }
      const int tx = x + lbl_cx[i], ty = y + lbl_cy[i], tz = z + lbl_cz[i];
      const int ux = lx + lbl_cx[i], uy = ly + lbl_cy[i], uz = lz + lbl_cz[i];
      const bool inGrid = tx >= 0 && ty >= 0 && tz >= 0 && tx < dims.x && ty < dims.y && tz < dims.z;
      const bool inBlock = ux >= 0 && uy >= 0 && uz >= 0 && ux < REFRACTA_LBL_B && uy < REFRACTA_LBL_B && uz < REFRACTA_LBL_B;
      if (inGrid && !inBlock)
      {
        const size_t base = ((size_t)(blk * 6 + i) * REFRACTA_LBL_B * REFRACTA_LBL_B + lbl_face_pos(i, lx, ly, lz)) * 3;
        #pragma unroll
        for (int ch = 0; ch < 3; ++ch)
        {
          ifaceOut[base + ch] = outAcc[i][ch];
        }
      }
    }
  }
}

// Between the state's interface-fed entries and the interface the next launch reads, one
// work-item per voxel, global (nx, ny, nz):
// - toInterface 0, after a launch: each entry gets the density that will
//   stream in during the next substep (1/m of the interface), so that the state reads like a
//   global state (exactly the global state for m = 1);
// - toInterface 1, the inverse (the coarse start's seed): the interface is set so that each entry
//   receives its value in the state at each of the m substeps, for a state written in the global
//   layout, whose interface-fed entries lbl_block would otherwise ignore.
__kernel void lbl_block_state_interface(__global float* state, __global float* iface,
  const int4 dims, const int4 nblocks, const int toInterface)
{
  const int x = get_global_id(0), y = get_global_id(1), z = get_global_id(2);
  if (x >= dims.x || y >= dims.y || z >= dims.z)
  {
    return;
  }
  const size_t n = lbl_voxels(dims);
  const size_t v = refracta_voxel_index(dims, x, y, z);
  #pragma unroll
  for (int i = 0; i < REFRACTA_LBL_Q; ++i)
  {
    const int nb = lbl_inbound_block(i, x, y, z, dims, nblocks);
    if (nb >= 0)
    {
      const size_t base = ((size_t)(nb * 6 + i) * REFRACTA_LBL_B * REFRACTA_LBL_B +
                            lbl_face_pos(i, x % REFRACTA_LBL_B, y % REFRACTA_LBL_B, z % REFRACTA_LBL_B)) * 3;
      #pragma unroll
      for (int ch = 0; ch < 3; ++ch)
      {
        const size_t entry = (i * 3 + ch) * n + v;
        if (toInterface)
        {
          iface[base + ch] = state[entry] * (float)REFRACTA_LBL_SUBSTEPS;
        }
        else
        {
          state[entry] = iface[base + ch] * LBL_INV_SUBSTEPS;
        }
      }
    }
  }
}
#endif

// ---------------------------------------------------------------------------------------------
// Convergence probes: out[p * 3 + ch] = sum_i f_i at voxel probes[p]. One work-item per probe.
__kernel void lbl_probes(__global const float* state, __global const uint* probes,
  __global float* out, const uint count, const int4 dims)
{
  const uint p = get_global_id(0);
  if (p >= count)
  {
    return;
  }
  const size_t n = lbl_voxels(dims);
  const size_t v = probes[p];
  #pragma unroll
  for (int ch = 0; ch < 3; ++ch)
  {
    float sum = 0.0f;
    #pragma unroll
    for (int i = 0; i < REFRACTA_LBL_Q; ++i)
    {
      sum += state[(i * 3 + ch) * n + v];
    }
    out[p * 3 + ch] = sum;
  }
}

// The power of channel ch that collides in voxel v (of n) coming along direction i, (1 - T_i) f_i:
// what the read-outs below sum (the albedo's share of it scatters).
__attribute__((always_inline)) inline float lbl_collided(
  __global const float* state, __global const float* coef, size_t n, size_t v, int i, int ch)
{
  return (1.0f - coef[(lbl_class[i] * 3 + ch) * n + v]) * state[(i * 3 + ch) * n + v];
}

// The multiple-scattering source S_ms = sigma_s phi_ms: the power per unit volume that the diffuse
// field loses to scattering in each voxel, a sum_i (1 - T_i) f_i, interleaved RGB (a VTK array).
// One work-item per voxel, global (nx, ny, nz).
__kernel void lbl_scattered(
  __global const float* state, __global const float* coef, __global float* out, const int4 dims)
{
  const int x = get_global_id(0), y = get_global_id(1), z = get_global_id(2);
  if (x >= dims.x || y >= dims.y || z >= dims.z)
  {
    return;
  }
  const size_t n = lbl_voxels(dims);
  const size_t v = refracta_voxel_index(dims, x, y, z);
  #pragma unroll
  for (int ch = 0; ch < 3; ++ch)
  {
    float sum = 0.0f;
    #pragma unroll
    for (int i = 0; i < REFRACTA_LBL_Q; ++i)
    {
      sum += lbl_collided(state, coef, n, v, i, ch);
    }
    out[v * 3 + ch] = coef[(LBL_COEF_ALBEDO + ch) * n + v] * sum;
  }
}

// The direction of the multiple-scattering source (lbl_scattered): the net flux of the light
// being scattered over its scattered power, F / S = sum_i w_i e_i / sum_i w_i with w_i =
// a (1 - T_i) f_i summed over the channels and e_i lattice direction i's unit vector in the
// grid's frame, as 3 floats per voxel (a VTK array). Its length is the mean cosine of that light
// about F (0 isotropic, 1 collimated along a lattice direction); zero where nothing scatters.
// One work-item per voxel, global (nx, ny, nz).
__kernel void lbl_scattered_flux(
  __global const float* state, __global const float* coef, __global float* out, const int4 dims)
{
  const int x = get_global_id(0), y = get_global_id(1), z = get_global_id(2);
  if (x >= dims.x || y >= dims.y || z >= dims.z)
  {
    return;
  }
  const size_t n = lbl_voxels(dims);
  const size_t v = refracta_voxel_index(dims, x, y, z);
  float fx = 0.0f, fy = 0.0f, fz = 0.0f, total = 0.0f;
  #pragma unroll
  for (int ch = 0; ch < 3; ++ch)
  {
    const float a = coef[(LBL_COEF_ALBEDO + ch) * n + v];
    #pragma unroll
    for (int i = 0; i < REFRACTA_LBL_Q; ++i)
    {
      const float w = a * lbl_collided(state, coef, n, v, i, ch);
      fx += w * LBL_EX(i);
      fy += w * LBL_EY(i);
      fz += w * LBL_EZ(i);
      total += w;
    }
  }
  // Each component over the total (never larger than it): 1 / total would overflow for a total
  // below FLT_MIN (deep shadow), and 0 * inf is NaN.
  const bool some = total > 0.0f;
  out[3 * v] = some ? fx / total : 0.0f;
  out[3 * v + 1] = some ? fy / total : 0.0f;
  out[3 * v + 2] = some ? fz / total : 0.0f;
}

// Plain copy (the memory-bandwidth reference of the benchmark): b[i] = a[i], float4 per item.
__kernel void lbl_copy(__global const float4* a, __global float4* b, const ulong count)
{
  const size_t i = get_global_id(0);
  if (i < count)
  {
    b[i] = a[i];
  }
}

// The photon pass's fixed-point deposits (six cl_long per voxel: RGB power, then the direction
// sums) -> the LBL source planes:
// src[c * n + v] = S1 = radiance * radianceFactor, src[(3 + c) * n + v] = direction sums *
// directionFactor (unnormalised; the source weights normalise it). One work-item per voxel.
__kernel void lbl_source_from_fixed(__global const long* deposits, const float radianceFactor,
  const float directionFactor, __global float* src, const uint n)
{
  const size_t v = get_global_id(0);
  if (v >= n)
  {
    return;
  }
  for (int c = 0; c < 3; ++c)
  {
    src[c * (size_t)n + v] = (float)deposits[6 * v + c] * radianceFactor;
    src[(3 + c) * (size_t)n + v] = (float)deposits[6 * v + 3 + c] * directionFactor;
  }
}

// Point arrays on the device (the photon pass's kept output: 3 floats per voxel) -> the LBL
// source planes, the values unchanged: src[c * n + v] = s1[3 v + c], src[(3 + c) * n + v] =
// d1[3 v + c] (0 without a direction: hasDirection 0). One work-item per voxel.
__kernel void lbl_source_from_fields(__global const float* s1, __global const float* d1,
  const int hasDirection, __global float* src, const uint n)
{
  const size_t v = get_global_id(0);
  if (v >= n)
  {
    return;
  }
  for (int c = 0; c < 3; ++c)
  {
    src[c * (size_t)n + v] = s1[3 * v + c];
    src[(3 + c) * (size_t)n + v] = hasDirection ? d1[3 * v + c] : 0.0f;
  }
}

// a[i] += b[i] (one float each; the host adds the same way, so the sums are the host's bits).
__kernel void lbl_add(__global float* a, __global const float* b, const ulong count)
{
  const size_t i = get_global_id(0);
  if (i < count)
  {
    a[i] += b[i];
  }
}

// ---------------------------------------------------------------------------------------------
// Coarse start (vtkLatticeBoltzmannSolver::CoarseStart): the source restricted to a grid of half
// the resolution, and the coarse grid's steady state prolonged back as the fine grid's first
// state. A coarse voxel (cx, cy, cz) covers the fine voxels (2 cx + {0, 1}, ...) that exist.

// src planes (S1 RGB, then the direction sums when there are 6) -> the mean over the children.
// One work-item per coarse voxel, global (cnx, cny, cnz).
__kernel void lbl_restrict_source(__global const float* fine, __global float* coarse,
  const int4 fdims, const int4 cdims, const int planes)
{
  const int x = get_global_id(0), y = get_global_id(1), z = get_global_id(2);
  if (x >= cdims.x || y >= cdims.y || z >= cdims.z)
  {
    return;
  }
  const size_t nf = lbl_voxels(fdims);
  const size_t nc = lbl_voxels(cdims);
  const size_t vc = refracta_voxel_index(cdims, x, y, z);
  const int x1 = min(2 * x + 2, fdims.x), y1 = min(2 * y + 2, fdims.y), z1 = min(2 * z + 2, fdims.z);
  const float inverseCount = 1.0f / (float)((x1 - 2 * x) * (y1 - 2 * y) * (z1 - 2 * z));
  for (int p = 0; p < planes; ++p)
  {
    float sum = 0.0f;
    for (int fz = 2 * z; fz < z1; ++fz)
    {
      for (int fy = 2 * y; fy < y1; ++fy)
      {
        for (int fx = 2 * x; fx < x1; ++fx)
        {
          sum += fine[p * nf + refracta_voxel_index(fdims, fx, fy, fz)];
        }
      }
    }
    coarse[p * nc + vc] = sum * inverseCount;
  }
}

// Fine state from the coarse steady state: f_i = ratio * f_i(parent). In a homogeneous medium the
// steady state is sum_i f_i = sum_i q_i / ((1 - a) p) per voxel (the source per step over the
// absorption per step), so the exact ratio is p_coarse / p_fine (the collision probabilities of
// the two grids, from their coefficients: p = 1 - T); it tends to the step-length ratio
// (maxRatio, 2) for optically thin voxels and to 1 for thick ones, to which it is clamped (a
// vacuum voxel takes maxRatio: its density is a flux, and a coarse step lasts maxRatio fine ones).
// The parent's value is taken as it is (trilinear interpolation measured no fewer fine steps);
// so an entry that only the world outside a vacuum boundary streams into, which lbl_step never
// writes, stays zero: its parent's is zero too. One work-item per fine voxel, global (nx, ny, nz).
// With `correct` (the coarse correction of a warm start) the fine state instead keeps what it holds
// (the last light's steady state) and adds the change of the coarse steady state from
// `coarseBefore` (the last light's) to `coarse`, prolonged the same way: what the coarse grid
// resolves of the change (its slow, smooth part) is then paid for at the coarse level, and the
// fine detail of the last solution is kept; the sum is clamped at zero (a density is never
// negative; the fixed point does not depend on the start).
__kernel void lbl_prolong_state(__global const float* coarse, __global const float* coarseBefore,
  __global const float* coarseCoef, __global float* fine, __global const float* fineCoef,
  const int4 fdims, const int4 cdims, const float maxRatio, const int correct)
{
  const int x = get_global_id(0), y = get_global_id(1), z = get_global_id(2);
  if (x >= fdims.x || y >= fdims.y || z >= fdims.z)
  {
    return;
  }
  const size_t nf = lbl_voxels(fdims);
  const size_t nc = lbl_voxels(cdims);
  const size_t v = refracta_voxel_index(fdims, x, y, z);
  const size_t vc = refracta_voxel_index(cdims, x / 2, y / 2, z / 2);
  #pragma unroll
  for (int i = 0; i < REFRACTA_LBL_Q; ++i)
  {
    #pragma unroll
    for (int ch = 0; ch < 3; ++ch)
    {
      const size_t plane = (size_t)(lbl_class[i] * 3 + ch);
      const float pFine = 1.0f - fineCoef[plane * nf + v];
      const float pCoarse = 1.0f - coarseCoef[plane * nc + vc];
      const float ratio = pFine > 0.0f ? clamp(pCoarse / pFine, 1.0f, maxRatio) : maxRatio;
      const size_t c = (i * 3 + ch) * nc + vc;
      const size_t f = (i * 3 + ch) * nf + v;
      fine[f] = correct ? fmax(0.0f, fine[f] + ratio * (coarse[c] - coarseBefore[c]))
                        : ratio * coarse[c];
    }
  }
}
