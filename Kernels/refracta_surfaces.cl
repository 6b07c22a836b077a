// refracta_surfaces.cl: opaque triangle surfaces for the OpenCL passes (photon_trace.cl,
// view_pass.cl). The flattened layout below is the one definition shared with the host:
// vtkRefractaBVH.cxx and vtkRefractaSurfaceSet.cxx include this file as a C++ header and see only
// the macros (the device functions are compiled only by an OpenCL compiler, __OPENCL_VERSION__).
//
// Frame: every flattened coordinate is in the "surface frame", world minus the set's
// FrameOrigin (vtkRefractaBVH::GetFrameOrigin(), the centre of the surfaces' bounds), so that
// float keeps its precision for scenes far from the world origin. A pass maps its own frame to it
// with one affine map computed on the host in double.
//
// Buffers (all produced by vtkRefractaSurfaceSet::Build()):
//   triangles  float4[3 * T]: v0, v1, v2 of triangle t at 3t, 3t + 1, 3t + 2 (w unused); the
//              triangles are in BVH order (the leaves reference contiguous ranges).
//   nodes      float4[2 * N]: node k = (lo.xyz, as_float(a)), (hi.xyz, as_float(count)); count > 0:
//              a leaf holding triangles [a, a + count); count == 0: an interior node whose first
//              child is k + 1 (depth-first order) and second child is a. Node 0 is the root.
//   triInfo    int4[T]: (first texel, subdivision n, surface index, kind), kind
//              REFRACTA_SURFACE_LAMBERTIAN (opaque) or REFRACTA_SURFACE_DIELECTRIC (interface).
//   normals    float4[3 * T]: the unit corner normals of triangle t at 3t, 3t + 1, 3t + 2 (w 0):
//              interpolated over the triangle for the dielectric optics (refracta_shading_normal).
//   interfaces float2[S]: (index inside, index outside) of surface s ((1, 1) if Lambertian);
//              inside is against the winding normal (v1 - v0) x (v2 - v0), outside along it.
//   bodies     float4[3 * S]: the homogeneous medium filling the inside of surface s
//              (vtkRefractaSurfaceMaterial's InsideMedium; Physics.md "Glass bodies"): (extinction
//              RGB, 1 when s has one else 0), (albedo RGB, anisotropy g), (emission RGB, 0). A
//              surface without one (0) leaves the passes on the grid's medium inside it.
//   albedo     float[3 * texels]: RGB albedo in [0, 1] of each texel.
//   texel area float[texels] (world units^2), for irradiance = flux / area on the host.
//   irradiance per texel side: the passes keep the two sides of a Lambertian texel apart (light
//              that arrives against the winding normal lands on the front, side 0, the rest on
//              the back, side 1) at the sided texel 2 texel + side (refracta_sided_texel).
//
// Texel index: triangle t with subdivision n is cut into n^2 equal-area sub-triangles. With the
// barycentric weights (u, v) of v1 and v2, a = n u and b = n v; cell (i, j) = (floor a, floor b)
// holds an upright sub-triangle (frac a + frac b < 1, or a + b < i + j + 1 here) and, when
// i + j <= n - 2, an inverted one above it. Row j holds 2 (n - j) - 1 texels, so
//   texel = j (2 n - j) + 2 i + inverted.
// Points on the boundary or slightly outside (rounding) are clamped into the triangle.
#ifndef REFRACTA_SURFACES_CL
#define REFRACTA_SURFACES_CL

#define REFRACTA_TRIANGLE_FLOAT4S 3  /* float4 per triangle */
#define REFRACTA_BVH_NODE_FLOAT4S 2  /* float4 per BVH node */
#define REFRACTA_TRIANGLE_INFO_INTS 4 /* ints per triangle in triInfo */
#define REFRACTA_TRIANGLE_INFO_TEXEL 0
#define REFRACTA_TRIANGLE_INFO_SUBDIVISION 1
#define REFRACTA_TRIANGLE_INFO_SURFACE 2
#define REFRACTA_TRIANGLE_INFO_KIND 3
#define REFRACTA_SURFACE_LAMBERTIAN 0 /* opaque two-sided Lambertian reflector */
#define REFRACTA_SURFACE_DIELECTRIC 1 /* transparent interface between two indices */
#define REFRACTA_SURFACE_SIDES 2 /* front, back: vtkRefractaLightingVolume::SurfaceSide */
/* vtkRefractaGridCuts' byte per voxel: bit a (1, 2, 4) its link along +axis a is cut; this bit:
   an opaque triangle passes within one voxel per axis of its centre */
#define REFRACTA_CUT_NEAR 8
#define REFRACTA_TRIANGLE_NORMAL_FLOATS 12 /* floats per triangle in normals (3 float4) */
#define REFRACTA_SURFACE_INTERFACE_FLOATS 2 /* floats per surface in interfaces */
#define REFRACTA_SURFACE_BODY_FLOATS 12 /* floats per surface in bodies (3 float4) */
#define REFRACTA_BVH_STACK_SIZE 64 /* traversal stack; the build never exceeds this depth */
#define REFRACTA_BVH_MAX_DEPTH 60

#ifdef __OPENCL_VERSION__

#ifdef cl_khr_fp64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#endif

// The irradiance slot of `side` (0 front, 1 back) of a texel (see the layout above).
inline long refracta_sided_texel(long texel, int side)
{
  return REFRACTA_SURFACE_SIDES * texel + side;
}

// A ray prepared for the watertight test of Woop, Benthin and Wald (2013, JCGT 2(1)): kz is the
// axis of the direction's largest component, (kx, ky) the other two (swapped when d[kz] < 0 to
// keep the winding), shear (sx, sy, sz) maps the ray onto +z.
typedef struct
{
  float3 origin;
  float3 dir;
  float3 invDir;
  int kx, ky, kz;
  float sx, sy, sz;
} refracta_ray;

typedef struct
{
  float t;    // distance along the ray (units of |dir|)
  float u, v; // barycentric weights of v1 and v2
  int triangle; // -1: no hit
} refracta_hit;

inline float refracta_component(float3 p, int axis)
{
  return axis == 0 ? p.x : (axis == 1 ? p.y : p.z);
}

inline refracta_ray refracta_make_ray(float3 origin, float3 dir)
{
  refracta_ray r;
  r.origin = origin;
  r.dir = dir;
  r.invDir = (float3)(1.0f) / dir;
  const float3 a = fabs(dir);
  r.kz = (a.x > a.y) ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  r.kx = r.kz == 2 ? 0 : r.kz + 1;
  r.ky = r.kx == 2 ? 0 : r.kx + 1;
  if (refracta_component(dir, r.kz) < 0.0f)
  {
    const int swap = r.kx;
    r.kx = r.ky;
    r.ky = swap;
  }
  const float dz = refracta_component(dir, r.kz);
  r.sx = refracta_component(dir, r.kx) / dz;
  r.sy = refracta_component(dir, r.ky) / dz;
  r.sz = 1.0f / dz;
  return r;
}

// The 2D edge function x1 y2 - y1 x2, never contracted into an fma: the same edge seen from the
// two triangles that share it must give exactly opposite values (watertightness).
inline float refracta_edge(float x1, float y1, float x2, float y2)
{
#pragma OPENCL FP_CONTRACT OFF
  const float p = x1 * y2;
  const float q = y1 * x2;
  return p - q;
}

// Watertight ray-triangle test; true and (t, u, v) when the ray hits in (tMin, tMax).
inline bool refracta_intersect_triangle(const refracta_ray* r, float3 p0, float3 p1, float3 p2,
  float tMin, float tMax, float* tOut, float* uOut, float* vOut)
{
  const float3 a = p0 - r->origin;
  const float3 b = p1 - r->origin;
  const float3 c = p2 - r->origin;
  const float az = refracta_component(a, r->kz);
  const float bz = refracta_component(b, r->kz);
  const float cz = refracta_component(c, r->kz);
  const float ax = refracta_component(a, r->kx) - r->sx * az;
  const float ay = refracta_component(a, r->ky) - r->sy * az;
  const float bx = refracta_component(b, r->kx) - r->sx * bz;
  const float by = refracta_component(b, r->ky) - r->sy * bz;
  const float cx = refracta_component(c, r->kx) - r->sx * cz;
  const float cy = refracta_component(c, r->ky) - r->sy * cz;
  float U = refracta_edge(cx, cy, bx, by);
  float V = refracta_edge(ax, ay, cx, cy);
  float W = refracta_edge(bx, by, ax, ay);
#ifdef cl_khr_fp64
  if (U == 0.0f || V == 0.0f || W == 0.0f)
  {
    // Exactly on an edge in float: decide in double, as the paper does.
    U = (float)((double)cx * (double)by - (double)cy * (double)bx);
    V = (float)((double)ax * (double)cy - (double)ay * (double)cx);
    W = (float)((double)bx * (double)ay - (double)by * (double)ax);
  }
#endif
  if ((U < 0.0f || V < 0.0f || W < 0.0f) && (U > 0.0f || V > 0.0f || W > 0.0f))
  {
    return false;
  }
  const float det = U + V + W;
  if (det == 0.0f)
  {
    return false;
  }
  const float T = U * (r->sz * az) + V * (r->sz * bz) + W * (r->sz * cz);
  const float inv = 1.0f / det;
  const float t = T * inv;
  if (!(t > tMin) || !(t < tMax))
  {
    return false;
  }
  *tOut = t;
  *uOut = V * inv;
  *vOut = W * inv;
  return true;
}

// Entry distance of the ray into the node's box when it enters before tMax, else INFINITY.
inline float refracta_node_entry(const refracta_ray* r, float4 lo, float4 hi, float tMax)
{
  const float3 ta = (lo.xyz - r->origin) * r->invDir;
  const float3 tb = (hi.xyz - r->origin) * r->invDir;
  const float3 tmin = fmin(ta, tb);
  const float3 tmax = fmax(ta, tb);
  const float enter = fmax(fmax(tmin.x, tmin.y), fmax(tmin.z, 0.0f));
  // 1 + 2 gamma(3) (Pharr, Jakob and Humphreys, 3rd ed., 6.8.2): a ray grazing a face of the
  // box is not rejected by the rounding of the slab distances.
  const float leave = fmin(fmin(tmax.x, tmax.y), tmax.z) * 1.0000004f;
  return (enter <= leave && enter < tMax) ? enter : INFINITY;
}

// Closest hit of the ray origin + t dir with t in (tMin, tMax), or hit.triangle = -1. A stack of
// REFRACTA_BVH_STACK_SIZE nodes, nearer child first. An empty set has zero nodes: no hit.
inline refracta_hit refracta_bvh_closest(__global const float4* nodes, int nodeCount,
  __global const float4* triangles, float3 origin, float3 dir, float tMin, float tMax)
{
  refracta_hit hit;
  hit.t = tMax;
  hit.u = hit.v = 0.0f;
  hit.triangle = -1;
  if (nodeCount <= 0)
  {
    return hit;
  }
  const refracta_ray r = refracta_make_ray(origin, dir);
  int stack[REFRACTA_BVH_STACK_SIZE];
  int top = 0;
  int node = 0;
  if (refracta_node_entry(&r, nodes[0], nodes[1], hit.t) == INFINITY)
  {
    return hit;
  }
  while (true)
  {
    const float4 lo = nodes[2 * node];
    const float4 hi = nodes[2 * node + 1];
    const int count = as_int(hi.w);
    if (count > 0)
    {
      const int first = as_int(lo.w);
      for (int k = first; k < first + count; ++k)
      {
        float t, u, v;
        if (refracta_intersect_triangle(&r, triangles[3 * k].xyz, triangles[3 * k + 1].xyz,
              triangles[3 * k + 2].xyz, tMin, hit.t, &t, &u, &v))
        {
          hit.t = t;
          hit.u = u;
          hit.v = v;
          hit.triangle = k;
        }
      }
    }
    else
    {
      const int c0 = node + 1;
      const int c1 = as_int(lo.w);
      float e0 = refracta_node_entry(&r, nodes[2 * c0], nodes[2 * c0 + 1], hit.t);
      float e1 = refracta_node_entry(&r, nodes[2 * c1], nodes[2 * c1 + 1], hit.t);
      int near = c0;
      int far = c1;
      if (e1 < e0)
      {
        near = c1;
        far = c0;
        const float s = e0;
        e0 = e1;
        e1 = s;
      }
      if (e0 != INFINITY)
      {
        if (e1 != INFINITY && top < REFRACTA_BVH_STACK_SIZE)
        {
          stack[top++] = far;
        }
        node = near;
        continue;
      }
    }
    // Pop the next node that the (possibly shortened) ray still reaches.
    node = -1;
    while (top > 0)
    {
      const int candidate = stack[--top];
      if (refracta_node_entry(&r, nodes[2 * candidate], nodes[2 * candidate + 1], hit.t) !=
        INFINITY)
      {
        node = candidate;
        break;
      }
    }
    if (node < 0)
    {
      break;
    }
  }
  return hit;
}

// Whether a triangle meets the ray within (tMin, tMax), stopping at the first hit: any triangle
// where opaqueOnly is false (shadow rays), else only opaque ones (REFRACTA_SURFACE_LAMBERTIAN in
// triInfo): the test of whether an opaque surface separates two points (refracta_opaque_between).
inline bool refracta_bvh_any_hit(__global const float4* nodes, int nodeCount,
  __global const float4* triangles, __global const int* triInfo, bool opaqueOnly, float3 origin,
  float3 dir, float tMin, float tMax)
{
  if (nodeCount <= 0)
  {
    return false;
  }
  const refracta_ray r = refracta_make_ray(origin, dir);
  int stack[REFRACTA_BVH_STACK_SIZE];
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const int node = stack[--top];
    const float4 lo = nodes[2 * node];
    const float4 hi = nodes[2 * node + 1];
    if (refracta_node_entry(&r, lo, hi, tMax) == INFINITY)
    {
      continue;
    }
    const int count = as_int(hi.w);
    if (count > 0)
    {
      const int first = as_int(lo.w);
      for (int k = first; k < first + count; ++k)
      {
        float t, u, v;
        if ((!opaqueOnly ||
              triInfo[REFRACTA_TRIANGLE_INFO_INTS * k + REFRACTA_TRIANGLE_INFO_KIND] ==
                REFRACTA_SURFACE_LAMBERTIAN) &&
          refracta_intersect_triangle(&r, triangles[3 * k].xyz, triangles[3 * k + 1].xyz,
            triangles[3 * k + 2].xyz, tMin, tMax, &t, &u, &v))
        {
          return true;
        }
      }
    }
    else if (top + 2 <= REFRACTA_BVH_STACK_SIZE)
    {
      stack[top++] = as_int(lo.w);
      stack[top++] = node + 1;
    }
  }
  return false;
}

inline bool refracta_bvh_occluded(__global const float4* nodes, int nodeCount,
  __global const float4* triangles, float3 origin, float3 dir, float tMin, float tMax)
{
  return refracta_bvh_any_hit(
    nodes, nodeCount, triangles, (__global const int*)0, false, origin, dir, tMin, tMax);
}

// Whether an opaque triangle separates grid-local point a from b, the rows
// toSurface0..2 mapping grid-local points to the surface frame: light on one side of a wall is
// not light on the other (vtkRefractaGridCuts flags the voxels near opaque triangles where the
// photon pass's deposits and the view pass's lookups ask). A triangle through b, or within 0.1%
// of the segment's length beyond it, counts: a voxel centre on a wall belongs to neither side.
inline bool refracta_opaque_between(__global const float4* nodes, int nodeCount,
  __global const float4* triangles, __global const int* triInfo, float4 toSurface0,
  float4 toSurface1, float4 toSurface2, float3 a, float3 b)
{
  const float3 sa = (float3)(dot(toSurface0.xyz, a) + toSurface0.w,
    dot(toSurface1.xyz, a) + toSurface1.w, dot(toSurface2.xyz, a) + toSurface2.w);
  const float3 sb = (float3)(dot(toSurface0.xyz, b) + toSurface0.w,
    dot(toSurface1.xyz, b) + toSurface1.w, dot(toSurface2.xyz, b) + toSurface2.w);
  const float3 d = sb - sa;
  const float len = length(d);
  return len > 0.0f &&
    refracta_bvh_any_hit(
      nodes, nodeCount, triangles, triInfo, true, sa, d / len, 0.0f, 1.001f * len);
}

// Unit geometric normal of triangle k (the winding's normal; surfaces are two-sided).
inline float3 refracta_triangle_normal(__global const float4* triangles, int k)
{
  const float3 p0 = triangles[3 * k].xyz;
  return normalize(cross(triangles[3 * k + 1].xyz - p0, triangles[3 * k + 2].xyz - p0));
}

// Texel of barycentric weights (u, v) (of v1, v2) within a triangle of subdivision n, in
// [0, n^2). The same arithmetic, step for step, as vtkRefractaSurfaceSet::TexelIndex.
inline int refracta_texel_index(float u, float v, int n)
{
  const float fn = (float)n;
  const float a = clamp(u * fn, 0.0f, fn);
  const float b = clamp(v * fn, 0.0f, fn);
  int j = min((int)floor(b), n - 1);
  int i = min((int)floor(a), n - 1);
  if (i + j > n - 1)
  {
    i = n - 1 - j; // past the hypotenuse by rounding: the last upright texel of the row
    return j * (2 * n - j) + 2 * i;
  }
  const float s = a + b;
  const int inverted = (i + j <= n - 2 && s > (float)(i + j + 1)) ? 1 : 0;
  return j * (2 * n - j) + 2 * i + inverted;
}

// ---------------------------------------------------------------------------------------------
// Dielectric interfaces (Documentation/Physics.md, "Dielectric interfaces"): the optics every pass
// shares. vtkRefractaDielectric is the host's twin, step for step in double.

// Unpolarised Fresnel reflectance of light going from index etaI into etaT at cos(incidence)
// cosI (clamped to [0, 1]): (Rs + Rp) / 2 with Rs = ((etaI cI - etaT cT) / (etaI cI + etaT cT))^2
// and Rp = ((etaI cT - etaT cI) / (etaI cT + etaT cI))^2; exactly 1 from the critical angle on
// (total internal reflection).
inline float refracta_fresnel_reflectance(float cosI, float etaI, float etaT)
{
  const float c = clamp(cosI, 0.0f, 1.0f);
  const float eta = etaI / etaT;
  const float sin2T = eta * eta * fmax(0.0f, 1.0f - c * c);
  if (sin2T >= 1.0f)
  {
    return 1.0f;
  }
  const float cosT = sqrt(1.0f - sin2T);
  const float rs = (etaI * c - etaT * cosT) / (etaI * c + etaT * cosT);
  const float rp = (etaI * cosT - etaT * c) / (etaI * cosT + etaT * c);
  return 0.5f * (rs * rs + rp * rp);
}

// Mirror direction of d about the unit normal n (either side).
inline float3 refracta_reflect(float3 d, float3 n)
{
  return d - 2.0f * dot(d, n) * n;
}

// Snell's law: unit d meets the unit normal nf that faces it (dot(d, nf) < 0), eta = etaI / etaT.
// False (and *t untouched) under total internal reflection, else *t the unit refracted direction.
inline bool refracta_refract(float3 d, float3 nf, float eta, float3* t)
{
  const float cosI = -dot(d, nf);
  const float sin2T = eta * eta * fmax(0.0f, 1.0f - cosI * cosI);
  if (sin2T >= 1.0f)
  {
    return false;
  }
  const float cosT = sqrt(1.0f - sin2T);
  *t = normalize(eta * d + (eta * cosI - cosT) * nf);
  return true;
}

// The shading normal of triangle k at barycentric (u, v) of v1, v2: its corner normals
// interpolated and normalised (on the side of the winding normal).
inline float3 refracta_shading_normal(__global const float4* normals, int k, float u, float v)
{
  return normalize((1.0f - u - v) * normals[3 * k].xyz + u * normals[3 * k + 1].xyz +
    v * normals[3 * k + 2].xyz);
}

// One choice at a dielectric interface, for a unit direction d meeting a triangle with unit
// winding (outward) normal ng and shading normal ns, between nInside and nOutside, with xi uniform
// in [0, 1): reflected with probability R (Fresnel with the shading normal; 1 under total internal
// reflection), else refracted. Returns the new unit direction; *transmitted says which branch,
// *reflectance is the R used, *etaFrom and *etaTo the indices of the incident and the other side.
// When the shading normal would send the ray to the wrong side of the triangle's plane (reflected
// through it or refracted back), the choice is made again, with the same xi, about the geometric
// normal: a ray never tunnels, and the branch's probability is still its weight.
inline float3 refracta_dielectric_sample(float3 d, float3 ng, float3 ns, float nInside,
  float nOutside, float xi, int* transmitted, float* reflectance, float* etaFrom, float* etaTo)
{
  const bool entering = dot(d, ng) < 0.0f;
  const float etaI = entering ? nOutside : nInside;
  const float etaT = entering ? nInside : nOutside;
  *etaFrom = etaI;
  *etaTo = etaT;
  const float3 fg = entering ? ng : -ng; // the geometric normal on the incident side
  const float3 fs = entering ? ns : -ns;
  float3 nf = dot(d, fs) < 0.0f ? fs : fg;
  float3 out = d;
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    const float r = refracta_fresnel_reflectance(-dot(d, nf), etaI, etaT);
    *reflectance = r;
    *transmitted = (xi < r || !refracta_refract(d, nf, etaI / etaT, &out)) ? 0 : 1;
    if (!*transmitted)
    {
      out = refracta_reflect(d, nf);
    }
    const float side = dot(out, fg);
    if ((*transmitted ? side < 0.0f : side > 0.0f) || attempt == 1)
    {
      break;
    }
    nf = fg;
  }
  return out;
}

// The body a path is in after it is refracted through surface `surface`: the surface's when the
// path enters its inside (travels against the outward normal) and the surface has an inside
// medium, else -1 (the grid's medium; between nested bodies too, see Physics.md "Glass bodies").
inline int refracta_body_after_refraction(__global const float4* bodies, int surface, bool entering)
{
  return entering && bodies[3 * surface].w > 0.5f ? surface : -1;
}

#endif // __OPENCL_VERSION__
#endif // REFRACTA_SURFACES_CL
