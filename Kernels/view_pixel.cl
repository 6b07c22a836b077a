// view_pixel.cl: a pixel of the view pass: the paths of its rays through glass, and where its
// footprint needs more than one ray. Prepend refracta_common.cl, (with surfaces)
// refracta_surfaces.cl and view_surfaces.cl, view_caustic.cl and view_pass.cl (the legs,
// refracta_view_march). Documentation/Physics.md, "The view pass", "Glass in the view pass" and
// "Glass edges: supersampling".
//
// A pixel is the path of its centre ray (refracta_view_path). With dielectric surfaces
// (REFRACTA_DIELECTRIC) and `supersampling` n > 1, a pixel whose footprint holds an edge of glass
// (refracta_view_footprint_aliases) is the mean of the paths through the centres of an n x n grid
// over its footprint instead: the reflections and refractions seen there change within the pixel,
// and its one centre ray aliases them into speckle (Benchmarks.md, "The ball's rim"). The choice
// and the sample positions are fixed, so the image stays deterministic.

// A leg still to follow: where it starts, its direction, its weight in the pixel.
typedef struct
{
  float3 origin, d, weight;
  int depth; // interfaces met before this leg
  int body;  // the glass body it travels in, or -1 (the grid's medium)
} refracta_view_branch;

#ifdef REFRACTA_HAS_SURFACES
// Surface-frame vector -> grid-local normal: the map grid-local -> surface frame has linear part
// M (rows m0..m2); normals transform with M^T.
inline float3 refracta_view_normal_to_local(float3 n, float4 m0, float4 m1, float4 m2)
{
  return normalize(n.x * m0.xyz + n.y * m1.xyz + n.z * m2.xyz);
}
#endif

#ifdef REFRACTA_DIELECTRIC
// Dielectric interfaces (Documentation/Physics.md, "Glass in the view pass"): at a triangle of
// kind REFRACTA_SURFACE_DIELECTRIC the path splits into the Fresnel-reflected and the refracted
// leg (Snell's law and the unpolarised Fresnel reflectance with the shading normal; total
// internal reflection gives R = 1 and no refracted leg). Basic radiance L / n^2 is conserved
// through a refraction, so the legs carry the weights R and 1 - R. Up to REFRACTA_SPLIT_DEPTH
// interfaces both legs are followed (a depth-first stack); deeper, only the leg of larger weight,
// carrying the path's whole weight (the other's weight is given to it): this keeps the image
// deterministic and noise-free, and its error was measured against deep splitting
// (Documentation/Physics.md). A path that meets more than REFRACTA_MAX_INTERFACES interfaces is
// dropped (adds nothing), like a ray trapped by the step cap.
#ifndef REFRACTA_SPLIT_DEPTH
#define REFRACTA_SPLIT_DEPTH 1
#endif
#ifndef REFRACTA_MAX_INTERFACES
#define REFRACTA_MAX_INTERFACES 16
#endif

// Both legs at a dielectric hit: the incident unit direction d meets triangle tri at (u, v). Out:
// the reflected and (when *refracts) the refracted unit directions, the reflectance R, and the
// geometric normal on the incident side (for offsetting the new origins). As in
// refracta_dielectric_sample, the shading normal is used unless it would send a leg to the wrong
// side of the triangle's plane (or faces away from d): then both legs use the geometric normal.
inline float refracta_view_dielectric_split(float3 d, int tri, float u, float v,
  __global const float4* triangles, __global const int* triInfo,
  __global const float4* triNormals, __global const float2* interfaces, float4 m0, float4 m1,
  float4 m2, float3* reflected, float3* refracted, bool* refracts, float3* incidentSide)
{
  const float3 ng =
    refracta_view_normal_to_local(refracta_triangle_normal(triangles, tri), m0, m1, m2);
  const float3 ns =
    refracta_view_normal_to_local(refracta_shading_normal(triNormals, tri, u, v), m0, m1, m2);
  const float2 indices =
    interfaces[triInfo[REFRACTA_TRIANGLE_INFO_INTS * tri + REFRACTA_TRIANGLE_INFO_SURFACE]];
  const bool entering = dot(d, ng) < 0.0f;
  const float etaI = entering ? indices.y : indices.x;
  const float etaT = entering ? indices.x : indices.y;
  const float3 fg = entering ? ng : -ng;
  const float3 fs = entering ? ns : -ns;
  *incidentSide = fg;
  float3 nf = dot(d, fs) < 0.0f ? fs : fg;
  float r = 1.0f;
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    r = refracta_fresnel_reflectance(-dot(d, nf), etaI, etaT);
    *reflected = refracta_reflect(d, nf);
    *refracts = refracta_refract(d, nf, etaI / etaT, refracted);
    if (!*refracts)
    {
      r = 1.0f;
    }
    const bool good = dot(*reflected, fg) > 0.0f && (!*refracts || dot(*refracted, fg) < 0.0f);
    if (good || attempt == 1)
    {
      break;
    }
    nf = fg;
  }
  return r;
}
#endif


// A camera ray through image point (sx, sy) in [-1, 1]^2.
inline void refracta_view_camera_ray(const float4 eye, const float4 camU, const float4 camV,
  const float4 camW, const float sx, const float sy, float3* origin, float3* d)
{
#ifdef REFRACTA_PARALLEL
  *origin = eye.xyz + sx * camU.xyz + sy * camV.xyz;
  *d = normalize(camW.xyz);
#else
  *origin = eye.xyz;
  *d = normalize(camW.xyz + sx * camU.xyz + sy * camV.xyz);
#endif
}

#ifdef REFRACTA_DIELECTRIC
// Whether pixel (pi, pj)'s footprint holds an edge of glass: its four corner rays and its centre
// ray, straight from the eye to the first surface before the pixel's depth limit (the test
// ignores grad n: it only chooses where to take more rays), do not all meet the same dielectric
// surface or all none, or one of them meets a dielectric surface at grazing incidence: |cos| of
// the angle of incidence below grazingCosine, where the reflectance and the refracted direction
// change fastest (a ray at r from the axis of a distant ball of radius R meets it at
// cos = sqrt(1 - (r / R)^2): 0.5 marks the outer 13% of its radius, 1 every pixel of glass).
inline bool refracta_view_footprint_aliases(__global const float4* nodes, const int nodeCount,
  __global const float4* triangles, const float4 m0, const float4 m1, const float4 m2,
  __global const int* triInfo, const float4 eye, const float4 camU, const float4 camV,
  const float4 camW, const int pi, const int pj, const int width, const int height,
  const float limit, const float grazingCosine)
{
  int firstGlass = -2;
  for (int k = 0; k < 5; ++k)
  {
    const float fx = k < 4 ? (float)(pi + (k & 1)) : (float)pi + 0.5f;
    const float fy = k < 4 ? (float)(pj + (k >> 1)) : (float)pj + 0.5f;
    float3 origin, d;
    refracta_view_camera_ray(eye, camU, camV, camW, 2.0f * fx / (float)width - 1.0f,
      2.0f * fy / (float)height - 1.0f, &origin, &d);
    float t, u, v;
    const int tri = refracta_view_surface_hit(nodes, nodeCount, triangles, m0, m1, m2, origin, d,
      limit, &t, &u, &v);
    const bool glass = tri >= 0 &&
      triInfo[REFRACTA_TRIANGLE_INFO_INTS * tri + REFRACTA_TRIANGLE_INFO_KIND] ==
        REFRACTA_SURFACE_DIELECTRIC;
    const int surface =
      glass ? triInfo[REFRACTA_TRIANGLE_INFO_INTS * tri + REFRACTA_TRIANGLE_INFO_SURFACE] : -1;
    if (k > 0 && surface != firstGlass)
    {
      return true;
    }
    firstGlass = surface;
    if (glass &&
      fabs(dot(d, refracta_view_normal_to_local(refracta_triangle_normal(triangles, tri), m0, m1,
             m2))) < grazingCosine)
    {
      return true;
    }
  }
  return false;
}
#endif

// What a path needs beyond its legs: the background and the surfaces' materials.
#define REFRACTA_VIEW_PATH_PARAMS                                                                 \
  REFRACTA_VIEW_LEG_PARAMS, const float4 background, __global const float *environment,          \
    const int2 envSize, const float4 envRight, const float4 envUp, const float4 envFront,         \
    __global const float *surfaceAlbedo,                                                         \
    __global const float *surfaceIrradiance, __global const float *surfaceCorners,               \
    __global const float4 *triNormals, __global const float2 *interfaces
#define REFRACTA_VIEW_PATH_ARGS                                                                   \
  REFRACTA_VIEW_LEG_ARGS, background, environment, envSize, envRight, envUp, envFront,           \
    surfaceAlbedo, surfaceIrradiance, surfaceCorners, triNormals, interfaces

// One path's result: its radiance, the RGB transmittance of the legs that end in the background,
// the part of the radiance that is the background seen through them, the path length to the
// first surface its primary ray meets (INFINITY: none) and its steps.
typedef struct
{
  float3 radiance, transmittance, background;
  float firstDepth;
  uint count;
} refracta_view_sample;

// The path of the ray from `origin` along unit d: its legs (refracta_view_march), split at glass.
inline refracta_view_sample refracta_view_path(
  REFRACTA_VIEW_PATH_PARAMS, const float3 origin, const float3 d, const float limit)
{
  float3 lo, hi;
  refracta_domain(dims, spacing, &lo, &hi);
  refracta_view_sample out;
  out.radiance = (float3)(0.0f);
  out.transmittance = (float3)(0.0f); // of the legs that end in the background
  out.background = (float3)(0.0f);
  out.firstDepth = INFINITY;
  out.count = 0;
  // The depth-first stack of legs still to follow; the primary ray first. The depth limit (opaque
  // geometry of a render window, along the primary ray) applies to the primary leg only.
  refracta_view_branch current;
  current.origin = origin;
  current.d = d;
  current.weight = (float3)(1.0f);
  current.depth = 0;
  current.body = -1;
#ifdef REFRACTA_DIELECTRIC
  refracta_view_branch stack[REFRACTA_SPLIT_DEPTH + 1];
  int stackSize = 0;
  const float offset = 1e-3f * fmin(spacing.x, fmin(spacing.y, spacing.z));
#endif
  bool primary = true;
  for (;;)
  {
    const refracta_view_leg leg = refracta_view_march(
      REFRACTA_VIEW_LEG_ARGS, current.origin, current.d, primary ? limit : INFINITY, current.body);
    out.count += leg.count;
    out.radiance += current.weight * leg.radiance;
    const float3 w = current.weight * leg.transmittance;
    if (primary && leg.surfaceTri >= 0 && !leg.stoppedEarly)
    {
      out.firstDepth = leg.surfaceDepth;
    }
    primary = false;
    bool next = false; // whether `current` holds a new leg
#ifdef REFRACTA_HAS_SURFACES
    if (leg.surfaceTri >= 0 && !leg.stoppedEarly)
    {
#ifdef REFRACTA_DIELECTRIC
      const int kind =
        triInfo[REFRACTA_TRIANGLE_INFO_INTS * leg.surfaceTri + REFRACTA_TRIANGLE_INFO_KIND];
      if (kind == REFRACTA_SURFACE_DIELECTRIC)
      {
        if (current.depth < REFRACTA_MAX_INTERFACES)
        {
          float3 reflected, refracted, fg;
          bool refracts;
          const float r = refracta_view_dielectric_split(leg.d, leg.surfaceTri, leg.surfaceU,
            leg.surfaceV, triangles, triInfo, triNormals, interfaces, toSurface0, toSurface1,
            toSurface2, &reflected, &refracted, &refracts, &fg);
          refracta_view_branch a, b; // a: reflected, b: refracted
          a.origin = leg.surfacePoint + offset * fg;
          a.d = reflected;
          a.depth = current.depth + 1;
          b.origin = leg.surfacePoint - offset * fg;
          b.d = refracted;
          b.depth = current.depth + 1;
          a.body = current.body;
          // Entering when it leaves the triangle's outward side behind (fg is the incident side).
          const float3 outward =
            refracta_view_normal_to_local(refracta_triangle_normal(triangles, leg.surfaceTri),
              toSurface0, toSurface1, toSurface2);
          b.body = refracta_body_after_refraction(bodies,
            triInfo[REFRACTA_TRIANGLE_INFO_INTS * leg.surfaceTri + REFRACTA_TRIANGLE_INFO_SURFACE],
            dot(fg, outward) > 0.0f);
          if (refracts && current.depth < REFRACTA_SPLIT_DEPTH)
          {
            a.weight = r * w;
            b.weight = (1.0f - r) * w;
            stack[stackSize++] = a;
            current = b;
          }
          else
          {
            // One leg with the path's whole weight: the likelier one.
            current = (!refracts || r > 0.5f) ? a : b;
            current.weight = w;
          }
          next = true;
        }
      }
      else
#endif
      {
        const float3 normal = refracta_view_normal_to_local(
          refracta_triangle_normal(triangles, leg.surfaceTri), toSurface0, toSurface1, toSurface2);
        float3 ls = refracta_view_surface_radiance(triInfo, surfaceAlbedo, surfaceIrradiance,
          surfaceCorners, leg.surfaceTri, leg.surfaceU, leg.surfaceV, leg.d, normal);
        // Basic radiance: a surface inside the medium is seen divided by n^2 (1 outside the box).
        const bool inBox = all(leg.surfacePoint >= lo) && all(leg.surfacePoint <= hi);
#ifdef REFRACTA_INDEX_WEIGHT
        if (inBox)
        {
          const float nHit = refracta_sample1(
            refractiveIndex, dims, refracta_to_voxel(leg.surfacePoint, spacing));
          ls *= 1.0f / (nHit * nHit);
        }
#elif defined(REFRACTA_SOURCE_SCALE)
        ls *= inBox ? REFRACTA_SOURCE_SCALE : 1.0f;
#endif
        out.radiance += w * ls; // opaque: nothing behind the surface shows through
      }
    }
    else
#endif
    {
      if (leg.seesBackground)
      {
        const float3 seen = w *
          refracta_background(leg.d, background, environment, envSize, envRight, envUp, envFront);
        out.radiance += seen;
        out.background += seen;
      }
      out.transmittance += w; // what shows through: the background, or geometry behind the limit
    }
    if (!next)
    {
#ifdef REFRACTA_DIELECTRIC
      if (stackSize > 0)
      {
        current = stack[--stackSize];
        continue;
      }
#endif
      break;
    }
  }
  return out;
}

// The view-pass kernels' parameters (refracta_view_pass here, refracta_view_pass_lanes in
// view_lanes.cl: one argument list for the host to set).
#define REFRACTA_VIEW_KERNEL_PARAMS                                                                \
  const int4 dims, const float4 spacing, __global const float* extinction,                         \
    __global const float* emission, __global const float* anisotropy,                              \
    __global const float* refractiveIndex, __global const float* gradient,                         \
    __global const float* radiance, __global const float* radianceDirection,                       \
    __global const float* multiple, const float4 eye, const float4 camU, const float4 camV,        \
    const float4 camW, const int width, const int height, const float stepLength,                  \
    const int maxSteps, const float cutoff, const float4 background,                               \
    __global const float* environment, const int2 envSize, const float4 envRight,                  \
    const float4 envUp, const float4 envFront, __global const float* depthLimit,                   \
    __global const uchar* occupancy, const int4 cellDims, const int4 activeLo,                     \
    const int4 activeHi, const uint skipMask, __global const float4* nodes,                        \
    const int nodeCount, __global const float4* triangles, __global const int* triInfo,            \
    __global const float* surfaceAlbedo, __global const float* surfaceIrradiance,                  \
    __global const float* surfaceCorners, __global const float4* triNormals,                       \
    __global const float2* interfaces,                                                             \
    const float4 toSurface0, const float4 toSurface1, const float4 toSurface2,                     \
    __global float* hdr, __global uint* steps, __global float* transmittanceOut,                   \
    __global float* backgroundOut, __global float* surfaceDepthOut,                                \
    __global const float4* bodies, __global const int* causticBricks,                              \
    __global const float* causticRadiance, __global const float* causticDirection,                 \
    const int causticSub, const int supersampling,                                                 \
    const float grazingCosine, volatile __global int* supersampledPixels,                          \
    __global const uchar* cutLinks

__kernel void refracta_view_pass(REFRACTA_VIEW_KERNEL_PARAMS)
{
  const int pi = (int)get_global_id(0);
  const int pj = (int)get_global_id(1);
  if (pi >= width || pj >= height)
  {
    return;
  }
  const size_t pixel = (size_t)pi + (size_t)width * (size_t)pj;
#ifdef REFRACTA_HAS_DEPTH_LIMIT
  const float limit = depthLimit[pixel];
#else
  const float limit = INFINITY;
#endif
  float3 origin, d;
  refracta_view_camera_ray(eye, camU, camV, camW, 2.0f * ((float)pi + 0.5f) / (float)width - 1.0f,
    2.0f * ((float)pj + 0.5f) / (float)height - 1.0f, &origin, &d);
  const refracta_view_sample centre = refracta_view_path(REFRACTA_VIEW_PATH_ARGS, origin, d, limit);
  float3 radianceSum = centre.radiance;
  float3 transmittance = centre.transmittance;
  float3 backgroundSum = centre.background;
  uint count = centre.count;
#ifdef REFRACTA_DIELECTRIC
  if (supersampling > 1 &&
    refracta_view_footprint_aliases(nodes, nodeCount, triangles, toSurface0, toSurface1,
      toSurface2, triInfo, eye, camU, camV, camW, pi, pj, width, height, limit, grazingCosine))
  {
    // The mean over an n x n grid of the footprint; with n odd its middle point is the centre ray.
    const int n = supersampling;
    radianceSum = transmittance = backgroundSum = (float3)(0.0f);
    for (int b = 0; b < n; ++b)
    {
      for (int a = 0; a < n; ++a)
      {
        if ((n & 1) && a == n / 2 && b == n / 2)
        {
          radianceSum += centre.radiance;
          transmittance += centre.transmittance;
          backgroundSum += centre.background;
          continue;
        }
        refracta_view_camera_ray(eye, camU, camV, camW,
          2.0f * ((float)pi + ((float)a + 0.5f) / (float)n) / (float)width - 1.0f,
          2.0f * ((float)pj + ((float)b + 0.5f) / (float)n) / (float)height - 1.0f, &origin, &d);
        const refracta_view_sample s =
          refracta_view_path(REFRACTA_VIEW_PATH_ARGS, origin, d, limit);
        radianceSum += s.radiance;
        transmittance += s.transmittance;
        backgroundSum += s.background;
        count += s.count;
      }
    }
    radianceSum /= (float)(n * n);
    transmittance /= (float)(n * n);
    backgroundSum /= (float)(n * n);
    atomic_inc(supersampledPixels);
  }
#endif
  surfaceDepthOut[pixel] = centre.firstDepth;
  // A multiplication, not '/ 3': OpenCL lets a division be 2.5 ulp off, and NVIDIA's driver
  // rounds 3 / 3 above 1, which made the alpha of a clear pixel -1e-7 (clamped all the same).
  const float alpha =
    clamp(1.0f - (transmittance.x + transmittance.y + transmittance.z) * (1.0f / 3.0f), 0.0f, 1.0f);
  vstore4((float4)(radianceSum, alpha), pixel, hdr);
  steps[pixel] = count;
  vstore4((float4)(transmittance, 0.0f), pixel, transmittanceOut);
  vstore4((float4)(backgroundSum, 0.0f), pixel, backgroundOut);
}
