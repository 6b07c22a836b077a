// light_rays.cl: single scattering by straight light rays (vtkLightRaySingleScattering).
// Needs refracta_common.cl and refracta_surfaces.cl before it.
//
// The unscattered light at a point x is found without noise: for every light, a straight ray from
// x towards the light, its optical depth integrated voxel piece by voxel piece with sigma_t sampled
// (trilinearly) at each piece's midpoint, as the photon pass walks its rays, and skipped through
// macro cells where nothing attenuates (their largest sigma_t, grown by one voxel for the stencil),
// and a shadow test against the surfaces' BVH. What comes out of one evaluation is
//   phi  (RGB): the fluence of the unscattered beams, sum over lights of E_l T_l V_l;
//   flux (xyz): sum over lights of (phi_l.r + phi_l.g + phi_l.b) w_l, w_l the light's travel
//               direction: the weight of the mean direction the view pass's phase function needs.
// The paper's source radiance (Ren et al. 2008, eq. 1) is phi / (4 pi) for isotropic scattering;
// the lighting volume stores S1 = sigma_s phi like the photon pass.
//
// Lights: LR_LIGHT_FLOAT4S float4 per light, made by vtkLightRaySingleScattering on the host:
//   [0] position (grid-local; unused for directional), w = 1 positional, 0 directional
//   [1] axis: travel direction (directional) or spot axis (spot), w = cos of the cone (< -1.5: none)
//   [2] colour x intensity (irradiance E for directional, intensity I for positional), w = exponent
//   [3] x = extent (sphere radius, grid-local units; sin of the angular radius for directional),
//       y = quadrature directions for an extended light (>= 1), z = the light's lobe (below)
//
// Lobes (-DLR_LOBES=K, K >= 2): the lights fall into K groups, and each group's S1 and mean
// direction are stored apart as well as the sum over all lights, because the view pass shades S1
// with the phase function about one mean direction: right for light from one side, wrong where
// two lights cross (their mean points between them). Every output is then LR_BLOCKS blocks of one
// field each (3 floats per voxel, sample or point): block 0 the sum of all lights (Radiance,
// RadianceDirection), block 1 + k lobe k (vtkRefractaLightingVolume::RadianceLobeName(k)).
#define LR_LIGHT_FLOAT4S 4
#ifndef LR_LOBES
#define LR_LOBES 1
#endif
#define LR_BLOCKS (LR_LOBES > 1 ? LR_LOBES + 1 : 1)
#define LR_MACRO 8 /* voxels per macro-cell edge: empty-space skipping */
#define LR_DEEP 40.0f /* optical depth past which a ray is dark (e^-40) */
#define LR_GOLDEN_ANGLE 2.39996323f
#ifndef LR_NODE_CUTS
#define LR_NODE_CUTS 0 /* 1: pieces cut at node planes (set from the medium, as for photons) */
#endif

typedef struct
{
  __global const float* extinction; // RGB per voxel
  __global const float* macro;      // largest sigma_t per macro cell
  int4 dims, macroDims;
  float4 spacing;
  float3 lo, hi;
  __global const float4* nodes; // surfaces (nodeCount 0: none)
  __global const float4* triangles;
  int nodeCount;
  float4 frame0, frame1, frame2; // grid-local -> surface frame rows
  float surfaceEpsilon;
} lr_scene;

// Optical depth (RGB) along o + t d, t in [0, tMax], d unit: voxel piece by voxel piece, whole
// macro cells at a time where their largest sigma_t (over the cell grown by one voxel) is 0.
// With LR_NODE_CUTS (where sigma_t bends steeply at nodes, as the photon walk's
// REFRACTA_NODE_CUTS) the pieces are cut at the node planes too, half voxels: the photon pass's
// optical depth, piece for piece.
inline float3 lr_optical_depth(const lr_scene* s, float3 o, float3 d, float tMax)
{
  float t0, t1;
  float3 tau = (float3)(0.0f);
  if (!refracta_intersect_box(o, d, s->lo, s->hi, &t0, &t1))
  {
    return tau;
  }
  t1 = fmin(t1, tMax);
  const float h = fmin(fmin(s->spacing.x, s->spacing.y), s->spacing.z);
  const float nudge = 1e-4f * h;
  const float3 inv = (float3)(1.0f) / d;
  const int3 dims = s->dims.xyz;
  const int cap = (LR_NODE_CUTS ? 8 : 4) * (dims.x + dims.y + dims.z) + 16; // never a hang
  float t = t0;
  for (int step = 0; step < cap && t < t1; ++step)
  {
    // The cell the ray leaves u into (on a face, the one beyond it: floor along d >= 0, ceil - 1
    // along d < 0), and its exit from u in index units, so that the exit always lies ahead of u.
    // The exit computed in world units from a rounded cell did not: a ray from a voxel's centre
    // along its node plane (|d.x| of 1e-16 to 1e-5, as a frame turned by 90 degrees gives) sat
    // on the plane, took the cell behind it and its exit at the plane itself: steps of `nudge`
    // until the cap, the optical depth cut short and the image up to 4x too bright.
    const float3 u = (o + d * (t + nudge) - s->lo) / s->spacing.xyz;
    const int3 back = d < (float3)(0.0f);
    const int3 v =
      clamp(convert_int3(select(floor(u), ceil(u) - 1.0f, back)), (int3)(0), dims - 1);
    const int3 mv = v / LR_MACRO;
    const float m =
      s->macro[mv.x + s->macroDims.x * (mv.y + s->macroDims.y * (size_t)mv.z)];
#if LR_NODE_CUTS
    // Half-voxel cells (node planes lie at the voxels' middles), 2 per voxel along an axis.
    const int3 halves = clamp(
      convert_int3(select(floor(2.0f * u), ceil(2.0f * u) - 1.0f, back)), (int3)(0), 2 * dims - 1);
    const int3 cellLo = m > 0.0f ? halves : 2 * mv * LR_MACRO;
    const int3 cellHi = m > 0.0f ? halves + 1 : 2 * min((mv + 1) * LR_MACRO, dims);
    const float3 bound = 0.5f * convert_float3(select(cellLo, cellHi, d > (float3)(0.0f)));
#else
    const int3 cellLo = m > 0.0f ? v : mv * LR_MACRO;
    const int3 cellHi = m > 0.0f ? v + 1 : min((mv + 1) * LR_MACRO, dims);
    const float3 bound = convert_float3(select(cellLo, cellHi, d > (float3)(0.0f)));
#endif
    const float3 te = select((t + nudge) + (bound - u) * s->spacing.xyz * inv, (float3)(INFINITY),
      d == (float3)(0.0f));
    float exitT = fmin(fmin(te.x, te.y), te.z);
    exitT = fmin(fmax(exitT, t + nudge), t1);
    if (m > 0.0f)
    {
      // sigma_t at the piece's midpoint, trilinear: the photon pass's and view pass's medium.
      const float3 mid = refracta_to_voxel(o + d * (0.5f * (t + exitT)), s->spacing);
      tau += refracta_sample3(s->extinction, s->dims, mid) * (exitT - t);
      if (fmax(fmax(tau.x, tau.y), tau.z) > LR_DEEP)
      {
        break;
      }
    }
    t = exitT;
  }
  return tau;
}

// Whether a surface blocks o + t d, t in (eps, tMax), o and d grid-local.
inline bool lr_shadowed(const lr_scene* s, float3 o, float3 d, float tMax)
{
  if (s->nodeCount <= 0)
  {
    return false;
  }
  const float3 so = (float3)(dot(s->frame0.xyz, o) + s->frame0.w,
    dot(s->frame1.xyz, o) + s->frame1.w, dot(s->frame2.xyz, o) + s->frame2.w);
  const float3 sd = (float3)(dot(s->frame0.xyz, d), dot(s->frame1.xyz, d), dot(s->frame2.xyz, d));
  return refracta_bvh_occluded(
    s->nodes, s->nodeCount, s->triangles, so, sd, s->surfaceEpsilon, tMax);
}

// Transmittance x visibility of one straight ray.
inline float3 lr_transmittance(const lr_scene* s, float3 o, float3 d, float tMax)
{
  if (lr_shadowed(s, o, d, tMax))
  {
    return (float3)(0.0f);
  }
  return exp(-lr_optical_depth(s, o, d, tMax));
}

// Direction q of K equal-solid-angle directions (a Fibonacci spiral) in the cap of directions
// within acos(cosMax) of axis a.
inline float3 lr_cap_direction(float3 a, float cosMax, int q, int count)
{
  const float3 helper = fabs(a.x) < 0.9f ? (float3)(1.0f, 0.0f, 0.0f) : (float3)(0.0f, 1.0f, 0.0f);
  const float3 b1 = normalize(cross(helper, a));
  const float3 b2 = cross(a, b1);
  const float c = 1.0f - ((float)q + 0.5f) / (float)count * (1.0f - cosMax);
  const float sn = sqrt(fmax(0.0f, 1.0f - c * c));
  const float phi = LR_GOLDEN_ANGLE * (float)q;
  return c * a + sn * (cos(phi) * b1 + sin(phi) * b2);
}

// Distance from x along unit q to the sphere (centre p, radius r), x outside it.
inline float lr_sphere_distance(float3 x, float3 q, float3 p, float r)
{
  const float3 w = p - x;
  const float b = dot(w, q);
  const float disc = b * b - (dot(w, w) - r * r);
  return disc > 0.0f ? fmax(b - sqrt(disc), 0.0f) : fmax(b, 0.0f);
}

// The weight of light arriving along unit direction q (towards the light): 1 for fluence (normal
// 0), max(n . q, 0) for the irradiance on the side of a surface that unit normal n faces.
inline float lr_cosine(float3 normal, float3 q)
{
  return any(normal != (float3)(0.0f)) ? fmax(dot(normal, q), 0.0f) : 1.0f;
}

// Fluence (RGB) of one light at x and its travel direction there; with a unit `normal`, the
// irradiance on the side of a surface there that the normal faces instead (each direction
// weighted by lr_cosine; a direction of weight 0 is not traced).
inline float3 lr_light_fluence(const lr_scene* s, __global const float4* light, float3 x,
  float minDistance, float3* travel, float3 normal)
{
  const float4 p0 = light[0], p1 = light[1], p2 = light[2], p3 = light[3];
  const int count = max((int)p3.y, 1);
  const float3 colour = p2.xyz;
  if (p0.w < 0.5f)
  {
    // Directional: irradiance E on a plane facing it; a disc of angular radius delta has radiance
    // E / (pi sin^2 delta) over a cap of 2 pi (1 - cos delta).
    *travel = p1.xyz;
    const float3 toLight = -p1.xyz;
    if (!(p3.x > 0.0f) || count == 1)
    {
      const float c = lr_cosine(normal, toLight);
      return c > 0.0f ? colour * c * lr_transmittance(s, x, toLight, INFINITY) : (float3)(0.0f);
    }
    const float sinD = p3.x;
    const float cosD = sqrt(fmax(0.0f, 1.0f - sinD * sinD));
    const float weight = 2.0f * (1.0f - cosD) / (sinD * sinD) / (float)count;
    float3 sum = (float3)(0.0f);
    for (int q = 0; q < count; ++q)
    {
      const float3 dir = lr_cap_direction(toLight, cosD, q, count);
      const float c = lr_cosine(normal, dir);
      sum += c > 0.0f ? c * lr_transmittance(s, x, dir, INFINITY) : (float3)(0.0f);
    }
    return colour * sum * weight;
  }
  const float3 w = p0.xyz - x;
  const float d = fmax(length(w), minDistance);
  const float3 toLight = length(w) > 0.0f ? w / length(w) : (float3)(0.0f, 0.0f, 1.0f);
  *travel = -toLight;
  float falloff = 1.0f;
  if (p1.w > -1.5f)
  {
    const float c = dot(-toLight, p1.xyz);
    falloff = c >= p1.w ? (p2.w > 0.0f ? pow(fmax(c, 0.0f), p2.w) : 1.0f) : 0.0f;
  }
  if (falloff <= 0.0f)
  {
    return (float3)(0.0f);
  }
  const float r = p3.x;
  if (!(r > 0.0f) || count == 1 || d <= r)
  {
    // A delta light (or a point inside the sphere light, where the near field is taken as the
    // delta light's): I / d^2.
    const float c = lr_cosine(normal, toLight);
    return c > 0.0f
      ? colour * (falloff * c / (d * d)) * lr_transmittance(s, x, toLight, length(w))
      : (float3)(0.0f);
  }
  // A sphere of radius r with radiance I / (pi r^2) seen under a cap of 2 pi (1 - cos theta).
  const float sinT = r / d;
  const float cosT = sqrt(fmax(0.0f, 1.0f - sinT * sinT));
  const float omega = 2.0f * REFRACTA_PI * (1.0f - cosT);
  const float weight = falloff / (REFRACTA_PI * r * r) * omega / (float)count;
  float3 sum = (float3)(0.0f);
  for (int q = 0; q < count; ++q)
  {
    const float3 dir = lr_cap_direction(toLight, cosT, q, count);
    const float c = lr_cosine(normal, dir);
    sum += c > 0.0f ? c * lr_transmittance(s, x, dir, lr_sphere_distance(x, dir, p0.xyz, r))
                    : (float3)(0.0f);
  }
  return colour * sum * weight;
}

// The block (head of the file) that light `light`'s light joins besides block 0.
inline int lr_lobe_block(__global const float4* light)
{
  return LR_LOBES > 1 ? 1 + clamp((int)light[3].z, 0, LR_LOBES - 1) : 0;
}

// Zero values and fluxes in every block.
inline void lr_clear_blocks(float3* value, float3* flux)
{
  for (int b = 0; b < LR_BLOCKS; ++b)
  {
    value[b] = flux[b] = (float3)(0.0f);
  }
}

// Adds one light's value `e` (fluence or S1, RGB) travelling along `travel` to block 0 and to its
// lobe's block: the value, and the flux weighted by its channel sum.
inline void lr_add_light(
  __global const float4* light, float3 e, float3 travel, float3* value, float3* flux)
{
  const float3 f = (e.x + e.y + e.z) * travel;
  value[0] += e;
  flux[0] += f;
  const int b = lr_lobe_block(light);
  if (b > 0)
  {
    value[b] += e;
    flux[b] += f;
  }
}

// phi and flux (see the head of the file) at x of every block: of all lights, then of each lobe.
inline void lr_evaluate(const lr_scene* s, __global const float4* lights, int lightCount,
  float3 x, float minDistance, float3* phi, float3* flux)
{
  lr_clear_blocks(phi, flux);
  for (int l = 0; l < lightCount; ++l)
  {
    __global const float4* light = lights + LR_LIGHT_FLOAT4S * l;
    float3 travel;
    const float3 e = lr_light_fluence(s, light, x, minDistance, &travel, (float3)(0.0f));
    lr_add_light(light, e, travel, phi, flux);
  }
}

#define LR_SCENE_ARGS                                                                              \
  __global const float *extinction, __global const float *macro, const int4 dims,                 \
    const int4 macroDims, const float4 spacing, __global const float4 *nodes,                     \
    __global const float4 *triangles, const int nodeCount, const float4 frame0,                   \
    const float4 frame1, const float4 frame2, const float surfaceEpsilon

inline lr_scene lr_make_scene(__global const float* extinction, __global const float* macro,
  int4 dims, int4 macroDims, float4 spacing, __global const float4* nodes,
  __global const float4* triangles, int nodeCount, float4 frame0, float4 frame1, float4 frame2,
  float surfaceEpsilon)
{
  lr_scene s;
  s.extinction = extinction;
  s.macro = macro;
  s.dims = dims;
  s.macroDims = macroDims;
  s.spacing = spacing;
  refracta_domain(dims, spacing, &s.lo, &s.hi);
  s.nodes = nodes;
  s.triangles = triangles;
  s.nodeCount = nodeCount;
  s.frame0 = frame0;
  s.frame1 = frame1;
  s.frame2 = frame2;
  s.surfaceEpsilon = surfaceEpsilon;
  return s;
}

#define LR_MAKE_SCENE()                                                                            \
  lr_make_scene(extinction, macro, dims, macroDims, spacing, nodes, triangles, nodeCount, frame0, \
    frame1, frame2, surfaceEpsilon)

// S1 and its unit mean direction (zero where nothing scatters or no light arrives) at entry `at`
// of every block (`entries` per block) from each block's S1 and flux.
inline void lr_store_blocks(const float3* s1, const float3* flux, size_t at, size_t entries,
  __global float* radiance, __global float* direction)
{
  for (int b = 0; b < LR_BLOCKS; ++b)
  {
    const float len = length(flux[b]);
    const size_t e = at + (size_t)b * entries;
    vstore3(s1[b], e, radiance);
    vstore3(len > 0.0f && (s1[b].x + s1[b].y + s1[b].z) > 0.0f ? flux[b] / len : (float3)(0.0f),
      e, direction);
  }
}

// The lighting volume's arrays from phi and flux at voxel v: S1 = sigma_s phi per block.
inline void lr_store(__global const float* scattering, size_t v, size_t voxelCount,
  const float3* phi, const float3* flux, __global float* radiance, __global float* direction)
{
  const float3 sc = vload3(v, scattering);
  float3 s1[LR_BLOCKS];
  for (int b = 0; b < LR_BLOCKS; ++b)
  {
    s1[b] = sc * fmax(phi[b], (float3)(0.0f));
  }
  lr_store_blocks(s1, flux, v, voxelCount, radiance, direction);
}

// Per-voxel light rays: every voxel that scatters marches one ray per light (and quadrature
// direction) to it. `radiance` and `direction` hold LR_BLOCKS blocks of voxelCount entries.
__kernel void light_rays_voxels(LR_SCENE_ARGS, __global const float* scattering,
  __global const float4* lights, const int lightCount, const float minDistance,
  __global float* radiance, __global float* direction, const ulong voxelCount)
{
  const size_t v = get_global_id(0);
  if (v >= voxelCount)
  {
    return;
  }
  const float3 sc = vload3(v, scattering);
  float3 phi[LR_BLOCKS], flux[LR_BLOCKS];
  lr_clear_blocks(phi, flux);
  if (sc.x > 0.0f || sc.y > 0.0f || sc.z > 0.0f)
  {
    const lr_scene s = LR_MAKE_SCENE();
    const int i = (int)(v % (size_t)dims.x);
    const int j = (int)((v / (size_t)dims.x) % (size_t)dims.y);
    const int k = (int)(v / ((size_t)dims.x * (size_t)dims.y));
    const float3 x = (float3)((float)i, (float)j, (float)k) * spacing.xyz;
    lr_evaluate(&s, lights, lightCount, x, minDistance, phi, flux);
  }
  lr_store(scattering, v, voxelCount, phi, flux, radiance, direction);
}

// ---------------------------------------------------------------------------------------------
// Box means at sharp voxels. Where sigma_t changes steeply within a voxel's box (the ramp of the
// trilinear medium between a dense centre and an empty one), S1 at the centre is not what the
// view pass needs: the light scatters in the ramp, where the centre values (sigma_s = 0 on the
// empty side, phi ~ 0 on the dense side) hold almost none of it. There the voxel gets the mean
// of sigma_s phi over its box instead, the quantity every photon deposit estimates, computed
// without noise: parallel lines along each light's travel direction w, LR_BOX_LINES^2 through
// each face the light enters by, each weighted by the area of the box's projection it stands
// for (the midpoint rule on each face: exact where the integrand is linear over a line's patch,
// within 5% of a double-precision integral at 10 optical depths per voxel under oblique light).
// A line carries the fluence it has on the plane Pi (normal w, LR_BOX_UPSTREAM spacings upstream
// of the box's centre: interpolated between four light rays traced from the corners of the box's
// shadow on Pi by lr_light_fluence, with its transmittance, shadows, spot cone and extended
// lights; lr_far_fluence), loses exp(-optical depth) from Pi to the box (the medium right in
// front of the box, where the fluence changes fast, integrated along each line; a surface there
// shades the line), then through the box loses phi (1 - exp(-sigma_t len)) per piece, cut at the voxel's centre
// planes (the trilinear medium's kinks), sigma_t and the albedo sampled at each piece's midpoint
// as a photon does; a times the loss scatters. The sum divided by the box's volume is the mean.
// A positional light closer than Pi, and a fluence on Pi that a fifth ray at the shadow's centre
// shows is not log-linear there (within LR_BOX_FAR_TOLERANCE), are traced from every line's
// entry instead.
#define LR_BOX_LINES 4
#define LR_BOX_UPSTREAM 4.0f
#define LR_BOX_FAR_TOLERANCE 0.02f
#define LR_BOX_DARK 0.05f

// The fluence at (alpha, beta) in [0, 1]^2 of the square whose corners hold far[0..3] (x, then
// y): bilinear in log phi (exact where the optical depth to the light changes linearly across
// Pi, as behind a uniform layer), bilinear in phi in a channel where a corner is dark.
inline float3 lr_far_fluence(const float3* far, float alpha, float beta)
{
  const float3 linear = mix(mix(far[0], far[1], alpha), mix(far[2], far[3], alpha), beta);
  const int3 dark = far[0] <= 0.0f || far[1] <= 0.0f || far[2] <= 0.0f || far[3] <= 0.0f;
  const float3 lf[4] = { log(fmax(far[0], FLT_MIN)), log(fmax(far[1], FLT_MIN)),
    log(fmax(far[2], FLT_MIN)), log(fmax(far[3], FLT_MIN)) };
  const float3 logLinear = exp(mix(mix(lf[0], lf[1], alpha), mix(lf[2], lf[3], alpha), beta));
  return select(logLinear, linear, dark);
}

// Scattered power (RGB) of one light's beam through the box [lo, lo + h], per unit volume.
inline float3 lr_box_light(const lr_scene* s, __global const float* albedo,
  __global const float4* light, float3 lo, float minDistance, float3* travelOut)
{
  const float3 h = s->spacing.xyz;
  const float3 centre = lo + 0.5f * h;
  const bool positional = light[0].w >= 0.5f;
  const float upstream = LR_BOX_UPSTREAM * fmax(fmax(h.x, h.y), h.z);
  float3 w;
  bool exact = false; // every line's fluence by its own light ray
  if (!positional)
  {
    w = light[1].xyz;
  }
  else
  {
    const float3 away = centre - light[0].xyz;
    w = length(away) > 0.0f ? normalize(away) : (float3)(0.0f, 0.0f, -1.0f);
    exact = length(away) < upstream + length(h);
  }
  *travelOut = w;
  // The plane Pi and the fluence at the corners of the box's shadow on it.
  const float3 origin = centre - upstream * w;
  const float3 u1 = normalize(cross(fabs(w.x) < 0.9f ? (float3)(1.0f, 0.0f, 0.0f)
                                                       : (float3)(0.0f, 1.0f, 0.0f),
    w));
  const float3 u2 = cross(w, u1);
  const float r1 = 0.5f * dot(fabs(u1), h), r2 = 0.5f * dot(fabs(u2), h);
  float3 far[4] = { (float3)(0.0f), (float3)(0.0f), (float3)(0.0f), (float3)(0.0f) };
  if (!exact)
  {
    float3 unused;
    bool lit = false;
    for (int corner = 0; corner < 4; ++corner)
    {
      const float3 q = origin + ((corner & 1) ? r1 : -r1) * u1 + ((corner & 2) ? r2 : -r2) * u2;
      far[corner] = lr_light_fluence(s, light, q, minDistance, &unused, (float3)(0.0f));
      lit = lit || any(far[corner] > (float3)(0.0f));
    }
    // Where the fluence is not log-linear across the shadow (Pi crosses a face of the medium, a
    // shadow's edge), a fifth ray at its centre disagrees with the interpolation: there every
    // line's fluence comes from its own light ray.
    const float3 middle = lr_light_fluence(s, light, origin, minDistance, &unused, (float3)(0.0f));
    const float3 predicted = lr_far_fluence(far, 0.5f, 0.5f);
    // (Differences below LR_BOX_DARK of the light's unattenuated fluence do not count: deep in a
    // shadow the lines carry next to nothing either way.)
    const float3 toCentre = centre - light[0].xyz;
    const float3 unattenuated = positional
      ? light[2].xyz / fmax(dot(toCentre, toCentre), minDistance * minDistance)
      : light[2].xyz;
    exact = any(fabs(predicted - middle) >
      LR_BOX_FAR_TOLERANCE * fmax(fmax(middle, predicted), LR_BOX_DARK * unattenuated));
    if (!lit && !exact)
    {
      return (float3)(0.0f);
    }
  }
  float3 sum = (float3)(0.0f);
  const float wa[3] = { w.x, w.y, w.z };
  const float ha[3] = { h.x, h.y, h.z };
  for (int a = 0; a < 3; ++a)
  {
    if (fabs(wa[a]) < 1e-6f)
    {
      continue; // no line enters through a face parallel to the beam
    }
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const float area = ha[b] * ha[c] * fabs(wa[a]) / (float)(LR_BOX_LINES * LR_BOX_LINES);
    for (int p = 0; p < LR_BOX_LINES; ++p)
    {
      for (int q = 0; q < LR_BOX_LINES; ++q)
      {
        float e[3];
        e[a] = wa[a] > 0.0f ? 0.0f : ha[a];
        e[b] = ((float)p + 0.5f) / (float)LR_BOX_LINES * ha[b];
        e[c] = ((float)q + 0.5f) / (float)LR_BOX_LINES * ha[c];
        const float3 entry = lo + (float3)(e[0], e[1], e[2]);
        float3 phi;
        if (exact)
        {
          float3 unused;
          phi = lr_light_fluence(s, light, entry, minDistance, &unused, (float3)(0.0f));
        }
        else
        {
          const float depth = dot(entry - origin, w); // > 0: Pi lies upstream of the box
          const float3 start = entry - depth * w;
          const float alpha = clamp(0.5f * (dot(start - origin, u1) / r1 + 1.0f), 0.0f, 1.0f);
          const float beta = clamp(0.5f * (dot(start - origin, u2) / r2 + 1.0f), 0.0f, 1.0f);
          // A surface between Pi and the box (a wall in front of a dense body) shades the line.
          phi = lr_shadowed(s, start, w, depth)
            ? (float3)(0.0f)
            : lr_far_fluence(far, alpha, beta) * exp(-lr_optical_depth(s, start, w, depth));
          if (positional)
          {
            const float3 toStart = start - light[0].xyz, toEntry = entry - light[0].xyz;
            phi *= dot(toStart, toStart) / fmax(dot(toEntry, toEntry), minDistance * minDistance);
          }
        }
        if (!any(phi > (float3)(0.0f)))
        {
          continue;
        }
        // Exit distance and the (at most three) centre-plane crossings, in order.
        float tEntry, tExit;
        refracta_intersect_box(entry, w, lo, lo + h, &tEntry, &tExit);
        const float3 inv = (float3)(1.0f) / w;
        float3 cut = select((centre - entry) * inv, (float3)(INFINITY), fabs(w) < 1e-6f);
        cut = select(cut, (float3)(INFINITY), cut <= 0.0f || cut >= tExit);
        // The pieces' ends: the crossings in order (smallest, median, largest), then the exit.
        const float ends[4] = { fmin(fmin(cut.x, cut.y), cut.z),
          fmax(fmin(cut.x, cut.y), fmin(fmax(cut.x, cut.y), cut.z)), fmax(fmax(cut.x, cut.y), cut.z),
          tExit };
        float3 carried = (float3)(1.0f);
        float3 scattered = (float3)(0.0f);
        float t = 0.0f;
        for (int piece = 0; piece < 4; ++piece)
        {
          const float end = fmin(ends[piece], tExit);
          if (!(end > t))
          {
            continue;
          }
          const float3 mid = refracta_to_voxel(entry + w * (0.5f * (t + end)), s->spacing);
          const float3 sigmaT = refracta_sample3(s->extinction, s->dims, mid);
          const float3 lost = carried * (-expm1(-sigmaT * (end - t)));
          scattered += lost * clamp(refracta_sample3(albedo, s->dims, mid), 0.0f, 1.0f);
          carried -= lost;
          t = end;
        }
        sum += area * phi * scattered;
      }
    }
  }
  return sum / (h.x * h.y * h.z);
}

// S1 and the direction at the sharp voxels listed in `voxels` (their linear indices): the box
// mean of sigma_s phi over all lights (and each lobe's); boxRadiance[v'] and boxDirection[v'] by
// list position, in LR_BLOCKS blocks of `count` entries.
__kernel void light_rays_boxes(LR_SCENE_ARGS, __global const float* albedo,
  __global const float4* lights, const int lightCount, const float minDistance,
  __global const ulong* voxels, __global float* boxRadiance, __global float* boxDirection,
  const ulong count)
{
  const size_t n = get_global_id(0);
  if (n >= count)
  {
    return;
  }
  const lr_scene s = LR_MAKE_SCENE();
  const size_t v = voxels[n];
  const int i = (int)(v % (size_t)dims.x);
  const int j = (int)((v / (size_t)dims.x) % (size_t)dims.y);
  const int k = (int)(v / ((size_t)dims.x * (size_t)dims.y));
  const float3 lo = ((float3)((float)i, (float)j, (float)k) - 0.5f) * spacing.xyz;
  float3 s1[LR_BLOCKS], flux[LR_BLOCKS];
  lr_clear_blocks(s1, flux);
  for (int l = 0; l < lightCount; ++l)
  {
    __global const float4* light = lights + LR_LIGHT_FLOAT4S * l;
    float3 travel;
    const float3 e = lr_box_light(&s, albedo, light, lo, minDistance, &travel);
    lr_add_light(light, e, travel, s1, flux);
  }
  lr_store_blocks(s1, flux, n, count, boxRadiance, boxDirection);
}

// phi and flux at arbitrary grid-local points (the samples of the interpolation, the points of
// their gradients and of their error metric), in LR_BLOCKS blocks of pointCount entries.
__kernel void light_rays_points(LR_SCENE_ARGS, __global const float4* points, const int pointCount,
  __global const float4* lights, const int lightCount, const float minDistance,
  __global float4* phiOut, __global float4* fluxOut)
{
  const int p = (int)get_global_id(0);
  if (p >= pointCount)
  {
    return;
  }
  const lr_scene s = LR_MAKE_SCENE();
  float3 phi[LR_BLOCKS], flux[LR_BLOCKS];
  lr_evaluate(&s, lights, lightCount, points[p].xyz, minDistance, phi, flux);
  for (int b = 0; b < LR_BLOCKS; ++b)
  {
    phiOut[(size_t)b * pointCount + p] = (float4)(phi[b], 0.0f);
    fluxOut[(size_t)b * pointCount + p] = (float4)(flux[b], 0.0f);
  }
}

// The direct irradiance (RGB) on surfaces: at each grid-local point with its unit normal, the
// light of every light that reaches it along a straight ray, on each side of the surface:
// weighted by max(n . q, 0) on the front (irradianceOut[2 p]), by max(-n . q, 0) on the back
// (irradianceOut[2 p + 1]), as the photons' atlas keeps the sides apart. A direction lights one
// side only, so each is traced once. vtkLightRaySingleScattering::ComputeSurfaceIrradiance.
__kernel void light_rays_surface_points(LR_SCENE_ARGS, __global const float4* points,
  __global const float4* normals, const int pointCount, __global const float4* lights,
  const int lightCount, const float minDistance, __global float4* irradianceOut)
{
  const int p = (int)get_global_id(0);
  if (p >= pointCount)
  {
    return;
  }
  float3 front = (float3)(0.0f);
  float3 back = (float3)(0.0f);
  const float3 normal = normals[p].xyz;
  if (any(normal != (float3)(0.0f))) // else glass or a degenerate triangle: nothing to light
  {
    const lr_scene s = LR_MAKE_SCENE();
    for (int l = 0; l < lightCount; ++l)
    {
      __global const float4* light = lights + LR_LIGHT_FLOAT4S * l;
      float3 travel;
      front += lr_light_fluence(&s, light, points[p].xyz, minDistance, &travel, normal);
      back += lr_light_fluence(&s, light, points[p].xyz, minDistance, &travel, -normal);
    }
  }
  irradianceOut[2 * p] = (float4)(front, 0.0f);
  irradianceOut[2 * p + 1] = (float4)(back, 0.0f);
}

// Gradient-based interpolation (Ren et al. 2008, eq. 4) at every voxel that scatters:
//   L(x) = sum_S W_j(x) (L_j + (x - x_j) . grad L_j) / sum_S W_j(x),
//   S = { j : |x - x_j| < R_j },  W_j(x) = R_j / |x - x_j|,
// for L = phi (RGB) and flux (xyz). The samples live on the vertices of the levels' regular grids
// (level k: vertex (a, b, c) at origin + h_k (a, b, c), valid radius R_k); `vertexSample` maps each
// level's vertices (offset levelOffset[k], sizes levelSize[k]) to a sample index or -1. Each voxel
// sums over the vertices whose valid sphere holds it: the sum the paper's splats accumulate, read
// here by the voxel (a gather) so that no float atomics are needed and the result is deterministic.
// samples: 8 float4 per sample and block (LR_BLOCKS, the blocks of one sample together): phi,
// flux, dphi/dx, dphi/dy, dphi/dz, dflux/dx, dflux/dy, dflux/dz. The outputs hold LR_BLOCKS blocks
// of voxelCount entries.
// A voxel that no valid sphere covers is computed by its own light rays and counted (uncovered).
__kernel void light_rays_interpolate(LR_SCENE_ARGS, __global const float* scattering,
  __global const float4* lights, const int lightCount, const float minDistance,
  __global const int* vertexSample, __global const int4* levelSize,
  __global const int* levelOffset, __global const float4* levelGrid, const int levelCount,
  __global const float4* samples, __global float* radiance, __global float* direction,
  volatile __global int* uncovered, const ulong voxelCount)
{
  const size_t v = get_global_id(0);
  if (v >= voxelCount)
  {
    return;
  }
  const float3 sc = vload3(v, scattering);
  float3 phi[LR_BLOCKS], flux[LR_BLOCKS];
  lr_clear_blocks(phi, flux);
  if (sc.x > 0.0f || sc.y > 0.0f || sc.z > 0.0f)
  {
    const int i = (int)(v % (size_t)dims.x);
    const int j = (int)((v / (size_t)dims.x) % (size_t)dims.y);
    const int k = (int)(v / ((size_t)dims.x * (size_t)dims.y));
    const float3 x = (float3)((float)i, (float)j, (float)k) * spacing.xyz;
    float weightSum = 0.0f;
    for (int level = 0; level < levelCount; ++level)
    {
      const int4 size = levelSize[level];
      const float4 grid = levelGrid[2 * level];     // origin.xyz, w = valid radius R
      const float4 interval = levelGrid[2 * level + 1]; // h.xyz
      const float radius = grid.w;
      const float3 rel = (x - grid.xyz) / interval.xyz;
      const float3 reach = radius / interval.xyz;
      const int3 first = max(convert_int3(ceil(rel - reach)), (int3)(0));
      const int3 last = min(convert_int3(floor(rel + reach)), size.xyz - 1);
      for (int c = first.z; c <= last.z; ++c)
      {
        for (int b = first.y; b <= last.y; ++b)
        {
          for (int a = first.x; a <= last.x; ++a)
          {
            const int id =
              vertexSample[levelOffset[level] + a + size.x * (b + size.y * c)];
            if (id < 0)
            {
              continue;
            }
            const float3 xj = grid.xyz + (float3)((float)a, (float)b, (float)c) * interval.xyz;
            const float3 dx = x - xj;
            const float dist = length(dx);
            if (dist >= radius)
            {
              continue;
            }
            // W = R / |x - x_j|, bounded where x sits on the sample (its own value then rules).
            const float w = radius / fmax(dist, 1e-4f * radius);
            for (int bl = 0; bl < LR_BLOCKS; ++bl)
            {
              __global const float4* sj = samples + 8 * ((size_t)id * LR_BLOCKS + bl);
              phi[bl] +=
                w * (sj[0].xyz + dx.x * sj[2].xyz + dx.y * sj[3].xyz + dx.z * sj[4].xyz);
              flux[bl] +=
                w * (sj[1].xyz + dx.x * sj[5].xyz + dx.y * sj[6].xyz + dx.z * sj[7].xyz);
            }
            weightSum += w;
          }
        }
      }
    }
    if (weightSum > 0.0f)
    {
      for (int b = 0; b < LR_BLOCKS; ++b)
      {
        phi[b] /= weightSum;
        flux[b] /= weightSum;
      }
    }
    else
    {
      const lr_scene s = LR_MAKE_SCENE();
      lr_evaluate(&s, lights, lightCount, x, minDistance, phi, flux);
      atomic_inc(uncovered);
    }
  }
  lr_store(scattering, v, voxelCount, phi, flux, radiance, direction);
}
