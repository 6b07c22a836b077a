#include "vtkRefractaViewPassSurfaces.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaSurfaceSet.h"

#include <cmath>
#include <sstream>

namespace vtkRefractaViewPassDetail
{
namespace
{
// vtkErrorWithObjectMacro needs the object's class; the owner is always a vtkObject here.
void ReportError(vtkObject* owner, const std::string& message)
{
  vtkErrorWithObjectMacro(owner, << message);
}
}

//------------------------------------------------------------------------------
bool SurfaceBuffers::Update(vtkRefractaSurfaceSet* set, vtkOpenCLContext* context, vtkObject* owner)
{
  if (set != this->Set)
  {
    this->Set = set;
    this->UploadedBuild = -1;
  }
  if (!set)
  {
    this->NodeCount = 0;
    this->Texels = 0;
    this->Nodes.Reset();
    this->Triangles.Reset();
    this->TriangleInfo.Reset();
    this->Albedo.Reset();
    this->Irradiance.Reset();
    this->Normals.Reset();
    this->Interfaces.Reset();
    this->Dielectric = false;
    return true;
  }
  if (!set->Build())
  {
    ReportError(owner, "The surface set could not be built (see the error above).");
    return false;
  }
  if (set->GetNumberOfBuilds() == this->UploadedBuild)
  {
    return true;
  }
  vtkRefractaBVH* bvh = set->GetBVH();
  const vtkIdType nodes = bvh ? bvh->GetNumberOfNodes() : 0;
  this->NodeCount = static_cast<int>(nodes);
  this->Texels = set->GetNumberOfTexels();
  this->IrradianceDirty = true;
  this->UploadedBuild = set->GetNumberOfBuilds();
  if (nodes == 0)
  {
    // Nothing to hit (no surface, or every triangle dropped): the kernel is built without them.
    return true;
  }
  for (int a = 0; a < 3; ++a)
  {
    this->FrameOrigin[a] = bvh->GetFrameOrigin()[a];
  }
  const std::vector<float>& nodeData = bvh->GetNodes();
  const std::vector<float>& triangles = bvh->GetFloatTriangles();
  const std::vector<int>& info = set->GetTriangleInfo();
  const std::vector<float>& albedo = set->GetTexelAlbedo();
  const cl_mem_flags flags = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  this->Nodes = context->CreateBuffer(
    flags, nodeData.size() * sizeof(float), nodeData.data(), "surface BVH nodes", owner);
  this->Triangles = context->CreateBuffer(
    flags, triangles.size() * sizeof(float), triangles.data(), "surface triangles", owner);
  this->TriangleInfo = context->CreateBuffer(
    flags, info.size() * sizeof(int), info.data(), "surface triangle texels", owner);
  this->Albedo = context->CreateBuffer(
    flags, albedo.size() * sizeof(float), albedo.data(), "surface albedo", owner);
  // Glass: the corner normals and the index pairs, only where there are dielectric triangles.
  this->Dielectric = set->GetNumberOfDielectricTriangles() > 0;
  this->Normals.Reset();
  this->Interfaces.Reset();
  if (this->Dielectric)
  {
    const std::vector<float>& normals = set->GetTriangleNormals();
    const std::vector<float>& interfaces = set->GetSurfaceInterfaces();
    this->Normals = context->CreateBuffer(
      flags, normals.size() * sizeof(float), normals.data(), "surface corner normals", owner);
    this->Interfaces = context->CreateBuffer(flags, interfaces.size() * sizeof(float),
      interfaces.data(), "surface interface indices", owner);
  }
  if (!this->Nodes || !this->Triangles || !this->TriangleInfo || !this->Albedo ||
    (this->Dielectric && (!this->Normals || !this->Interfaces)))
  {
    this->NodeCount = 0;
    this->UploadedBuild = -1;
    return false;
  }
  ++this->NumberOfUploads;
  return true;
}

//------------------------------------------------------------------------------
bool SurfaceBuffers::SetLighting(vtkImageData* lighting, vtkObject* owner)
{
  vtkDataArray* array = lighting
    ? lighting->GetFieldData()->GetArray(vtkRefractaLightingVolume::SurfaceIrradianceName())
    : nullptr;
  if (array == this->IrradianceArray && (!array || array->GetMTime() == this->IrradianceTime))
  {
    return true;
  }
  this->IrradianceDirty = true;
  this->IrradianceArray = nullptr;
  if (!array)
  {
    return true;
  }
  const char* name = vtkRefractaLightingVolume::SurfaceIrradianceName();
  if (array->GetNumberOfComponents() != 3)
  {
    std::ostringstream msg;
    msg << "The lighting volume's field array '" << name << "' has "
        << array->GetNumberOfComponents()
        << " components; it needs 3 (RGB irradiance, one tuple per surface texel).";
    ReportError(owner, msg.str());
    return false;
  }
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double v = array->GetComponent(i, c);
      if (!std::isfinite(v) || v < 0)
      {
        std::ostringstream msg;
        msg << "The lighting volume's field array '" << name << "' has the invalid value " << v
            << " at tuple " << i << " component " << c << "; values must be finite and >= 0.";
        ReportError(owner, msg.str());
        return false;
      }
    }
  }
  this->IrradianceArray = array;
  this->IrradianceTime = array->GetMTime();
  return true;
}

//------------------------------------------------------------------------------
bool SurfaceBuffers::PrepareIrradiance(vtkOpenCLContext* context, vtkObject* owner)
{
  if (!this->IrradianceDirty && this->Irradiance)
  {
    return true;
  }
  std::vector<float> values(static_cast<size_t>(this->Texels) * 3, 0.0f);
  if (vtkDataArray* array = this->IrradianceArray)
  {
    if (array->GetNumberOfTuples() != this->Texels)
    {
      std::ostringstream msg;
      msg << "The lighting volume's field array '"
          << vtkRefractaLightingVolume::SurfaceIrradianceName() << "' has "
          << array->GetNumberOfTuples() << " tuples but the surface set has " << this->Texels
          << " texels; compute the lighting with the same surface set (the photon pass's "
             "SetSurfaces) after its last change.";
      ReportError(owner, msg.str());
      return false;
    }
    for (vtkIdType i = 0; i < this->Texels; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        values[3 * i + c] = static_cast<float>(array->GetComponent(i, c));
      }
    }
  }
  this->Irradiance = context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    values.size() * sizeof(float), values.data(), "surface irradiance", owner);
  if (!this->Irradiance)
  {
    return false;
  }
  this->IrradianceDirty = false;
  return true;
}

//------------------------------------------------------------------------------
void SurfaceBuffers::ComputeLocalToSurface(const double worldToLocal[4][4], cl_float4 rows[3]) const
{
  vtkNew<vtkMatrix4x4> toLocal, toWorld;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      toLocal->SetElement(r, c, worldToLocal[r][c]);
    }
  }
  vtkMatrix4x4::Invert(toLocal, toWorld);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      rows[r].s[c] = static_cast<float>(toWorld->GetElement(r, c));
    }
    rows[r].s[3] = static_cast<float>(toWorld->GetElement(r, 3) - this->FrameOrigin[r]);
  }
}
}
