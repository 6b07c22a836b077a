// Private to vtkRefractaViewPass (not installed): the host side of opaque surfaces in the view
// pass. It keeps the surface set's BVH, triangles and atlas (triangle info, baked albedo) on the
// device, uploaded once per Build() of the set (a camera move uploads nothing), and the surface
// irradiance of the lighting volume (its field array vtkRefractaLightingVolume::
// SurfaceIrradianceName()), uploaded when the lighting volume or the set changes. The kernel side
// is Kernels/view_surfaces.cl.
#ifndef vtkRefractaViewPassSurfaces_h
#define vtkRefractaViewPassSurfaces_h

#include "vtkDataArray.h"     // for LightingArrays
#include "vtkNew.h"           // for the grid cuts
#include "vtkOpenCLContext.h" // for vtkOpenCLBuffer, cl_float4
#include "vtkRefractaGridCuts.h" // for the grid cuts
#include "vtkSmartPointer.h"  // for members
#include "vtkType.h"          // for vtkMTimeType, vtkIdType

#include <algorithm> // for std::equal
#include <string>    // for messages
#include <vector>    // for the irradiance copy

class vtkImageData;
class vtkObject;
class vtkRefractaSurfaceSet;

namespace vtkRefractaViewPassDetail
{
class SurfaceBuffers
{
public:
  // Builds the set (vtkRefractaSurfaceSet::Build() is cached) and uploads its arrays when the
  // build is new. nullptr or an empty set leaves no surfaces. False after an error on `owner`.
  bool Update(vtkRefractaSurfaceSet* set, vtkOpenCLContext* context, vtkObject* owner);

  // Takes the lighting volume's surface irradiance (nullptr, or a lighting volume without the
  // array: none, surfaces are then unlit). Checks it (6 components, front and back RGB, or 3 for
  // both sides; finite, >= 0); false after an error naming the problem. The upload happens in
  // PrepareIrradiance().
  bool SetLighting(vtkImageData* lighting, vtkObject* owner);

  // Uploads the irradiance for the current build (zeros when the lighting has none), both sides
  // of each texel side by side (front RGB, back RGB). With the caustic atlas, the buffer holds
  // the atlas less the caustic light shown by the fine texels, then the fine texels of the atlas
  // texel sides where at least photonsPerFineTexel c^2 caustic photons landed (zeros elsewhere).
  // False, with an error, when the tuples do not match the set's texels.
  bool PrepareIrradiance(vtkOpenCLContext* context, double photonsPerFineTexel, vtkObject* owner);

  // Where the set's opaque triangles cut the medium's grid (vtkRefractaGridCuts, found again only
  // when the build, the grid or the placement changed): uploads which voxels are near an opaque
  // triangle (CutLinks, bit REFRACTA_CUT_NEAR), where the sided lookups of light ask the BVH
  // whether one separates a sample from a voxel; none without surfaces or cuts. `worldToLocal` maps
  // the set's world to the grid-local frame. False after an error.
  bool UpdateCuts(const int dims[3], const double spacing[3], const double worldToLocal[4][4],
    vtkOpenCLContext* context, vtkObject* owner);
  // Whether the last UpdateCuts() found cuts (the kernel then reads light sided).
  bool HasCuts() const { return static_cast<bool>(this->CutLinks); }
  // Whether there is anything to hit.
  bool Active() const { return this->NodeCount > 0; }

  // Rows of the affine map grid-local -> surface frame (world minus the BVH's frame origin), from
  // the view's world -> grid-local map, in double then rounded.
  void ComputeLocalToSurface(const double worldToLocal[4][4], cl_float4 rows[3]) const;

  int GetNodeCount() const { return this->NodeCount; }
  // Whether the set has dielectric (glass) triangles: the kernel then splits paths at them.
  bool HasDielectric() const { return this->NodeCount > 0 && this->Dielectric; }
  int GetNumberOfUploads() const { return this->NumberOfUploads; }
  // The caustic atlas's subdivision c in the uploaded irradiance (1: none), and the number of
  // atlas texels before its fine texels in that buffer.
  int GetCausticSubdivision() const { return this->Caustic; }
  // How many atlas texel sides show their caustic light from their fine texels.
  vtkIdType GetNumberOfFineCausticTexels() const { return this->FineCausticTexels; }
  vtkIdType GetNumberOfTexels() const { return this->Texels; }

  vtkOpenCLBuffer Nodes, Triangles, TriangleInfo, Albedo, Irradiance;
  // The irradiance at each triangle's three corners, averaged over the triangles sharing the mesh
  // point (vtkRefractaSurfaceSet::ComputeCornerIrradiance; 9 floats per triangle and side, the
  // front's first).
  vtkOpenCLBuffer Corners;
  // Corner normals (float4 per corner), (IndexInside, IndexOutside) per surface and the glass
  // bodies' inside media (vtkRefractaSurfaceSet::GetSurfaceBodies()).
  vtkOpenCLBuffer Normals, Interfaces, Bodies;
  vtkOpenCLBuffer CutLinks; // UpdateCuts()

private:
  vtkSmartPointer<vtkRefractaSurfaceSet> Set;
  vtkNew<vtkRefractaGridCuts> Cuts;
  int UploadedBuild = -1; // the set's GetNumberOfBuilds() at the last upload
  int NodeCount = 0;
  bool Dielectric = false;
  vtkIdType Texels = 0;
  double FrameOrigin[3] = { 0, 0, 0 };
  int NumberOfUploads = 0;

  // The lighting volume's surface arrays (each may be nullptr) and their MTimes at SetLighting.
  struct LightingArrays
  {
    vtkSmartPointer<vtkDataArray> Irradiance, Caustic, CausticPhotons;
    vtkMTimeType Times[3] = { 0, 0, 0 };
    void Stamp()
    {
      vtkDataArray* arrays[3] = { this->Irradiance, this->Caustic, this->CausticPhotons };
      for (int i = 0; i < 3; ++i)
      {
        this->Times[i] = arrays[i] ? arrays[i]->GetMTime() : 0;
      }
    }
    bool SameAs(const LightingArrays& o) const
    {
      LightingArrays now = *this;
      now.Stamp();
      return now.Irradiance == o.Irradiance && now.Caustic == o.Caustic &&
        now.CausticPhotons == o.CausticPhotons && std::equal(now.Times, now.Times + 3, o.Times);
    }
  };
  // Moves the caustic light of the texels read fine from `values` (one side of the atlas, 3 per
  // texel) into the fine texels of that side appended to it; sets Caustic.
  bool SplitCaustic(
    std::vector<float>& values, int side, double photonsPerFineTexel, vtkObject* owner);
  // For subdivision n and caustic subdivision c: the atlas texel of each fine texel.
  static void FineToCoarseTexels(int n, int c, std::vector<int>& coarseOf);
  bool CheckTuples(
    vtkDataArray* array, vtkIdType expected, const char* name, vtkObject* owner) const;

  LightingArrays Lighting;
  bool IrradianceDirty = true;
  double PhotonsPerFineTexel = -1;
  int Caustic = 1;
  vtkIdType FineCausticTexels = 0;
};
}

#endif
