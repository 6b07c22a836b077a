// refracta_common.cl: device helpers shared by every Refracta pass. Prepend it (after
// refracta_atomics.cl when a program accumulates) to a program's sources.
//
// Conventions (Documentation/Physics.md): kernels work in the grid-local frame, where voxel
// (i, j, k) is centred at (i, j, k) * spacing and the medium occupies [-spacing/2,
// (dims - 1/2) * spacing]. Grids are passed as `int4 dims` (w unused) and `float4 spacing`
// (w unused). RGB fields are interleaved float triples (a 3-component vtkFloatArray), accessed
// with vload3/vstore3. Voxel (i, j, k) has linear index i + dims.x * (j + dims.y * k).

#ifndef REFRACTA_PI
#define REFRACTA_PI 3.14159265358979323846f
#endif

// ---------------------------------------------------------------------------------------------
// Random numbers: PCG-style hash (O'Neill; "Hash Functions for GPU Rendering", Jarzynski &
// Olano 2020). A stream is a 32-bit state; refracta_rng_seed gives decorrelated streams for
// (seed, id) pairs, so a run is reproducible for a given seed regardless of scheduling.
inline uint refracta_pcg_hash(uint v)
{
  const uint state = v * 747796405u + 2891336453u;
  const uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

inline uint refracta_rng_seed(uint seed, uint id)
{
  return refracta_pcg_hash(seed ^ refracta_pcg_hash(id + 0x9e3779b9u));
}

// Uniform float in [0, 1): 24 random bits.
inline float refracta_rng_uniform(uint* state)
{
  *state = *state * 747796405u + 2891336453u;
  uint word = ((*state >> ((*state >> 28u) + 4u)) ^ *state) * 277803737u;
  word = (word >> 22u) ^ word;
  return (float)(word >> 8) * (1.0f / 16777216.0f);
}

// ---------------------------------------------------------------------------------------------
// Grid addressing and trilinear sampling (clamped to the edge voxels).
inline size_t refracta_voxel_index(int4 dims, int i, int j, int k)
{
  return (size_t)i + (size_t)dims.x * ((size_t)j + (size_t)dims.y * (size_t)k);
}

// Continuous voxel coordinate of a grid-local position.
inline float3 refracta_to_voxel(float3 p, float4 spacing)
{
  return p / spacing.xyz;
}

// Linear index of the voxel whose box contains continuous voxel coordinate u, or -1 outside.
inline long refracta_voxel_containing(int4 dims, float3 u)
{
  const int i = (int)floor(u.x + 0.5f);
  const int j = (int)floor(u.y + 0.5f);
  const int k = (int)floor(u.z + 0.5f);
  if (i < 0 || j < 0 || k < 0 || i >= dims.x || j >= dims.y || k >= dims.z)
  {
    return -1;
  }
  return (long)refracta_voxel_index(dims, i, j, k);
}

// Corner indices and weights of the trilinear stencil around u (clamped to the grid).
typedef struct
{
  int i0, j0, k0, i1, j1, k1;
  float fx, fy, fz;
} refracta_stencil;

inline refracta_stencil refracta_make_stencil(int4 dims, float3 u)
{
  refracta_stencil s;
  const float3 hi = (float3)((float)(dims.x - 1), (float)(dims.y - 1), (float)(dims.z - 1));
  const float3 c = clamp(u, (float3)(0.0f), hi);
  const float3 f = floor(c);
  s.i0 = (int)f.x;
  s.j0 = (int)f.y;
  s.k0 = (int)f.z;
  s.i1 = min(s.i0 + 1, dims.x - 1);
  s.j1 = min(s.j0 + 1, dims.y - 1);
  s.k1 = min(s.k0 + 1, dims.z - 1);
  s.fx = c.x - f.x;
  s.fy = c.y - f.y;
  s.fz = c.z - f.z;
  return s;
}

inline float refracta_sample1(__global const float* field, int4 dims, float3 u)
{
  const refracta_stencil s = refracta_make_stencil(dims, u);
#define REFRACTA_AT(i, j, k) field[refracta_voxel_index(dims, i, j, k)]
  const float c00 = mix(REFRACTA_AT(s.i0, s.j0, s.k0), REFRACTA_AT(s.i1, s.j0, s.k0), s.fx);
  const float c10 = mix(REFRACTA_AT(s.i0, s.j1, s.k0), REFRACTA_AT(s.i1, s.j1, s.k0), s.fx);
  const float c01 = mix(REFRACTA_AT(s.i0, s.j0, s.k1), REFRACTA_AT(s.i1, s.j0, s.k1), s.fx);
  const float c11 = mix(REFRACTA_AT(s.i0, s.j1, s.k1), REFRACTA_AT(s.i1, s.j1, s.k1), s.fx);
#undef REFRACTA_AT
  return mix(mix(c00, c10, s.fy), mix(c01, c11, s.fy), s.fz);
}

inline float3 refracta_sample3(__global const float* field, int4 dims, float3 u)
{
  const refracta_stencil s = refracta_make_stencil(dims, u);
#define REFRACTA_AT(i, j, k) vload3(refracta_voxel_index(dims, i, j, k), field)
  const float3 c00 = mix(REFRACTA_AT(s.i0, s.j0, s.k0), REFRACTA_AT(s.i1, s.j0, s.k0), s.fx);
  const float3 c10 = mix(REFRACTA_AT(s.i0, s.j1, s.k0), REFRACTA_AT(s.i1, s.j1, s.k0), s.fx);
  const float3 c01 = mix(REFRACTA_AT(s.i0, s.j0, s.k1), REFRACTA_AT(s.i1, s.j0, s.k1), s.fx);
  const float3 c11 = mix(REFRACTA_AT(s.i0, s.j1, s.k1), REFRACTA_AT(s.i1, s.j1, s.k1), s.fx);
#undef REFRACTA_AT
  return mix(mix(c00, c10, s.fy), mix(c01, c11, s.fy), s.fz);
}

// ---------------------------------------------------------------------------------------------
// Geometry.

// The medium's box in the grid-local frame.
inline void refracta_domain(int4 dims, float4 spacing, float3* lo, float3* hi)
{
  *lo = -0.5f * spacing.xyz;
  *hi = ((float3)((float)dims.x, (float)dims.y, (float)dims.z) - 0.5f) * spacing.xyz;
}

// Slab test: parametric entry and exit of the ray o + t d with the box [lo, hi]; false when it
// misses or the box is behind. d need not be normalised; zero components are handled.
inline bool refracta_intersect_box(float3 o, float3 d, float3 lo, float3 hi, float* t0, float* t1)
{
  const float3 inv = (float3)(1.0f) / d; // +-inf for zero components: IEEE makes the test work
  const float3 ta = (lo - o) * inv;
  const float3 tb = (hi - o) * inv;
  const float3 tmin = fmin(ta, tb);
  const float3 tmax = fmax(ta, tb);
  const float enter = fmax(fmax(tmin.x, tmin.y), fmax(tmin.z, 0.0f));
  const float leave = fmin(fmin(tmax.x, tmax.y), tmax.z);
  *t0 = enter;
  *t1 = leave;
  return leave >= enter;
}

// ---------------------------------------------------------------------------------------------
// Henyey-Greenstein phase function, normalised over the sphere; cosTheta between the incoming and
// the outgoing travel directions.
// The denominator 1 + g^2 - 2 g cos(theta) is evaluated as a sum of two non-negative terms,
// (1 - g)^2 + 2 g (1 - cos) for g >= 0 and (1 + g)^2 - 2 g (1 + cos) for g < 0: the textbook form
// cancels catastrophically in float near the peak when abs(g) -> 1 (15% error at g = -0.999).
inline float refracta_hg_phase(float cosTheta, float g)
{
  const float c = clamp(cosTheta, -1.0f, 1.0f);
  const float denom = g >= 0.0f ? (1.0f - g) * (1.0f - g) + 2.0f * g * (1.0f - c)
                                : (1.0f + g) * (1.0f + g) - 2.0f * g * (1.0f + c);
  const float d = fmax(denom, 1e-30f);
  return (1.0f - g) * (1.0f + g) / (4.0f * REFRACTA_PI * d * sqrt(d));
}
