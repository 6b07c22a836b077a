/**
 * @class   vtkRefractaSurfaceSet
 * @brief   The opaque triangle surfaces of a Refracta scene, flattened for the light and view
 *          passes: world triangles in a BVH, and an irradiance atlas with baked albedo.
 *
 * A surface is a vtkPolyData (its polygons and triangle strips; vertices and lines are ignored),
 * a vtkRefractaSurfaceMaterial (nullptr: a new default one of its own, albedo 0.8) and an optional
 * matrix (model to world, as vtkProp3D::GetMatrix(); nullptr: identity). Open meshes are fine (a
 * plane is open); triangles are two-sided Lambertian reflectors.
 *
 * Build() (cached: it does nothing while GetMTime(), which includes the meshes, materials and
 * matrices, is not newer than the last build) does, in order:
 * 1. transforms every surface's points to world coordinates; a surface with a non-finite point
 *    (NaN or Inf, in the mesh or produced by its matrix) is reported with vtkErrorMacro naming it
 *    and skipped (GetNumberOfRejectedSurfaces());
 * 2. triangulates polygons (ear cutting by vtkPolygon for more than four points, a fan for
 *    quads) and strips; drops degenerate triangles, those whose doubled area |e1 x e2| is at most
 *    1e-12 times the square of their longest edge (zero area, collinear or repeated points),
 *    counting them (GetNumberOfDroppedTriangles());
 * 3. builds the BVH (vtkRefractaBVH; the triangles are then numbered in BVH order);
 * 4. lays out the irradiance atlas: triangle t is cut into n_t x n_t equal-area sub-triangles
 *    ("texels", see TexelIndex) with n_t = clamp(ceil(longest edge / texel size), 1,
 *    MaximumTexelSubdivision); the texel size is TexelSize, or when that is 0 (default) the
 *    diagonal of the world bounds of the non-dielectric surfaces / 128; when the texels would
 * exceed MaximumNumberOfTexels the size grows until they fit (never below one texel per triangle);
 * 5. bakes one albedo per texel from the material (see vtkRefractaSurfaceMaterial), the mean of
 *    the colour at four points of the texel (its centroid and the centroids of its three corner
 *    sub-triangles), so a checker edge that cuts a texel gives the area-weighted blend.
 *
 * 6. for dielectric surfaces (vtkRefractaSurfaceMaterial::DIELECTRIC, transparent interfaces
 *    between two indices, see Documentation/Physics.md "Dielectric interfaces"): one texel per
 *    triangle (they receive no deposits, so they take nothing from the texel budget), the kind in
 *    the triangle info, the corner normals (GetTriangleNormals(): with SmoothNormals the
 *    area-weighted mean of the world normals of the surface's faces sharing the mesh point, kept
 *    where within 30 degrees of the face normal, else the face normal) and the surface's
 *    (IndexInside, IndexOutside) (GetSurfaceInterfaces()), and its inside medium when it has one
 *    (GetSurfaceBodies(); Documentation/Physics.md "Glass bodies");
 * 7. links the corners of the Lambertian triangles that share a mesh point (GetCornerTexels()):
 *    the view pass reconstructs the irradiance at a triangle's corner from the corner texels of
 *    every triangle of the same surface at that point whose face is within 30 degrees of its own
 *    (ComputeCornerIrradiance()), so a mesh finer than its texels is shaded continuously across
 *    its triangles, as VTK's Gouraud shading would, while a cube's edges stay sharp. Meshes
 *    whose triangles do not share point ids (unmerged points) keep each corner to its own texel.
 *
 * A pass deposits photon flux per texel; irradiance (W / m^2, per RGB channel) = flux / texel
 * area (GetTexelAreas()). The flattened arrays follow Kernels/refracta_surfaces.cl.
 */
#ifndef vtkRefractaSurfaceSet_h
#define vtkRefractaSurfaceSet_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for members

#include <vector> // for the flattened arrays

class vtkDataArray;
class vtkDataObject;
class vtkMatrix4x4;
class vtkPolyData;
class vtkRefractaBVH;
class vtkRefractaSurfaceMaterial;

class REFRACTACORE_EXPORT vtkRefractaSurfaceSet : public vtkObject
{
public:
  static vtkRefractaSurfaceSet* New();
  vtkTypeMacro(vtkRefractaSurfaceSet, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Adds a surface (kept by reference: changing the mesh, material or matrix later is seen by
   * the next Build()). Returns its index, or -1 (with an error) for a null mesh.
   */
  int AddSurface(vtkPolyData* mesh, vtkRefractaSurfaceMaterial* material = nullptr,
    vtkMatrix4x4* matrix = nullptr);

  /**
   * Adds the exact dielectric interfaces a medium carries in its field data
   * (vtkMeshVoxelizer::EXACT_INTERFACES, the arrays named by vtkRefractaMedium): one DIELECTRIC
   * surface (smooth normals) per distinct (index inside, index outside) pair, placed by `matrix`
   * (the medium's data coordinates to world; nullptr: identity). With the optional
   * InterfaceMaterials array the surfaces are also split by it and carry the medium inside
   * (vtkRefractaSurfaceMaterial::UseInsideMedium). Returns the number of surfaces
   * added: 0 for a medium without interface arrays (volumetric data, SMOOTHED_INDEX) or a null
   * one; -1 with an error when the arrays are inconsistent (wrong components, ids out of range,
   * InterfaceMaterials with the wrong tuple count or components, non-finite or out-of-range
   * values).
   */
  int AddMediumInterfaces(vtkDataObject* medium, vtkMatrix4x4* matrix = nullptr);

  /**
   * Removes every surface.
   */
  void RemoveAllSurfaces();

  /**
   * Number of surfaces added.
   */
  int GetNumberOfSurfaces() const;

  /**
   * Number of surfaces with at least one polygon or triangle strip (without building).
   */
  int GetNumberOfNonEmptySurfaces() const;

  /**
   * Number of those non-empty surfaces whose material is DIELECTRIC (exact interfaces between
   * two refractive indices; without building).
   */
  int GetNumberOfNonEmptyDielectricSurfaces() const;

  /**
   * Replaces this set's surfaces by those of `source` (meshes, materials and matrices by
   * reference, as AddSurface keeps them) and copies its atlas settings (TexelSize,
   * MaximumTexelSubdivision, MaximumNumberOfTexels). nullptr: no surfaces, default settings.
   */
  void CopySurfaces(vtkRefractaSurfaceSet* source);

  ///@{
  /**
   * The surfaces as added (nullptr for an index out of range).
   */
  vtkPolyData* GetSurface(int index) const;
  vtkRefractaSurfaceMaterial* GetMaterial(int index) const;
  vtkMatrix4x4* GetMatrix(int index) const;
  ///@}

  ///@{
  /**
   * Edge length of a texel of the irradiance atlas (world units); 0 (default): automatic, the
   * diagonal of the world bounds of the non-dielectric surfaces (those that receive deposits) /
   * 128.
   */
  void SetTexelSize(double value);
  vtkGetMacro(TexelSize, double);
  ///@}

  ///@{
  /**
   * Largest subdivision n of one triangle (n^2 texels), clamped to [1, 1024]. Default 256.
   */
  vtkSetClampMacro(MaximumTexelSubdivision, int, 1, 1024);
  vtkGetMacro(MaximumTexelSubdivision, int);
  ///@}

  ///@{
  /**
   * Budget of texels over all triangles (default 2^20; one texel per triangle is always kept,
   * so a mesh with more triangles than this gets exactly one texel each).
   */
  vtkSetClampMacro(MaximumNumberOfTexels, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfTexels, vtkIdType);
  ///@}

  /**
   * Builds (or keeps) the flattened arrays, see the class description. Returns false only when
   * nothing could be built because of an internal limit (more than 2^31 - 1 triangles or texels).
   */
  bool Build();

  /**
   * Modification time including every mesh, material and matrix.
   */
  vtkMTimeType GetMTime() override;

  ///@{
  /**
   * Results of the last Build().
   */
  vtkIdType GetNumberOfTriangles() const;
  vtkIdType GetNumberOfTexels() const { return static_cast<vtkIdType>(this->TexelAreas.size()); }
  vtkIdType GetNumberOfDroppedTriangles() const { return this->DroppedTriangles; }
  vtkIdType GetNumberOfDielectricTriangles() const { return this->DielectricTriangles; }
  int GetNumberOfRejectedSurfaces() const { return this->RejectedSurfaces; }
  double GetEffectiveTexelSize() const { return this->EffectiveTexelSize; }
  int GetNumberOfBuilds() const { return this->NumberOfBuilds; }
  double GetBuildSeconds() const { return this->BuildSeconds; }
  void GetBounds(double bounds[6]) const;
  vtkRefractaBVH* GetBVH() const;
  ///@}

#ifndef __VTK_WRAP__
  /**
   * Per triangle (BVH order): REFRACTA_TRIANGLE_INFO_INTS ints, (first texel, subdivision n,
   * surface index, kind: REFRACTA_SURFACE_LAMBERTIAN or REFRACTA_SURFACE_DIELECTRIC).
   */
  const std::vector<int>& GetTriangleInfo() const
  {
    return this->TriangleInfo;
  }

  /**
   * Per texel: baked albedo RGB in [0, 1] (3 floats).
   */
  const std::vector<float>& GetTexelAlbedo() const
  {
    return this->TexelAlbedo;
  }

  /**
   * Per triangle (BVH order): its three corner unit normals, REFRACTA_TRIANGLE_NORMAL_FLOATS
   * floats (x, y, z, 0 per corner). The flat winding normal for Lambertian triangles and for
   * dielectric surfaces without SmoothNormals.
   */
  const std::vector<float>& GetTriangleNormals() const
  {
    return this->TriangleNormals;
  }

  /**
   * Per surface: REFRACTA_SURFACE_INTERFACE_FLOATS floats, (IndexInside, IndexOutside) of a
   * dielectric surface, (1, 1) for a Lambertian one.
   */
  const std::vector<float>& GetSurfaceInterfaces() const
  {
    return this->SurfaceInterfaces;
  }

  /**
   * Per surface: REFRACTA_SURFACE_BODY_FLOATS floats, the homogeneous medium inside a dielectric
   * surface with UseInsideMedium (vtkRefractaSurfaceMaterial): extinction RGB, 1, albedo RGB,
   * anisotropy, emission RGB, 0; all 0 for any other surface (the passes use the grid there).
   */
  const std::vector<float>& GetSurfaceBodies() const
  {
    return this->SurfaceBodies;
  }

  /**
   * Per texel: area in world units^2 (triangle area / n^2).
   */
  const std::vector<double>& GetTexelAreas() const
  {
    return this->TexelAreas;
  }

  /**
   * Per triangle corner (BVH order, three per triangle; build step 7): the atlas texels whose
   * irradiance the view pass averages at that corner are GetCornerTexels()[i] for i from
   * GetCornerOffsets()[3 t + c] to GetCornerOffsets()[3 t + c + 1] (none for a dielectric
   * triangle). GetCornerOffsets() has 3 triangles + 1 entries.
   */
  const std::vector<vtkIdType>& GetCornerOffsets() const
  {
    return this->CornerOffsets;
  }
  const std::vector<int>& GetCornerTexels() const
  {
    return this->CornerTexels;
  }

  /**
   * The irradiance at every triangle corner (3 RGB floats per triangle, BVH order) from the
   * atlas's per-texel irradiance (3 floats per texel, GetNumberOfTexels() texels): the mean over
   * the corner's linked texels weighted by their areas (total flux over total area), 0 for
   * dielectric triangles.
   */
  void ComputeCornerIrradiance(const float* irradiance, std::vector<float>& corners) const;
#endif

  /**
   * Texel of the point with barycentric weights (u, v) of the second and third vertex in a
   * triangle of subdivision n: in [0, n^2), the same float arithmetic as refracta_texel_index in
   * Kernels/refracta_surfaces.cl. Points outside the triangle (rounding) are clamped into it.
   */
  static int TexelIndex(float u, float v, int n);

  /**
   * Barycentric (u, v) of the three corners of a texel (u0 v0 u1 v1 u2 v2); false for a texel
   * out of range.
   */
  static bool GetTexelCorners(int texel, int n, double corners[6]);

  /**
   * Barycentric (u, v) of the four equally weighted points that stand for a texel's area (its
   * centroid and the centroids of its three corner sub-triangles; u0 v0 ... u3 v3): the albedo
   * bake's points, and vtkLightRaySingleScattering's for the direct irradiance. False for a
   * texel out of range.
   */
  static bool GetTexelSamplePoints(int texel, int n, double points[8]);

protected:
  vtkRefractaSurfaceSet();
  ~vtkRefractaSurfaceSet() override;

  double TexelSize = 0.0;
  int MaximumTexelSubdivision = 256;
  vtkIdType MaximumNumberOfTexels = 1 << 20;

  vtkIdType DroppedTriangles = 0;
  vtkIdType DielectricTriangles = 0;
  int RejectedSurfaces = 0;
  double EffectiveTexelSize = 0.0;
  int NumberOfBuilds = 0;
  double BuildSeconds = 0.0;
  vtkMTimeType BuiltMTime = 0;
  bool Built = false;
  std::vector<int> TriangleInfo;
  std::vector<float> TexelAlbedo;
  std::vector<double> TexelAreas;
  std::vector<float> TriangleNormals;
  std::vector<float> SurfaceInterfaces;
  std::vector<float> SurfaceBodies;
  std::vector<vtkIdType> CornerOffsets;
  std::vector<int> CornerTexels;

private:
  vtkRefractaSurfaceSet(const vtkRefractaSurfaceSet&) = delete;
  void operator=(const vtkRefractaSurfaceSet&) = delete;
  struct Internals;
  Internals* Impl;
  // Build() steps 4 and 5 (see the class description), on the triangles in BVH order.
  void LayOutAtlas();
  void BakeAlbedo();
  // Build() step 6: kinds, corner normals and the interface table.
  void DescribeInterfaces();
  bool IsDielectric(int surface) const;
  // Build() step 7: the Lambertian corners' linked texels.
  void LinkCorners();
  // AddMediumInterfaces's checks of the optional InterfaceMaterials array (errors name it).
  bool CheckInterfaceMaterials(vtkDataArray* bodies, vtkIdType triangles);
};

#endif
