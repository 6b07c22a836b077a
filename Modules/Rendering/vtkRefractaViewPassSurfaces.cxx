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

#include "refracta_surfaces.cl" // REFRACTA_TRIANGLE_INFO_*

#include <algorithm>
#include <cmath>
#include <map>
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

constexpr int Sides = vtkRefractaLightingVolume::NUMBER_OF_SURFACE_SIDES;
static_assert(Sides == REFRACTA_SURFACE_SIDES, "the kernels' texel sides are the arrays' sides");

// The sides' values one after the other per item (`width` floats per item and side).
std::vector<float> Interleave(const std::vector<float> planes[Sides], size_t width)
{
  std::vector<float> out(Sides * planes[0].size());
  for (size_t i = 0; i < planes[0].size() / width; ++i)
  {
    for (int side = 0; side < Sides; ++side)
    {
      std::copy_n(&planes[side][width * i], width, &out[width * (Sides * i + side)]);
    }
  }
  return out;
}

// Checks a per-side lighting field array: perSide components for each side (front first) or
// perSide for both (vtkRefractaLightingVolume::GetSurfaceSideValue), every value finite and >= 0.
bool CheckArray(
  vtkDataArray* array, int perSide, const char* name, const char* meaning, vtkObject* owner)
{
  const int components = array->GetNumberOfComponents();
  if (components != Sides * perSide && components != perSide)
  {
    std::ostringstream msg;
    msg << "The lighting volume's field array '" << name << "' has " << components
        << " components; it needs " << Sides * perSide << " (" << meaning
        << ", on the front side then the back side) or " << perSide << " (one for both sides).";
    ReportError(owner, msg.str());
    return false;
  }
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < components; ++c)
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
  return true;
}
}

//------------------------------------------------------------------------------
bool SurfaceBuffers::UpdateCuts(const int dims[3], const double spacing[3],
  const double worldToLocal[4][4], vtkOpenCLContext* context, vtkObject* owner)
{
  if (!this->Active())
  {
    this->CutLinks.Reset();
    return true;
  }
  vtkNew<vtkMatrix4x4> localToWorld;
  localToWorld->DeepCopy(&worldToLocal[0][0]);
  localToWorld->Invert();
  const bool searched = this->Cuts->Update(this->Set, dims, spacing, localToWorld);
  if (!this->Cuts->HasCuts())
  {
    this->CutLinks.Reset();
    return true;
  }
  if (searched || !this->CutLinks)
  {
    const std::vector<unsigned char>& links = this->Cuts->GetLinks();
    this->CutLinks = context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, links.size(),
      links.data(), "voxels near opaque surfaces", owner);
    if (!this->CutLinks)
    {
      return false;
    }
  }
  return true;
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
    this->Corners.Reset();
    this->Normals.Reset();
    this->Interfaces.Reset();
    this->Bodies.Reset();
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
  this->Bodies.Reset();
  if (this->Dielectric)
  {
    const std::vector<float>& normals = set->GetTriangleNormals();
    const std::vector<float>& interfaces = set->GetSurfaceInterfaces();
    const std::vector<float>& bodies = set->GetSurfaceBodies();
    this->Normals = context->CreateBuffer(
      flags, normals.size() * sizeof(float), normals.data(), "surface corner normals", owner);
    this->Interfaces = context->CreateBuffer(flags, interfaces.size() * sizeof(float),
      interfaces.data(), "surface interface indices", owner);
    this->Bodies = context->CreateBuffer(
      flags, bodies.size() * sizeof(float), bodies.data(), "glass body media", owner);
  }
  if (!this->Nodes || !this->Triangles || !this->TriangleInfo || !this->Albedo ||
    (this->Dielectric && (!this->Normals || !this->Interfaces || !this->Bodies)))
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
  vtkFieldData* fd = lighting ? lighting->GetFieldData() : nullptr;
  auto get = [fd](const char* name) { return fd ? fd->GetArray(name) : nullptr; };
  LightingArrays arrays;
  arrays.Irradiance = get(vtkRefractaLightingVolume::SurfaceIrradianceName());
  arrays.Caustic = get(vtkRefractaLightingVolume::SurfaceCausticIrradianceName());
  arrays.CausticPhotons = get(vtkRefractaLightingVolume::SurfaceCausticPhotonsName());
  if (arrays.SameAs(this->Lighting))
  {
    return true;
  }
  this->IrradianceDirty = true;
  this->Lighting = LightingArrays();
  if (!arrays.Irradiance)
  {
    return true; // unlit surfaces (the caustic arrays mean nothing without the atlas)
  }
  if (arrays.Caustic && !arrays.CausticPhotons)
  {
    ReportError(owner,
      std::string("The lighting volume has the field array '") +
        vtkRefractaLightingVolume::SurfaceCausticIrradianceName() + "' but not '" +
        vtkRefractaLightingVolume::SurfaceCausticPhotonsName() +
        "', the caustic photons per atlas texel that say where it may be read.");
    return false;
  }
  if (!CheckArray(arrays.Irradiance, 3, vtkRefractaLightingVolume::SurfaceIrradianceName(),
        "RGB irradiance, one tuple per surface texel", owner) ||
    (arrays.Caustic &&
      (!CheckArray(arrays.Caustic, 3, vtkRefractaLightingVolume::SurfaceCausticIrradianceName(),
         "RGB irradiance, c^2 tuples per surface texel", owner) ||
        !CheckArray(arrays.CausticPhotons, 1,
          vtkRefractaLightingVolume::SurfaceCausticPhotonsName(),
          "a photon count, one tuple per surface texel", owner))))
  {
    return false;
  }
  arrays.Stamp();
  this->Lighting = arrays;
  return true;
}

//------------------------------------------------------------------------------
bool SurfaceBuffers::PrepareIrradiance(
  vtkOpenCLContext* context, double photonsPerFineTexel, vtkObject* owner)
{
  if (!this->IrradianceDirty && this->Irradiance &&
    photonsPerFineTexel == this->PhotonsPerFineTexel)
  {
    return true;
  }
  this->Caustic = 1;
  this->FineCausticTexels = 0;
  // Each side's irradiance (3 per texel, then its fine caustic texels) and corner values.
  std::vector<float> planes[Sides], planeCorners[Sides];
  for (int side = 0; side < Sides; ++side)
  {
    planes[side].assign(static_cast<size_t>(this->Texels) * 3, 0.0f);
  }
  if (vtkDataArray* array = this->Lighting.Irradiance)
  {
    if (!this->CheckTuples(
          array, this->Texels, vtkRefractaLightingVolume::SurfaceIrradianceName(), owner))
    {
      return false;
    }
    for (int side = 0; side < Sides; ++side)
    {
      for (vtkIdType i = 0; i < this->Texels; ++i)
      {
        for (int c = 0; c < 3; ++c)
        {
          planes[side][3 * i + c] = static_cast<float>(
            vtkRefractaLightingVolume::GetSurfaceSideValue(array, i, side, c, 3));
        }
      }
      if (this->Lighting.Caustic &&
        !this->SplitCaustic(planes[side], side, photonsPerFineTexel, owner))
      {
        return false;
      }
    }
  }
  // The corners' irradiance from the atlas as the kernel reads it (less the caustic light its
  // fine texels show, which is reconstructed within each triangle).
  for (int side = 0; side < Sides; ++side)
  {
    this->Set->ComputeCornerIrradiance(planes[side].data(), planeCorners[side]);
  }
  // The kernel's layout (view_surfaces.cl): a texel's sides side by side (front RGB, back RGB),
  // and a triangle's 9 corner floats of the front, then the back's.
  std::vector<float> values = Interleave(planes, 3);
  std::vector<float> corners = Interleave(planeCorners, 9);
  if (corners.empty())
  {
    corners.assign(3, 0.0f); // no triangles: a buffer of one value, never read
  }
  this->Irradiance = context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    values.size() * sizeof(float), values.data(), "surface irradiance", owner);
  this->Corners = this->Irradiance
    ? context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, corners.size() * sizeof(float),
        corners.data(), "surface corner irradiance", owner)
    : vtkOpenCLBuffer();
  if (!this->Irradiance || !this->Corners)
  {
    return false;
  }
  this->IrradianceDirty = false;
  this->PhotonsPerFineTexel = photonsPerFineTexel;
  return true;
}

//------------------------------------------------------------------------------
bool SurfaceBuffers::SplitCaustic(
  std::vector<float>& values, int side, double photonsPerFineTexel, vtkObject* owner)
{
  vtkDataArray* caustic = this->Lighting.Caustic;
  vtkDataArray* photons = this->Lighting.CausticPhotons;
  const vtkIdType texels = this->Texels;
  const vtkIdType fine = caustic->GetNumberOfTuples();
  const int c = texels > 0 ? static_cast<int>(std::lround(std::sqrt(double(fine) / texels))) : 0;
  if (texels == 0 || c < 2 || static_cast<vtkIdType>(c) * c * texels != fine)
  {
    std::ostringstream msg;
    msg << "The lighting volume's field array '"
        << vtkRefractaLightingVolume::SurfaceCausticIrradianceName() << "' has " << fine
        << " tuples; it needs c^2 x " << texels
        << " (c >= 2, the caustic atlas's subdivision of the surface set's " << texels
        << " texels).";
    ReportError(owner, msg.str());
    return false;
  }
  if (!this->CheckTuples(
        photons, texels, vtkRefractaLightingVolume::SurfaceCausticPhotonsName(), owner))
  {
    return false;
  }
  // The atlas keeps all of a texel's light; where the fine texels are read, their sum (the
  // caustic part) leaves the atlas value, so each photon is shown once. Each side on its own.
  auto photonsOf = [photons, side](vtkIdType texel)
  { return vtkRefractaLightingVolume::GetSurfaceSideValue(photons, texel, side, 0, 1); };
  const vtkIdType c2 = static_cast<vtkIdType>(c) * c;
  const double needed = photonsPerFineTexel * static_cast<double>(c2);
  std::vector<float> fineValues(static_cast<size_t>(fine) * 3, 0.0f);
  const std::vector<int>& info = this->Set->GetTriangleInfo();
  // Fine texel (in the triangle) -> its atlas texel, one table per subdivision n.
  std::map<int, std::vector<int>> tables;
  for (size_t k = 0; k + REFRACTA_TRIANGLE_INFO_INTS <= info.size();
       k += REFRACTA_TRIANGLE_INFO_INTS)
  {
    const int first = info[k + REFRACTA_TRIANGLE_INFO_TEXEL];
    const int n = info[k + REFRACTA_TRIANGLE_INFO_SUBDIVISION];
    bool any = false; // most triangles have no texel to read fine: no table needed
    for (int t = 0; t < n * n && !any; ++t)
    {
      any = photonsOf(first + t) >= needed;
    }
    if (!any)
    {
      continue;
    }
    std::vector<int>& coarseOf = tables[n];
    if (coarseOf.empty())
    {
      FineToCoarseTexels(n, c, coarseOf);
    }
    std::vector<double> removed(3 * static_cast<size_t>(n) * n, 0.0);
    for (size_t f = 0; f < coarseOf.size(); ++f)
    {
      const vtkIdType coarse = first + coarseOf[f];
      if (photonsOf(coarse) < needed)
      {
        continue;
      }
      const vtkIdType index = c2 * first + static_cast<vtkIdType>(f);
      for (int ch = 0; ch < 3; ++ch)
      {
        const double e =
          vtkRefractaLightingVolume::GetSurfaceSideValue(caustic, index, side, ch, 3);
        fineValues[3 * index + ch] = static_cast<float>(e);
        removed[3 * coarseOf[f] + ch] += e / static_cast<double>(c2);
      }
    }
    for (int t = 0; t < n * n; ++t)
    {
      this->FineCausticTexels += photonsOf(first + t) >= needed ? 1 : 0;
      for (int ch = 0; ch < 3; ++ch)
      {
        float& e = values[3 * static_cast<size_t>(first + t) + ch];
        e = static_cast<float>(std::max(0.0, e - removed[3 * t + ch]));
      }
    }
  }
  values.insert(values.end(), fineValues.begin(), fineValues.end());
  this->Caustic = c;
  return true;
}

//------------------------------------------------------------------------------
void SurfaceBuffers::FineToCoarseTexels(int n, int c, std::vector<int>& coarseOf)
{
  // Each fine texel lies inside one atlas texel (the grid lines of n are among those of n c):
  // its centroid finds it.
  const int fine = n * c * n * c;
  coarseOf.resize(fine);
  for (int f = 0; f < fine; ++f)
  {
    double corners[6];
    vtkRefractaSurfaceSet::GetTexelCorners(f, n * c, corners);
    const float u = static_cast<float>((corners[0] + corners[2] + corners[4]) / 3);
    const float v = static_cast<float>((corners[1] + corners[3] + corners[5]) / 3);
    coarseOf[f] = vtkRefractaSurfaceSet::TexelIndex(u, v, n);
  }
}

//------------------------------------------------------------------------------
bool SurfaceBuffers::CheckTuples(
  vtkDataArray* array, vtkIdType expected, const char* name, vtkObject* owner) const
{
  if (array->GetNumberOfTuples() == expected)
  {
    return true;
  }
  std::ostringstream msg;
  msg << "The lighting volume's field array '" << name << "' has " << array->GetNumberOfTuples()
      << " tuples but the surface set has " << expected
      << " texels; compute the lighting with the same surface set (the photon pass's "
         "SetSurfaces) after its last change.";
  ReportError(owner, msg.str());
  return false;
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
