// Private to vtkRefractaViewPass (not installed): the host side of opaque surfaces in the view
// pass. It keeps the surface set's BVH, triangles and atlas (triangle info, baked albedo) on the
// device, uploaded once per Build() of the set (a camera move uploads nothing), and the surface
// irradiance of the lighting volume (its field array vtkRefractaLightingVolume::
// SurfaceIrradianceName()), uploaded when the lighting volume or the set changes. The kernel side
// is Kernels/view_surfaces.cl.
#ifndef vtkRefractaViewPassSurfaces_h
#define vtkRefractaViewPassSurfaces_h

#include "vtkOpenCLContext.h" // for vtkOpenCLBuffer, cl_float4
#include "vtkSmartPointer.h"  // for members
#include "vtkType.h"          // for vtkMTimeType, vtkIdType

#include <string> // for messages
#include <vector> // for the irradiance copy

class vtkDataArray;
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
  // array: none, surfaces are then unlit). Checks it (3 components, finite, >= 0); false after an
  // error naming the problem. The upload happens in PrepareIrradiance().
  bool SetLighting(vtkImageData* lighting, vtkObject* owner);

  // Uploads the irradiance for the current build (zeros when the lighting has none). False, with
  // an error, when its tuples do not match the set's texels.
  bool PrepareIrradiance(vtkOpenCLContext* context, vtkObject* owner);

  // Whether there is anything to hit.
  bool Active() const { return this->NodeCount > 0; }

  // Rows of the affine map grid-local -> surface frame (world minus the BVH's frame origin), from
  // the view's world -> grid-local map, in double then rounded.
  void ComputeLocalToSurface(const double worldToLocal[4][4], cl_float4 rows[3]) const;

  int GetNodeCount() const { return this->NodeCount; }
  // Whether the set has dielectric (glass) triangles: the kernel then splits paths at them.
  bool HasDielectric() const { return this->NodeCount > 0 && this->Dielectric; }
  int GetNumberOfUploads() const { return this->NumberOfUploads; }

  vtkOpenCLBuffer Nodes, Triangles, TriangleInfo, Albedo, Irradiance;
  // Corner normals (float4 per corner) and (IndexInside, IndexOutside) per surface.
  vtkOpenCLBuffer Normals, Interfaces;

private:
  vtkSmartPointer<vtkRefractaSurfaceSet> Set;
  int UploadedBuild = -1; // the set's GetNumberOfBuilds() at the last upload
  int NodeCount = 0;
  bool Dielectric = false;
  vtkIdType Texels = 0;
  double FrameOrigin[3] = { 0, 0, 0 };
  int NumberOfUploads = 0;

  vtkSmartPointer<vtkDataArray> IrradianceArray; // from the lighting volume, or nullptr
  vtkMTimeType IrradianceTime = 0;
  bool IrradianceDirty = true;
};
}

#endif
