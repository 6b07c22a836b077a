// photon_surfaces.cl: what a photon does at the surfaces of a vtkRefractaSurfaceSet (compiled with
// -DREFRACTA_SURFACES=1): Lambertian triangles (deposit into the atlas and the caustic atlas,
// albedo roulette, diffuse reflection), dielectric interfaces (Fresnel roulette, Snell, the glass
// body the photon is in) and the step that finds them (photon_surface_event). Prepend
// refracta_surfaces.cl and photon_trace.cl (the photon state, the march's steps); photon_march.cl
// follows. Documentation/Physics.md "Surfaces", "Dielectric interfaces", "Caustic atlas".

#if REFRACTA_SURFACES
// The surfaces a photon can meet: the BVH and atlas of refracta_surfaces.cl, the irradiance
// accumulators (fixed point, 3 per texel side: refracta_sided_texel) and the affine map
// grid-local -> surface frame (rows of [R | T]; R is a rotation, so lengths and ray parameters
// are kept).
typedef struct
{
  __global const float4* nodes;
  int nodeCount;
  __global const float4* triangles;
  __global const int4* triInfo;
  __global const float* albedo;
  volatile __global long* irradiance;
  float4 row0, row1, row2;
  float epsilon; // offset of a reflected photon from the surface (grid-local units)
  long causticOffset; // the coarse atlas's sided texels: the fine caustic atlas starts after them
  __global const float4* normals;    // corner normals (dielectric shading normals)
  __global const float2* interfaces; // (index inside, index outside) per surface
  volatile __global long* tallies;   // the interface books are added at each event
  volatile __global long* counters;
} photon_surfaces;

inline void photon_set_surfaces(photon_surfaces* s, __global const float4* nodes, int nodeCount,
  __global const float4* triangles, __global const int4* info, __global const float* albedo,
  volatile __global long* irradiance, float4 row0, float4 row1, float4 row2, float epsilon,
  long causticOffset, __global const float4* normals, __global const float2* interfaces,
  volatile __global long* tallies, volatile __global long* counters)
{
  s->causticOffset = causticOffset;
  s->normals = normals;
  s->interfaces = interfaces;
  s->tallies = tallies;
  s->counters = counters;
  s->epsilon = epsilon;
  s->nodes = nodes;
  s->nodeCount = nodeCount;
  s->triangles = triangles;
  s->triInfo = info;
  s->albedo = albedo;
  s->irradiance = irradiance;
  s->row0 = row0;
  s->row1 = row1;
  s->row2 = row2;
}

inline float3 photon_to_surface_point(const photon_surfaces* s, float3 p)
{
  return (float3)(dot(s->row0.xyz, p) + s->row0.w, dot(s->row1.xyz, p) + s->row1.w,
    dot(s->row2.xyz, p) + s->row2.w);
}

inline float3 photon_to_surface_vector(const photon_surfaces* s, float3 d)
{
  return (float3)(dot(s->row0.xyz, d), dot(s->row1.xyz, d), dot(s->row2.xyz, d));
}

// Closest surface hit of x + t d (grid-local) with t in (0, tMax), in units of d.
inline refracta_hit photon_trace_surfaces(const photon_surfaces* s, float3 x, float3 d, float tMax)
{
  return refracta_bvh_closest(s->nodes, s->nodeCount, s->triangles,
    photon_to_surface_point(s, x), photon_to_surface_vector(s, d), 0.0f, tMax);
}

// Whether x is inside the medium's box.
inline bool photon_in_box(float3 x, float3 lo, float3 hi)
{
  return all(x >= lo) && all(x <= hi);
}

// The surface-frame vector n (a normal) in the grid-local frame (R^T n).
inline float3 photon_from_surface_vector(const photon_surfaces* s, float3 n)
{
  return n.x * s->row0.xyz + n.y * s->row1.xyz + n.z * s->row2.xyz;
}

// The photon at *x travelling along unit d meets the dielectric triangle h: reflected with the
// Fresnel probability R, else refracted (refracta_dielectric_sample). The probability is the
// weight, so its power is unchanged and each event books the power once, as reflected or as
// transmitted: per interface, reflected + transmitted = incident exactly. It leaves epsilon off
// the surface on the side it now travels to; glass neither deposits nor resets the order.
inline void photon_interface_interact(photon_state* ps, float3* x, float3* dir, float3 d,
  refracta_hit h, const photon_surfaces* s)
{
  const int k = h.triangle;
  const float2 eta = s->interfaces[s->triInfo[k].z];
  const float3 ng = normalize(photon_from_surface_vector(s, refracta_triangle_normal(s->triangles, k)));
  const float3 ns =
    normalize(photon_from_surface_vector(s, refracta_shading_normal(s->normals, k, h.u, h.v)));
  int transmitted;
  float reflectance, etaFrom, etaTo;
  *dir = refracta_dielectric_sample(d, ng, ns, eta.x, eta.y, refracta_rng_uniform(&ps->rng),
    &transmitted, &reflectance, &etaFrom, &etaTo);
  const int book = transmitted ? PHOTON_TALLY_INTERFACE_TRANSMITTED : PHOTON_TALLY_INTERFACE_REFLECTED;
  refracta_atomic_add_fixed(s->tallies + 3 * book, ps->power.x);
  refracta_atomic_add_fixed(s->tallies + 3 * book + 1, ps->power.y);
  refracta_atomic_add_fixed(s->tallies + 3 * book + 2, ps->power.z);
  atom_add(s->counters +
      (transmitted ? PHOTON_COUNTER_INTERFACE_TRANSMISSIONS : PHOTON_COUNTER_INTERFACE_REFLECTIONS),
    1L);
  *x += s->epsilon * (dot(*dir, ng) > 0.0f ? ng : -ng);
  ps->caustic = 1; // an LS+D path from here on, reflected or refracted
  if (transmitted)
  {
    ps->body = refracta_body_after_refraction(ps->bodies, s->triInfo[k].z, dot(d, ng) < 0.0f);
  }
}

// The body a photon starting at x along unit d is in: the surface's it first meets, when that
// is a dielectric surface with an inside medium met from inside; else -1. For closed meshes the
// first hit decides (nested bodies: the innermost; outside all: a surface met from outside).
inline int photon_start_body(const photon_surfaces* s, const photon_state* ps, float3 x, float3 d)
{
  const refracta_hit h = photon_trace_surfaces(s, x, d, INFINITY);
  if (h.triangle < 0 || s->triInfo[h.triangle].w != REFRACTA_SURFACE_DIELECTRIC)
  {
    return -1;
  }
  const float3 ng =
    photon_from_surface_vector(s, refracta_triangle_normal(s->triangles, h.triangle));
  return dot(d, ng) > 0.0f
    ? refracta_body_after_refraction(ps->bodies, s->triInfo[h.triangle].z, true)
    : -1;
}

// Deposits the photon's power into the fixed-point accumulators of sided texel `sided`
// (refracta_sided_texel; 3 per sided texel).
inline void photon_deposit_texel(volatile __global long* irradiance, long sided, float3 power)
{
  refracta_atomic_add_fixed(irradiance + 3 * sided, power.x);
  refracta_atomic_add_fixed(irradiance + 3 * sided + 1, power.y);
  refracta_atomic_add_fixed(irradiance + 3 * sided + 2, power.z);
}

#if REFRACTA_CAUSTIC_SUBDIVISION > 1
// A caustic photon (Physics.md "Caustic atlas") meeting Lambertian triangle info at barycentric
// (u, v) on `side` (its atlas texel `texel`) also deposits into the fine atlas, where every coarse
// texel is cut again c x c (c = REFRACTA_CAUSTIC_SUBDIVISION): the same texel order with
// subdivision n c, fine first texel = coarse first texel c^2, sided like the coarse ones and
// stored after the s->causticOffset coarse sided texels, and counts itself in the sided texel's
// caustic photon count (one long per coarse sided texel after the fine accumulators), which tells
// the view pass where the fine texels are worth reading. The coarse deposit stays the surface's
// whole flux; the fine one resolves its caustic part.
inline void photon_deposit_caustic(const photon_surfaces* s, const photon_state* ps, int4 info,
  int texel, int side, float u, float v)
{
  if (ps->caustic)
  {
    const int c = REFRACTA_CAUSTIC_SUBDIVISION;
    const long coarse = s->causticOffset;
    const long fine = (long)info.x * (c * c) + refracta_texel_index(u, v, info.y * c);
    photon_deposit_texel(s->irradiance, coarse + refracta_sided_texel(fine, side), ps->power);
    atom_add(s->irradiance + 3 * coarse * (1 + c * c) + refracta_sided_texel(texel, side), 1L);
  }
}
#endif

// The photon at *x (on the surface) travelling along unit d meets triangle h: deposit, book,
// roulette on the albedo, and diffuse reflection. Returns -1 (goes on from *x along *dir) or
// PHOTON_COUNTER_SURFACE (absorbed).
inline int photon_surface_interact(photon_state* ps, float3* x, float3* dir, float3 d,
  refracta_hit h, const photon_surfaces* s)
{
  const int4 info = s->triInfo[h.triangle];
  if (info.w == REFRACTA_SURFACE_DIELECTRIC)
  {
    // A photon circling inside glass by total internal reflection (scattered there, see
    // Physics.md "Trapped light in glass") would otherwise run to the step cap: it ends here,
    // its power booked as remaining, like the step cap's.
    if (++ps->interfaces > REFRACTA_MAX_INTERFACES)
    {
      *dir = d;
      return PHOTON_COUNTER_STEP_CAP;
    }
    photon_interface_interact(ps, x, dir, d, h, s);
    return -1;
  }
  const int texel = info.x + refracta_texel_index(h.u, h.v, info.y);
  // The normal in the grid-local frame (R^T n): the photon lands on the side it comes from.
  const float3 ng = refracta_triangle_normal(s->triangles, h.triangle);
  float3 n = normalize(ng.x * s->row0.xyz + ng.y * s->row1.xyz + ng.z * s->row2.xyz);
  const int side = dot(n, d) > 0.0f ? 1 : 0;
#if REFRACTA_SKIP_DIRECT
  // Direct light (a photon from a light that met no surface, no glass and no scattering) is
  // computed without noise by light rays (vtkLightRaySingleScattering::ComputeSurfaceIrradiance)
  // and added on the host: such a photon deposits nothing, and goes on as any other.
  if (ps->hits > 0 || ps->order > 0 || ps->caustic)
#endif
  {
    photon_deposit_texel(s->irradiance, refracta_sided_texel(texel, side), ps->power);
#if REFRACTA_CAUSTIC_SUBDIVISION > 1
    photon_deposit_caustic(s, ps, info, texel, side, h.u, h.v);
#endif
  }
  ps->hits++;
  const float3 a = clamp(vload3(texel, s->albedo), 0.0f, 1.0f);
  const float3 reflected = ps->power * a;
  ps->surface += ps->power - reflected;
  ps->power = reflected;
  const float q = fmax(a.x, fmax(a.y, a.z));
  if (!(q > 0.0f) || refracta_rng_uniform(&ps->rng) >= q)
  {
    ps->killed += ps->power;
    ps->power = (float3)(0.0f);
    return PHOTON_COUNTER_SURFACE;
  }
  const float3 boosted = ps->power / q;
  ps->gained += boosted - ps->power;
  ps->power = boosted;
#if REFRACTA_ANALOG
  // Where the photons carry the scattered orders, reflected light joins them: its scattering
  // counts with S_ms, whose flux over its fluence shades it (MultipleScatteringDirection), and S1
  // keeps the beams from the lights, whose one direction per voxel is right for each. In S1, a
  // lit floor's diffuse reflection and the lamp's beam above it would be shaded as one beam along
  // their (nearly cancelling) mean direction.
  ps->order = 1;
#else
  ps->order = 0; // a new beam: its first scattering is S1 again
#endif
  ps->caustic = 0;
  // The normal turned towards the side the photon came from.
  n = side ? -n : n;
  // Cosine-weighted direction about n (Malley's method).
  const float u1 = refracta_rng_uniform(&ps->rng);
  const float phi = 2.0f * REFRACTA_PI * refracta_rng_uniform(&ps->rng);
  const float r = sqrt(u1);
  const float3 helper = fabs(n.x) < 0.9f ? (float3)(1.0f, 0.0f, 0.0f) : (float3)(0.0f, 1.0f, 0.0f);
  const float3 e1 = normalize(cross(n, helper));
  const float3 e2 = cross(n, e1);
  *dir = normalize(r * cos(phi) * e1 + r * sin(phi) * e2 + sqrt(fmax(0.0f, 1.0f - u1)) * n);
  *x += s->epsilon * n;
  return -1;
}

// v for a photon at x travelling along unit d: n(x) d inside a refracting medium, d elsewhere.
inline float3 photon_velocity(float3 x, float3 d, float3 lo, float3 hi,
  __global const float* refractiveIndex, int4 dims, float4 spacing)
{
#if REFRACTA_REFRACT
  if (photon_in_box(x, lo, hi))
  {
    return d * refracta_sample1(refractiveIndex, dims, refracta_to_voxel(x, spacing));
  }
#endif
  return d;
}

#if REFRACTA_ANALOG
// The photon scattered at ps->collisionPoint while travelling along unit d: it goes on from there
// in a Henyey-Greenstein direction, one order higher.
inline void photon_scatter(photon_state* ps, float3* x, float3* v, float3 d, float3 lo, float3 hi,
  __global const float* refractiveIndex, int4 dims, float4 spacing)
{
  *x = clamp(ps->collisionPoint, lo, hi);
#if REFRACTA_INTERFACES
  const float gs = ps->body >= 0
    ? ps->bodies[3 * ps->body + 1].w
    : refracta_sample1(ps->anisotropy, dims, refracta_to_voxel(*x, spacing));
  const float g = clamp(gs, -0.999f, 0.999f);
#else
  const float g = clamp(
    refracta_sample1(ps->anisotropy, dims, refracta_to_voxel(*x, spacing)), -0.999f, 0.999f);
#endif
  const float3 dir = photon_sample_hg(d, g, &ps->rng);
  *v = photon_velocity(*x, dir, lo, hi, refractiveIndex, dims, spacing);
  ps->collided = 0;
  ps->order++;
  ps->caustic = 0; // scattered in the volume: a diffuse event
}
#endif

// One event of a photon with surfaces: a curved step inside a refracting medium's box, else a
// straight flight (through the box when n is constant) to the next surface, to the box (curved
// rays continue inside it) or out of the scene. -1: it goes on; else its outcome.
inline int photon_surface_event(photon_state* ps, float3* x, float3* v, int* steps, float3 lo,
  float3 hi, __global const uchar* octree, __global const float* extinction,
  __global const float* albedo, __global const float* refractiveIndex,
  __global const float* gradient, int4 dims, float4 spacing, volatile __global long* deposits, const photon_surfaces* s)
{
  if (*steps >= REFRACTA_MAX_STEPS)
  {
    return PHOTON_COUNTER_STEP_CAP;
  }
  ++*steps;
  float3 d;
  refracta_hit h;
#if REFRACTA_REFRACT
  if (photon_in_box(*x, lo, hi))
  {
    float3 x1, v1;
    photon_advance(*x, *v, octree, extinction, refractiveIndex, gradient, dims, spacing, &x1, &v1);
    if (!all(isfinite(x1)) || !all(isfinite(v1)))
    {
      return PHOTON_COUNTER_INVALID;
    }
    const float3 chord = x1 - *x;
    const bool inBox = photon_in_box(x1, lo, hi);
    float tExit = 1.0f;
    if (!inBox)
    {
      float e0;
      float e1;
      tExit = refracta_intersect_box(*x, chord, lo, hi, &e0, &e1) ? clamp(e1, 0.0f, 1.0f) : 0.0f;
    }
    h = photon_trace_surfaces(s, *x, chord, tExit);
#if REFRACTA_EXTINCTION
    photon_walk(ps, *x, x1, h.triangle >= 0 ? h.t : tExit, dims, spacing, extinction, albedo,
      deposits);
    if (ps->dead)
    {
      return PHOTON_COUNTER_ROULETTE;
    }
#if REFRACTA_ANALOG
    if (ps->collided)
    {
      photon_scatter(ps, x, v, normalize(chord), lo, hi, refractiveIndex, dims, spacing);
      return -1;
    }
#endif
#endif
    d = normalize(chord);
    if (h.triangle < 0 && inBox)
    {
      *x = x1;
      *v = v1;
      return -1;
    }
    if (h.triangle < 0)
    {
      // Out of the box: on in a straight line from just outside it.
      *x += tExit * chord + s->epsilon * d;
      *v = d;
      return -1;
    }
    *x += h.t * chord;
  }
  else
#endif
  {
    d = normalize(*v);
    h = photon_trace_surfaces(s, *x, d, INFINITY);
    float t0;
    float t1;
    const bool box = refracta_intersect_box(*x, d, lo, hi, &t0, &t1) && t1 > t0;
#if REFRACTA_REFRACT
    if (box && t0 < h.t)
    {
      // Into the medium before any surface: curved steps from its face.
      *x = clamp(*x + t0 * d, lo, hi);
      *v = photon_velocity(*x, d, lo, hi, refractiveIndex, dims, spacing);
      return -1;
    }
#elif REFRACTA_EXTINCTION
    if (box && t0 < h.t)
    {
      photon_walk(ps, *x + t0 * d, *x + fmin(t1, h.t) * d, 1.0f, dims, spacing, extinction, albedo,
        deposits);
      if (ps->dead)
      {
        return PHOTON_COUNTER_ROULETTE;
      }
#if REFRACTA_ANALOG
      if (ps->collided)
      {
        photon_scatter(ps, x, v, d, lo, hi, refractiveIndex, dims, spacing);
        return -1;
      }
#endif
    }
#endif
    if (h.triangle < 0)
    {
      return PHOTON_COUNTER_ESCAPED;
    }
    *x += h.t * d;
  }
  float3 dir;
  const int outcome = photon_surface_interact(ps, x, &dir, d, h, s);
  *v = photon_velocity(*x, dir, lo, hi, refractiveIndex, dims, spacing);
  return outcome;
}
#endif
