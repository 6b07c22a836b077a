// The surface stage of vtkPhotonTracer: builds the vtkRefractaSurfaceSet, grows the box the lights
// aim at by the surfaces' bounds, uploads the BVH, triangles, texel table and albedo once per
// build of the set (kept between runs), and turns the fixed-point texel deposits into irradiance.
#include "vtkPhotonTracer.h"
#include "vtkPhotonTracerInternals.h"

#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaGridCuts.h"
#include "vtkRefractaGridFrame.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"

#include "refracta_surfaces.cl" // the flattened surface layout, shared with the kernels

#include <algorithm>
#include <memory>

using namespace vtkPhotonTracerDetail;

namespace
{
// Offset of a reflected photon from the surface, relative to the size of the scene: some hundred
// float roundings of the hit point, far below any length that matters for the light.
constexpr double RelativeSurfaceEpsilon = 1e-5;
// Margin around the surfaces' bounds in the box the lights aim at, relative to the scene's size.
constexpr double RelativeEmitMargin = 1e-3;

// The size of the scene the photons fly in: the emission box's extent and distance from the
// grid-local origin, whichever is larger (what float roundings of its points scale with).
double SceneSize(const double lo[3], const double hi[3])
{
  double size = 0;
  for (int a = 0; a < 3; ++a)
  {
    size = std::max({ size, hi[a] - lo[a], std::fabs(lo[a]), std::fabs(hi[a]) });
  }
  return size;
}
}

//------------------------------------------------------------------------------
void vtkPhotonTracerDetail::BodyMedia(vtkRefractaSurfaceSet* set, bool& attenuates, bool& scatters)
{
  attenuates = scatters = false;
  for (int s = 0; set && s < set->GetNumberOfSurfaces(); ++s)
  {
    vtkRefractaSurfaceMaterial* m = set->GetMaterial(s);
    if (m->GetKind() != vtkRefractaSurfaceMaterial::DIELECTRIC || !m->GetUseInsideMedium())
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      attenuates = attenuates || m->GetInsideExtinction()[c] > 0.0;
      scatters = scatters || m->GetInsideExtinction()[c] * m->GetInsideAlbedo()[c] > 0.0;
    }
  }
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::SetSurfaces(vtkRefractaSurfaceSet* surfaces)
{
  if (this->Surfaces != surfaces)
  {
    this->Surfaces = surfaces;
    this->Modified();
  }
}

vtkRefractaSurfaceSet* vtkPhotonTracer::GetSurfaces()
{
  return this->Surfaces;
}

void vtkPhotonTracer::SetMediumToWorld(vtkMatrix4x4* matrix)
{
  if (this->MediumToWorld != matrix)
  {
    this->MediumToWorld = matrix;
    this->Modified();
  }
}

vtkMatrix4x4* vtkPhotonTracer::GetMediumToWorld()
{
  return this->MediumToWorld;
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::PrepareSurfaces(Internals& run)
{
  const Medium& m = run.M;
  std::copy(m.ProxyLo, m.ProxyLo + 3, run.EmitLo);
  std::copy(m.ProxyHi, m.ProxyHi + 3, run.EmitHi);
  run.Surfaces = nullptr;
  // Without surfaces the event loop still runs for analog scattering: a photon leaving the box
  // steps this far out, so that it is not taken for inside again.
  run.SurfaceEpsilon = RelativeSurfaceEpsilon * SceneSize(run.EmitLo, run.EmitHi);
  if (!this->Surfaces || this->Surfaces->GetNumberOfSurfaces() == 0)
  {
    return true;
  }
  if (!this->Surfaces->Build())
  {
    vtkErrorMacro("The surface set could not be built (see its error); the photon pass needs a "
                  "set within its limits or no surfaces.");
    return false;
  }
  if (this->Surfaces->GetNumberOfTriangles() == 0)
  {
    return true; // nothing left to hit (empty or rejected meshes were reported by the set)
  }
  run.Surfaces = this->Surfaces;
  this->UsedSurfaces = true;
  vtkNew<vtkRefractaGridFrame> grid;
  grid->SetImage(run.Input);
  // Grid-local -> world of the surfaces: the medium's placement after the grid's own map.
  vtkNew<vtkMatrix4x4> localToData, localToWorld, worldToData;
  grid->GetLocalToWorldMatrix(localToData);
  localToWorld->DeepCopy(localToData);
  if (this->MediumToWorld)
  {
    vtkMatrix4x4::Multiply4x4(this->MediumToWorld, localToData, localToWorld);
    vtkMatrix4x4::Invert(this->MediumToWorld, worldToData);
  }
  double b[6];
  this->Surfaces->GetBounds(b);
  for (int corner = 0; corner < 8; ++corner)
  {
    const double world[3] = { b[(corner & 1) ? 1 : 0], b[(corner & 2) ? 3 : 2],
      b[(corner & 4) ? 5 : 4] };
    double data[4] = { world[0], world[1], world[2], 1.0 }, local[3];
    worldToData->MultiplyPoint(data, data);
    grid->WorldToLocalPoint(data, local);
    for (int a = 0; a < 3; ++a)
    {
      run.EmitLo[a] = std::min(run.EmitLo[a], local[a]);
      run.EmitHi[a] = std::max(run.EmitHi[a], local[a]);
    }
  }
  // Grid-local -> surface frame: world = LocalToWorld x, surface = world - FrameOrigin.
  const double* l2w = localToWorld->GetData();
  const double* frameOrigin = this->Surfaces->GetBVH()->GetFrameOrigin();
  for (int r = 0; r < 3; ++r)
  {
    run.Frame[r] =
      Float4(l2w[4 * r], l2w[4 * r + 1], l2w[4 * r + 2], l2w[4 * r + 3] - frameOrigin[r]);
  }
  this->FindGridCuts(run, localToWorld);
  const double size = SceneSize(run.EmitLo, run.EmitHi);
  run.SurfaceEpsilon = RelativeSurfaceEpsilon * size;
  // Photons start where their ray enters this box: grow it so that they start off any surface
  // on its boundary (a photon starting on a surface would not see it, t > 0 only).
  for (int a = 0; a < 3; ++a)
  {
    run.EmitLo[a] -= RelativeEmitMargin * size;
    run.EmitHi[a] += RelativeEmitMargin * size;
  }
  return true;
}

namespace
{
// Irradiance of `count` texels from their fixed-point accumulators (3 per texel, at `scale`);
// texel t has the area of coarse texel t / perCoarse over perCoarse (same triangle, same area).
void ResolveTexels(double scale, const cl_long* fixed, vtkIdType count, vtkIdType perCoarse,
  const std::vector<double>& coarseAreas, vtkFloatArray* out, const char* name)
{
  // Front RGB, back RGB per texel, as the kernel's sided texels 2 t + side hold them.
  constexpr int components = 3 * vtkRefractaLightingVolume::NUMBER_OF_SURFACE_SIDES;
  out->SetName(name);
  out->SetNumberOfComponents(components);
  out->SetNumberOfTuples(count);
  for (vtkIdType t = 0; t < count; ++t)
  {
    const double area = coarseAreas[t / perCoarse] / static_cast<double>(perCoarse);
    for (int c = 0; c < components; ++c)
    {
      // Deposited flux / texel area; rounding of the fixed point can leave a tiny negative.
      const double flux = static_cast<double>(fixed[components * t + c]) / scale;
      out->SetTypedComponent(t, c, static_cast<float>(std::max(flux, 0.0) / area));
    }
  }
}

}

//------------------------------------------------------------------------------
void vtkPhotonTracer::FindGridCuts(Internals& run, vtkMatrix4x4* localToWorld)
{
  if (!this->Cuts)
  {
    this->Cuts = vtkSmartPointer<vtkRefractaGridCuts>::New();
  }
  this->Cuts->Update(this->Surfaces, run.M.Dims, run.M.Spacing, localToWorld);
  run.Cuts = this->Cuts->HasCuts() ? this->Cuts.Get() : nullptr;
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::UploadSurfaces(Internals& run)
{
  vtkOpenCLContext* ctx = run.Context;
  Allocator& alloc = run.Alloc;
  this->LastRunReusedSurfaces = false;
  if (!run.Surfaces)
  {
    // The kernels take the arguments whatever the variant: placeholders.
    run.SurfNodes = alloc.Make(CL_MEM_READ_ONLY, 16, nullptr, "surface nodes (none)");
    run.SurfTriangles = alloc.Make(CL_MEM_READ_ONLY, 16, nullptr, "surface triangles (none)");
    run.SurfInfo = alloc.Make(CL_MEM_READ_ONLY, 16, nullptr, "surface texels (none)");
    run.SurfAlbedo = alloc.Make(CL_MEM_READ_ONLY, 16, nullptr, "surface albedo (none)");
    run.SurfIrradiance = alloc.Make(CL_MEM_READ_WRITE, 16, nullptr, "surface irradiance (none)");
    run.SurfNormals = alloc.Make(CL_MEM_READ_ONLY, 16, nullptr, "surface normals (none)");
    run.SurfInterfaces = alloc.Make(CL_MEM_READ_ONLY, 16, nullptr, "surface interfaces (none)");
    run.SurfBodies = alloc.Make(CL_MEM_READ_ONLY, 16, nullptr, "surface bodies (none)");
    for (auto& row : run.Frame)
    {
      row = Float4(0, 0, 0, 0);
    }
    this->KeptSurfaces.reset();
    return run.SurfNodes && run.SurfTriangles && run.SurfInfo && run.SurfAlbedo &&
      run.SurfIrradiance && run.SurfNormals && run.SurfInterfaces && run.SurfBodies &&
      this->UploadGridCuts(run);
  }
  vtkRefractaSurfaceSet* set = run.Surfaces;
  SurfaceCache* kept = this->KeptSurfaces.get();
  if (kept && kept->Set == set && kept->Builds == set->GetNumberOfBuilds() && kept->Context == ctx)
  {
    run.SurfNodes = std::move(kept->Nodes);
    run.SurfTriangles = std::move(kept->Triangles);
    run.SurfInfo = std::move(kept->Info);
    run.SurfAlbedo = std::move(kept->Albedo);
    run.SurfNormals = std::move(kept->Normals);
    run.SurfInterfaces = std::move(kept->Interfaces);
    run.SurfBodies = std::move(kept->Bodies);
    alloc.Bytes += kept->Bytes;
    this->LastRunReusedSurfaces = true;
  }
  else
  {
    const vtkRefractaBVH* bvh = set->GetBVH();
    const auto& nodes = bvh->GetNodes();
    const auto& triangles = bvh->GetFloatTriangles();
    const auto& info = set->GetTriangleInfo();
    const auto& albedo = set->GetTexelAlbedo();
    const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
    run.SurfNodes = alloc.Make(in, nodes.size() * sizeof(float), nodes.data(), "surface BVH");
    run.SurfTriangles =
      alloc.Make(in, triangles.size() * sizeof(float), triangles.data(), "surface triangles");
    run.SurfInfo = alloc.Make(in, info.size() * sizeof(int), info.data(), "surface texel table");
    run.SurfAlbedo =
      alloc.Make(in, albedo.size() * sizeof(float), albedo.data(), "surface texel albedo");
    const auto& normals = set->GetTriangleNormals();
    const auto& interfaces = set->GetSurfaceInterfaces();
    run.SurfNormals =
      alloc.Make(in, normals.size() * sizeof(float), normals.data(), "surface corner normals");
    run.SurfInterfaces = alloc.Make(
      in, interfaces.size() * sizeof(float), interfaces.data(), "surface interface indices");
    const auto& bodies = set->GetSurfaceBodies();
    run.SurfBodies =
      alloc.Make(in, bodies.size() * sizeof(float), bodies.data(), "surface body media");
  }
  this->KeptSurfaces.reset();
  // Three accumulators per texel side (photon_surfaces.cl's sided texels); the caustic atlas's
  // c^2 fine texels per coarse texel follow the coarse ones, then one caustic photon count per
  // coarse texel side.
  const size_t c2 = static_cast<size_t>(run.Caustic) * run.Caustic;
  const size_t sided = static_cast<size_t>(set->GetNumberOfTexels()) *
    vtkRefractaLightingVolume::NUMBER_OF_SURFACE_SIDES;
  const size_t accumulators = run.Caustic > 1 ? sided * (3 + 3 * c2 + 1) : 3 * sided;
  run.SurfIrradiance = alloc.Make(
    CL_MEM_READ_WRITE, accumulators * sizeof(cl_long), nullptr, "surface irradiance accumulator");
  run.SurfIrradianceBytes = accumulators * sizeof(cl_long);
  return run.SurfNodes && run.SurfTriangles && run.SurfInfo && run.SurfAlbedo &&
    run.SurfIrradiance && run.SurfNormals && run.SurfInterfaces && run.SurfBodies &&
    this->UploadGridCuts(run) &&
    ctx->ZeroBuffer(run.SurfIrradiance.Get(), accumulators * sizeof(cl_long), this);
}

//------------------------------------------------------------------------------
// vtkRefractaGridCuts' byte per voxel (cut links, near an opaque triangle) for the march's sided
// deposits and the smoothing (without cuts a one-byte stand-in: the kernels take the argument
// whatever the variant). Per run: the grid may change between runs.
bool vtkPhotonTracer::UploadGridCuts(Internals& run)
{
  Allocator& alloc = run.Alloc;
  const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  run.CutLinksBuffer = run.Cuts
    ? alloc.Make(in, run.Cuts->GetLinks().size(), run.Cuts->GetLinks().data(),
        "links and voxels near opaque surfaces")
    : alloc.Make(CL_MEM_READ_ONLY, 16, nullptr, "links and voxels near opaque surfaces (none)");
  run.NumberOfScaledVoxels = 0;
  if (run.Cuts && !run.Cuts->GetScaledVoxels().empty())
  {
    const std::vector<vtkIdType>& scaled = run.Cuts->GetScaledVoxels();
    const std::vector<cl_ulong> voxels(scaled.begin(), scaled.end());
    const std::vector<float>& scales = run.Cuts->GetVolumeScales();
    run.ScaledVoxels =
      alloc.Make(in, voxels.size() * sizeof(cl_ulong), voxels.data(), "voxels of scaled volume");
    run.VolumeScales =
      alloc.Make(in, scales.size() * sizeof(float), scales.data(), "their volume scales");
    if (!run.ScaledVoxels || !run.VolumeScales)
    {
      return false;
    }
    run.NumberOfScaledVoxels = static_cast<cl_uint>(voxels.size());
  }
  return static_cast<bool>(run.CutLinksBuffer);
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::SetSurfaceArguments(Internals& run, cl_kernel kernel, cl_uint& index)
{
  const cl_int nodeCount =
    run.Surfaces ? static_cast<cl_int>(run.Surfaces->GetBVH()->GetNumberOfNodes()) : 0;
  const cl_float epsilon = static_cast<cl_float>(run.SurfaceEpsilon);
  const cl_mem nodes = run.SurfNodes.Get(), triangles = run.SurfTriangles.Get();
  const cl_mem info = run.SurfInfo.Get(), albedo = run.SurfAlbedo.Get();
  const cl_mem irradiance = run.SurfIrradiance.Get();
  cl_int status = CL_SUCCESS;
  auto set = [&](size_t bytes, const void* value)
  {
    if (status == CL_SUCCESS)
    {
      status = clSetKernelArg(kernel, index++, bytes, value);
    }
  };
  set(sizeof(cl_mem), &nodes);
  set(sizeof(cl_int), &nodeCount);
  set(sizeof(cl_mem), &triangles);
  set(sizeof(cl_mem), &info);
  set(sizeof(cl_mem), &albedo);
  set(sizeof(cl_mem), &irradiance);
  for (const auto& row : run.Frame)
  {
    set(sizeof(cl_float4), &row);
  }
  set(sizeof(cl_float), &epsilon);
  // The fine caustic atlas's first sided texel (a run-time argument: one program serves every
  // set).
  const cl_long causticOffset = run.Caustic > 1
    ? static_cast<cl_long>(run.Surfaces->GetNumberOfTexels()) *
      vtkRefractaLightingVolume::NUMBER_OF_SURFACE_SIDES
    : 0;
  set(sizeof(cl_long), &causticOffset);
  const cl_mem anisotropy = run.AnisotropyBuffer.Get(), multiple = run.MultipleFixed.Get();
  set(sizeof(cl_mem), &anisotropy);
  set(sizeof(cl_mem), &multiple);
  const cl_mem normals = run.SurfNormals.Get(), interfaces = run.SurfInterfaces.Get();
  set(sizeof(cl_mem), &normals);
  set(sizeof(cl_mem), &interfaces);
  const cl_mem bodies = run.SurfBodies.Get();
  set(sizeof(cl_mem), &bodies);
  const cl_mem cutLinks = run.CutLinksBuffer.Get();
  set(sizeof(cl_mem), &cutLinks);
  return run.Context->Check(status, "clSetKernelArg(surfaces)", this);
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::ResolveSurfaces(Internals& run)
{
  if (!run.Surfaces)
  {
    return true;
  }
  constexpr int sides = vtkRefractaLightingVolume::NUMBER_OF_SURFACE_SIDES;
  const vtkIdType texels = run.Surfaces->GetNumberOfTexels();
  const vtkIdType c2 = static_cast<vtkIdType>(run.Caustic) * run.Caustic;
  const vtkIdType fine = run.Caustic > 1 ? texels * c2 : 0;
  const vtkIdType counts = run.Caustic > 1 ? sides * texels : 0;
  std::vector<cl_long> fixed(3 * sides * static_cast<size_t>(texels + fine) + counts);
  if (!run.Context->ReadBuffer(
        run.SurfIrradiance.Get(), fixed.size() * sizeof(cl_long), fixed.data(), this))
  {
    return false;
  }
  const std::vector<double>& areas = run.Surfaces->GetTexelAreas();
  ResolveTexels(run.Scale, fixed.data(), texels, 1, areas, run.Irradiance,
    vtkRefractaLightingVolume::SurfaceIrradianceName());
  if (fine > 0)
  {
    // A triangle's texels all have one area, and its fine texels (from its first texel c^2 on,
    // subdivision n c) 1 / c^2 of it: fine texel f has the area of coarse texel f / c^2 over c^2.
    ResolveTexels(run.Scale, fixed.data() + 3 * sides * texels, fine, c2, areas,
      run.CausticIrradiance, vtkRefractaLightingVolume::SurfaceCausticIrradianceName());
    vtkIdTypeArray* photons = run.CausticPhotons;
    photons->SetName(vtkRefractaLightingVolume::SurfaceCausticPhotonsName());
    photons->SetNumberOfComponents(sides);
    photons->SetNumberOfTuples(texels);
    const cl_long* count = fixed.data() + 3 * sides * (texels + fine);
    std::copy(count, count + counts, photons->GetPointer(0));
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::WriteSurfaceOutput(Internals& run, vtkImageData* output)
{
  if (run.Surfaces)
  {
    output->GetFieldData()->AddArray(run.Irradiance);
    if (run.Caustic > 1)
    {
      output->GetFieldData()->AddArray(run.CausticIrradiance);
      output->GetFieldData()->AddArray(run.CausticPhotons);
    }
  }
  if (run.Analog)
  {
    output->GetPointData()->AddArray(run.Multiple);
    output->GetPointData()->AddArray(run.MultipleDirection);
  }
  if (run.SplitOrders > 0)
  {
    output->GetPointData()->AddArray(run.LatticeSource);
    output->GetPointData()->AddArray(run.LatticeSourceDirection);
  }
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::KeepSurfaces(Internals& run)
{
  if (!run.Surfaces)
  {
    return;
  }
  auto kept = std::make_unique<SurfaceCache>();
  kept->Set = run.Surfaces;
  kept->Builds = run.Surfaces->GetNumberOfBuilds();
  kept->Context = run.Context;
  auto rounded = [](size_t bytes)
  { return static_cast<double>((std::max<size_t>(bytes, 1) + 15) / 16 * 16); };
  kept->Bytes = rounded(run.Surfaces->GetBVH()->GetNodes().size() * 4) +
    rounded(run.Surfaces->GetBVH()->GetFloatTriangles().size() * 4) +
    rounded(run.Surfaces->GetTriangleInfo().size() * 4) +
    rounded(run.Surfaces->GetTexelAlbedo().size() * 4) +
    rounded(run.Surfaces->GetTriangleNormals().size() * 4) +
    rounded(run.Surfaces->GetSurfaceInterfaces().size() * 4) +
    rounded(run.Surfaces->GetSurfaceBodies().size() * 4);
  kept->Nodes = std::move(run.SurfNodes);
  kept->Triangles = std::move(run.SurfTriangles);
  kept->Info = std::move(run.SurfInfo);
  kept->Albedo = std::move(run.SurfAlbedo);
  kept->Normals = std::move(run.SurfNormals);
  kept->Interfaces = std::move(run.SurfInterfaces);
  kept->Bodies = std::move(run.SurfBodies);
  this->KeptSurfaces = std::move(kept);
}
