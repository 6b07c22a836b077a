// view_surfaces.cl: opaque surfaces seen by the view pass (view_pass.cl, -DREFRACTA_HAS_SURFACES).
// Prepend refracta_common.cl and refracta_surfaces.cl (the BVH, the triangle test and the texel
// layout).
//
// The view pass marches in the medium's grid-local frame; the surfaces' flattened arrays are in
// the "surface frame" (world minus vtkRefractaBVH::GetFrameOrigin()). The host computes, in
// double, the affine map grid-local -> surface frame and passes its three rows (toSurface0..2:
// xyz the linear part's row, w the translation). A segment or ray is mapped point by point, so its
// hit parameter is the same fraction of the local segment whatever the map's scale.
//
// Shading (Documentation/Physics.md, "Surfaces in the view pass"): a Lambertian surface with
// irradiance E and albedo rho sends the radiance L = E rho / pi in every direction of the side E
// arrived on (the atlas keeps the sides apart: refracta_sided_texel; a view ray sees the side it
// comes from).
// E comes from the photon pass per texel (flux / texel area, a piecewise-constant and noisy
// estimate); it is reconstructed at the hit point by linear interpolation within the hit texel
// between values at the texel's three corners, each corner's value the mean of the texels of the
// same triangle that touch it (up to 6). Around an interior lattice vertex those texels' centroids
// lie symmetrically, so a linear irradiance is reproduced exactly there; the reconstruction is
// continuous inside a triangle and averages ~6 texels per corner (less photon noise). At the
// triangle's own three corners the value is the host's (surfaceCorners, 9 floats per triangle):
// the area-weighted mean of the corner texels of every triangle of the mesh sharing that point
// within 30 degrees (vtkRefractaSurfaceSet::ComputeCornerIrradiance), so a mesh finer than its
// texels (one texel per triangle) is shaded continuously across triangles from ~6 of them per
// corner instead of piecewise constant from one. Lattice vertices on a triangle's edges between
// its corners average one-sidedly: a first-order bias of about a third of a texel times the
// gradient there. -DREFRACTA_SURFACE_NEAREST instead reads the hit texel alone. The albedo is the
// hit texel's (never blurred: checker edges stay sharp).

#ifdef REFRACTA_HAS_SURFACES

// Texel index of cell (i, j) of a subdivision n (refracta_texel_index's layout): the upright
// sub-triangle, or the inverted one above it.
inline int refracta_view_texel(int i, int j, int n, int inverted)
{
  return j * (2 * n - j) + 2 * i + inverted;
}

// Irradiance of `texel` on one side: `sided` is the irradiance buffer offset by that side's
// first value (3 side floats, refracta_view_surface_irradiance); a texel's sides lie side by side.
inline float3 refracta_view_texel_irradiance(__global const float* sided, long texel)
{
  return vload3(refracta_sided_texel(texel, 0), sided);
}

// Mean irradiance (on one side, see refracta_view_texel_irradiance) of the texels of one
// triangle (first texel `first`, subdivision n) that touch lattice vertex (p, q), p + q <= n.
inline float3 refracta_view_vertex_irradiance(
  __global const float* irradiance, int first, int n, int p, int q)
{
  float3 sum = (float3)(0.0f);
  int count = 0;
  if (p + q <= n - 1)
  {
    // corner (0, 0)
    sum += refracta_view_texel_irradiance(irradiance, first + refracta_view_texel(p, q, n, 0));
    ++count;
  }
  if (p >= 1 && p - 1 + q <= n - 1)
  {
    // corner (1, 0)
    sum += refracta_view_texel_irradiance(irradiance, first + refracta_view_texel(p - 1, q, n, 0));
    ++count;
  }
  if (q >= 1)
  {
    // corner (0, 1)
    sum += refracta_view_texel_irradiance(irradiance, first + refracta_view_texel(p, q - 1, n, 0));
    ++count;
  }
  if (p >= 1 && p - 1 + q <= n - 2)
  {
    sum += refracta_view_texel_irradiance(irradiance, first + refracta_view_texel(p - 1, q, n, 1));
    ++count;
  }
  if (q >= 1 && p + q - 1 <= n - 2)
  {
    sum += refracta_view_texel_irradiance(irradiance, first + refracta_view_texel(p, q - 1, n, 1));
    ++count;
  }
  if (p >= 1 && q >= 1 && p + q - 2 <= n - 2)
  {
    sum +=
      refracta_view_texel_irradiance(irradiance, first + refracta_view_texel(p - 1, q - 1, n, 1));
    ++count;
  }
  return count > 0 ? sum / (float)count : sum;
}

// Value at lattice vertex (p, q): at the triangle's own corners the host's shared value (when
// `corners`, the triangle's 9 floats, is given), elsewhere refracta_view_vertex_irradiance.
inline float3 refracta_view_lattice_irradiance(__global const float* irradiance,
  __global const float* corners, int first, int n, int p, int q)
{
  if (corners && q == 0 && (p == 0 || p == n))
  {
    return vload3(p == 0 ? 0 : 1, corners);
  }
  if (corners && p == 0 && q == n)
  {
    return vload3(2, corners);
  }
  return refracta_view_vertex_irradiance(irradiance, first, n, p, q);
}

// Irradiance at barycentric (u, v) of a triangle's texels (first texel `first`, subdivision n;
// its shared corner values `corners`, or 0 to keep the corners to this triangle's texels; see the
// file comment).
inline float3 refracta_view_atlas_irradiance(__global const float* irradiance,
  __global const float* corners, int first, int n, float u, float v)
{
#ifdef REFRACTA_SURFACE_NEAREST
  return refracta_view_texel_irradiance(irradiance, first + refracta_texel_index(u, v, n));
#else
  // The hit texel's cell (i, j) and orientation: refracta_texel_index's arithmetic, step for
  // step, so that the cell is the texel whose albedo is read.
  const float a = clamp(u * (float)n, 0.0f, (float)n);
  const float b = clamp(v * (float)n, 0.0f, (float)n);
  const int j = min((int)floor(b), n - 1);
  int i = min((int)floor(a), n - 1);
  int inverted = 0;
  if (i + j > n - 1)
  {
    i = n - 1 - j;
  }
  else
  {
    inverted = (i + j <= n - 2 && a + b > (float)(i + j + 1)) ? 1 : 0;
  }
  if (inverted == 0)
  {
    // Corners (i, j), (i + 1, j), (i, j + 1).
    const float wa = clamp(a - (float)i, 0.0f, 1.0f);
    const float wb = clamp(b - (float)j, 0.0f, 1.0f - wa);
    return (1.0f - wa - wb) *
      refracta_view_lattice_irradiance(irradiance, corners, first, n, i, j) +
      wa * refracta_view_lattice_irradiance(irradiance, corners, first, n, i + 1, j) +
      wb * refracta_view_lattice_irradiance(irradiance, corners, first, n, i, j + 1);
  }
  // Corners (i + 1, j), (i, j + 1), (i + 1, j + 1).
  const float wa = clamp((float)(i + 1) - a, 0.0f, 1.0f); // weight of (i, j + 1)
  const float wb = clamp((float)(j + 1) - b, 0.0f, 1.0f - wa); // weight of (i + 1, j)
  return wa * refracta_view_lattice_irradiance(irradiance, corners, first, n, i, j + 1) +
    wb * refracta_view_lattice_irradiance(irradiance, corners, first, n, i + 1, j) +
    (1.0f - wa - wb) *
    refracta_view_lattice_irradiance(irradiance, corners, first, n, i + 1, j + 1);
#endif
}

// Irradiance at barycentric (u, v) of triangle `tri` on `side` (0 front, 1 back): the atlas,
// plus with the caustic atlas (REFRACTA_CAUSTIC_SUBDIVISION c > 1, Physics.md "Caustic atlas")
// the caustic light of the texels that the host chose to show fine, reconstructed the same way at
// subdivision n c (fine first texel REFRACTA_CAUSTIC_OFFSET + c^2 first; the host took that
// light out of the atlas). The corners hold 9 floats per triangle and side, the front's first.
inline float3 refracta_view_surface_irradiance(__global const int* triInfo,
  __global const float* irradiance, __global const float* corners, int tri, int side, float u,
  float v)
{
  const int first = triInfo[REFRACTA_TRIANGLE_INFO_INTS * tri + REFRACTA_TRIANGLE_INFO_TEXEL];
  const int n = triInfo[REFRACTA_TRIANGLE_INFO_INTS * tri + REFRACTA_TRIANGLE_INFO_SUBDIVISION];
  __global const float* sided = irradiance + 3 * side;
  const float3 e = refracta_view_atlas_irradiance(
    sided, corners + 9 * refracta_sided_texel(tri, side), first, n, u, v);
#if defined(REFRACTA_CAUSTIC_SUBDIVISION) && REFRACTA_CAUSTIC_SUBDIVISION > 1
  // The fine texels' caustic light stays within its triangle (0: no shared corners).
  const int c = REFRACTA_CAUSTIC_SUBDIVISION;
  return e +
    refracta_view_atlas_irradiance(
      sided + 3 * refracta_sided_texel(REFRACTA_CAUSTIC_OFFSET, 0), 0, c * c * first, c * n, u, v);
#else
  return e;
#endif
}

// Outgoing radiance E rho / pi of the surface hit (triangle tri, barycentrics u, v) towards a
// view ray that met it along grid-local direction d; `normal`, the triangle's winding normal in
// the same frame, tells the side it sees.
inline float3 refracta_view_surface_radiance(__global const int* triInfo,
  __global const float* albedo, __global const float* irradiance, __global const float* corners,
  int tri, float u, float v, float3 d, float3 normal)
{
  const int first = triInfo[REFRACTA_TRIANGLE_INFO_INTS * tri + REFRACTA_TRIANGLE_INFO_TEXEL];
  const int n = triInfo[REFRACTA_TRIANGLE_INFO_INTS * tri + REFRACTA_TRIANGLE_INFO_SUBDIVISION];
  const float3 rho = vload3(first + refracta_texel_index(u, v, n), albedo);
  const int side = dot(d, normal) > 0.0f ? 1 : 0;
  const float3 e = refracta_view_surface_irradiance(triInfo, irradiance, corners, tri, side, u, v);
  return fmax(e, (float3)(0.0f)) * rho * (1.0f / REFRACTA_PI);
}

// Grid-local point -> surface frame.
inline float3 refracta_view_to_surface(float3 x, float4 m0, float4 m1, float4 m2)
{
  return (float3)(dot(m0.xyz, x) + m0.w, dot(m1.xyz, x) + m1.w, dot(m2.xyz, x) + m2.w);
}

// Closest surface hit on the grid-local ray x + t d, t in (0, tMax) (t in units of |d|; d need
// not be unit: a segment is d = end - x with tMax = 1). Returns the triangle (BVH order) or -1,
// and *t, *u, *v.
inline int refracta_view_surface_hit(__global const float4* nodes, int nodeCount,
  __global const float4* triangles, float4 m0, float4 m1, float4 m2, float3 x, float3 d,
  float tMax, float* t, float* u, float* v)
{
  if (nodeCount <= 0 || !(tMax > 0.0f))
  {
    return -1;
  }
  const float3 o = refracta_view_to_surface(x, m0, m1, m2);
  const float3 e = (float3)(dot(m0.xyz, d), dot(m1.xyz, d), dot(m2.xyz, d));
  const refracta_hit hit = refracta_bvh_closest(nodes, nodeCount, triangles, o, e, 0.0f, tMax);
  *t = hit.t;
  *u = hit.u;
  *v = hit.v;
  return hit.triangle;
}

#endif // REFRACTA_HAS_SURFACES
