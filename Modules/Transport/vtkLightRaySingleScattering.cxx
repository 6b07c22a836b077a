#include "vtkLightRaySingleScattering.h"
#include "vtkLightRaySingleScatteringInternals.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMediumValidator.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaGridFrame.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaSettings.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTypeInt64Array.h"

#include <algorithm>
#include <array>
#include <cmath>

using namespace vtkPhotonTracerDetail;

namespace
{
constexpr int MacroCell = 8;                    // LR_MACRO in light_rays.cl
constexpr double OpaqueVoxelDepth = 30.0;       // optical depth across a voxel called opaque
constexpr double RelativeSurfaceEpsilon = 1e-5; // as vtkPhotonTracer's shadow rays
}

vtkStandardNewMacro(vtkLightRaySingleScattering);
vtkRefractaCxxSetClampMacro(vtkLightRaySingleScattering, LightRadius, 0.0, 1e30);
vtkRefractaCxxSetClampMacro(vtkLightRaySingleScattering, DirectionalLightAngularRadius, 0.0, 45.0);
vtkRefractaCxxSetClampMacro(vtkLightRaySingleScattering, ErrorTolerance, 0.0, 1e30);
vtkRefractaCxxSetVector3Macro(vtkLightRaySingleScattering, ViewPoint);

//------------------------------------------------------------------------------
vtkLightRaySingleScattering::vtkLightRaySingleScattering()
  : Lights(vtkSmartPointer<vtkLightCollection>::New())
  , SamplePositions(vtkSmartPointer<vtkDoubleArray>::New())
  , SampleLevels(vtkSmartPointer<vtkIntArray>::New())
{
  this->SamplePositions->SetNumberOfComponents(3);
}

vtkLightRaySingleScattering::~vtkLightRaySingleScattering() = default;

const char* vtkLightRaySingleScattering::GetMethodName(int method)
{
  return method == INTERPOLATED ? "interpolated" : "light_rays";
}

void vtkLightRaySingleScattering::AddLight(vtkLight* light)
{
  this->Lights->AddItem(light);
  this->Modified();
}

void vtkLightRaySingleScattering::RemoveAllLights()
{
  this->Lights->RemoveAllItems();
  this->Modified();
}

void vtkLightRaySingleScattering::SetLights(vtkLightCollection* lights)
{
  this->Lights = lights ? vtkSmartPointer<vtkLightCollection>(lights)
                        : vtkSmartPointer<vtkLightCollection>::New();
  this->Modified();
}

vtkLightCollection* vtkLightRaySingleScattering::GetLights()
{
  return this->Lights;
}

void vtkLightRaySingleScattering::SetSurfaces(vtkRefractaSurfaceSet* surfaces)
{
  if (this->Surfaces != surfaces)
  {
    this->Surfaces = surfaces;
    this->Modified();
  }
}

vtkRefractaSurfaceSet* vtkLightRaySingleScattering::GetSurfaces()
{
  return this->Surfaces;
}

void vtkLightRaySingleScattering::SetMediumToWorld(vtkMatrix4x4* matrix)
{
  if (this->MediumToWorld != matrix)
  {
    this->MediumToWorld = matrix;
    this->Modified();
  }
}

vtkMatrix4x4* vtkLightRaySingleScattering::GetMediumToWorld()
{
  return this->MediumToWorld;
}

void vtkLightRaySingleScattering::SetContext(vtkOpenCLContext* context)
{
  if (this->Context != context)
  {
    this->Context = context;
    this->Modified();
  }
}

vtkOpenCLContext* vtkLightRaySingleScattering::GetContext()
{
  return this->Context;
}

vtkDoubleArray* vtkLightRaySingleScattering::GetSamplePositions()
{
  return this->SamplePositions;
}

vtkIntArray* vtkLightRaySingleScattering::GetSampleLevels()
{
  return this->SampleLevels;
}

//------------------------------------------------------------------------------
int vtkLightRaySingleScattering::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkLightRaySingleScattering::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (inInfo && inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(),
      inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkLightRaySingleScattering::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  output->Initialize();
  this->TotalSeconds = this->SamplingSeconds = this->VoxelSeconds = 0;
  this->NumberOfSamples = this->NumberOfUncoveredVoxels = 0;
  this->NumberOfEvaluatedPoints = this->NumberOfBoxMeanVoxels = 0;
  this->BoxMeanSeconds = 0;
  this->LastRunAborted = false;
  this->LastNumberOfLobes = 1;
  this->SamplesPerLevel.clear();
  this->SamplePositions->SetNumberOfTuples(0);
  this->SampleLevels->SetNumberOfTuples(0);
  const auto start = Clock::now();
  vtkNew<vtkMediumValidator> validator;
  if (!input || !validator->Validate(input))
  {
    vtkErrorMacro("Input 0 is not a valid Refracta medium: "
      << (input ? validator->GetErrorMessage() : "no vtkImageData on port 0")
      << "; a vtkImageData with vtkRefractaMedium's arrays is needed.");
    return 0;
  }
  Internals run;
  run.Input = input;
  if (!this->SetUp(run))
  {
    return 0;
  }
  this->AssignLobes(run);
  run.AllocateOutput();
  const bool trivial = run.LightCount == 0 || !run.AnyScattering;
  if (trivial)
  {
    // Nothing to light or nothing scatters: the lighting volume is zero, which is right.
    vtkWarningMacro(<< (run.LightCount == 0 ? "No lights (or none switched on with power)"
                                            : "Nothing in the medium scatters (sigma_s = 0)")
                    << ": the single-scattering source is zero everywhere.");
    for (vtkFloatArray* a : { run.Radiance.Get(), run.Direction.Get() })
    {
      std::fill_n(a->GetPointer(0), 3 * run.M.Voxels, 0.0f);
    }
  }
  else
  {
    if (!this->Upload(run) ||
      !(this->Method == INTERPOLATED ? this->RunInterpolation(run) : this->RunLightRays(run)) ||
      (this->SharpVoxelBoxMeans && !run.Aborted && !this->RunBoxMeans(run)))
    {
      return 0;
    }
  }
  if (run.Aborted || this->GetAbortExecute())
  {
    // An abort is not an error: empty output, no message.
    output->Initialize();
    this->LastRunAborted = true;
    return 1;
  }
  this->WriteOutput(run, output);
  this->UpdateProgress(1.0);
  this->TotalSeconds = Seconds(start);
  return 1;
}

//------------------------------------------------------------------------------
// The medium (sigma_t, sigma_s, macro cells), the lights and the surfaces.
bool vtkLightRaySingleScattering::SetUp(Internals& run)
{
  Medium& m = run.M;
  LoadMedium(run.Input, false, m);
  run.MinimumDistance = 0.5 * std::min({ m.Spacing[0], m.Spacing[1], m.Spacing[2] });
  run.Scattering.resize(3 * m.Voxels);
  for (size_t i = 0; i < 3 * m.Voxels; ++i)
  {
    run.Scattering[i] = m.Extinction[i] * m.Albedo[i];
    run.AnyScattering = run.AnyScattering || run.Scattering[i] > 0.0f;
  }
  for (int a = 0; a < 3; ++a)
  {
    run.MacroDims[a] = (m.Dims[a] + MacroCell - 1) / MacroCell;
  }
  run.Macro.assign(
    static_cast<size_t>(run.MacroDims[0]) * run.MacroDims[1] * run.MacroDims[2], 0.0f);
  // Each voxel's sigma_t counts in every macro cell within one voxel of it: a piece's trilinear
  // stencil reaches that far.
  for (int k = 0; k < m.Dims[2]; ++k)
  {
    for (int j = 0; j < m.Dims[1]; ++j)
    {
      for (int i = 0; i < m.Dims[0]; ++i)
      {
        const size_t v =
          i + static_cast<size_t>(m.Dims[0]) * (j + static_cast<size_t>(m.Dims[1]) * k);
        const float st =
          std::max({ m.Extinction[3 * v], m.Extinction[3 * v + 1], m.Extinction[3 * v + 2] });
        if (!(st > 0.0f))
        {
          continue;
        }
        const int ijk[3] = { i, j, k };
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a)
        {
          lo[a] = std::max(0, ijk[a] - 1) / MacroCell;
          hi[a] = std::min(m.Dims[a] - 1, ijk[a] + 1) / MacroCell;
        }
        for (int c = lo[2]; c <= hi[2]; ++c)
        {
          for (int b = lo[1]; b <= hi[1]; ++b)
          {
            for (int a = lo[0]; a <= hi[0]; ++a)
            {
              float& cell =
                run.Macro[a + run.MacroDims[0] * (b + static_cast<size_t>(run.MacroDims[1]) * c)];
              cell = std::max(cell, st);
            }
          }
        }
      }
    }
  }
  return this->SetUpLights(run) && this->SetUpSurfaces(run);
}

//------------------------------------------------------------------------------
// Lights, converted to the grid-local frame in double precision (light_rays.cl's layout).
bool vtkLightRaySingleScattering::SetUpLights(Internals& run)
{
  const Medium& m = run.M;
  vtkNew<vtkRefractaGridFrame> grid;
  grid->SetImage(run.Input);
  vtkLight* light;
  vtkCollectionSimpleIterator it;
  int index = 0;
  for (this->Lights->InitTraversal(it); (light = this->Lights->GetNextLight(it)); ++index)
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    LocalLight local;
    std::string lightError;
    if (!ReadLocalLight(light, index, grid, local, lightError))
    {
      vtkErrorMacro(<< lightError);
      return false;
    }
    const double* p = local.Position;
    const double* axis = local.Axis;
    const double* colour = local.Colour; // x intensity
    const bool positional = local.Positional, spot = local.Spot;
    if (std::max({ colour[0], colour[1], colour[2] }) <= 0.0)
    {
      continue;
    }
    if (positional)
    {
      // A light inside an opaque voxel is legal but dark: say so.
      long ijk[3];
      bool inside = true;
      for (int a = 0; a < 3; ++a)
      {
        ijk[a] = std::lround(p[a] / m.Spacing[a]);
        inside = inside && ijk[a] >= 0 && ijk[a] < m.Dims[a];
      }
      if (inside)
      {
        const size_t v = ijk[0] + m.Dims[0] * (ijk[1] + static_cast<size_t>(m.Dims[1]) * ijk[2]);
        const double depth = std::min({ m.Spacing[0], m.Spacing[1], m.Spacing[2] }) *
          std::max({ m.Extinction[3 * v], m.Extinction[3 * v + 1], m.Extinction[3 * v + 2] });
        if (depth > OpaqueVoxelDepth)
        {
          vtkWarningMacro("Light " << index << " sits in voxel (" << ijk[0] << ", " << ijk[1]
                                   << ", " << ijk[2] << ") of optical depth " << depth
                                   << " across: it is opaque, so this light lights nothing "
                                      "beyond its own voxel.");
        }
      }
    }
    const double extent = positional
      ? this->LightRadius
      : std::sin(vtkMath::RadiansFromDegrees(this->DirectionalLightAngularRadius));
    const double half = vtkMath::RadiansFromDegrees(light->GetConeAngle());
    run.Lights.push_back(Float4(p, positional ? 1.0 : 0.0));
    run.Lights.push_back(Float4(axis, spot ? std::cos(half) : -2.0));
    run.Lights.push_back(
      Float4(colour[0], colour[1], colour[2], spot ? light->GetExponent() : 0.0));
    run.Lights.push_back(Float4(extent, extent > 0 ? this->LightQuadrature : 1, 0, 0));
    ++run.LightCount;
  }
  return true;
}

//------------------------------------------------------------------------------
// Surfaces: the built set and the grid-local -> surface-frame map of the shadow rays.
bool vtkLightRaySingleScattering::SetUpSurfaces(Internals& run)
{
  for (auto& row : run.Frame)
  {
    row = Float4(0, 0, 0, 0);
  }
  if (!this->Surfaces || this->Surfaces->GetNumberOfSurfaces() == 0)
  {
    return true;
  }
  if (!this->Surfaces->Build())
  {
    vtkErrorMacro("The surface set could not be built (see its error); the light rays need a "
                  "set within its limits or no surfaces.");
    return false;
  }
  if (this->Surfaces->GetNumberOfTriangles() == 0)
  {
    return true;
  }
  vtkNew<vtkRefractaGridFrame> grid;
  grid->SetImage(run.Input);
  vtkNew<vtkMatrix4x4> localToData, localToWorld;
  grid->GetLocalToWorldMatrix(localToData);
  localToWorld->DeepCopy(localToData);
  if (this->MediumToWorld)
  {
    vtkMatrix4x4::Multiply4x4(this->MediumToWorld, localToData, localToWorld);
  }
  const double* l2w = localToWorld->GetData();
  const double* frameOrigin = this->Surfaces->GetBVH()->GetFrameOrigin();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      run.SurfaceFrame[r][c] = l2w[4 * r + c] - (c == 3 ? frameOrigin[r] : 0.0);
    }
    run.Frame[r] = Float4(run.SurfaceFrame[r][0], run.SurfaceFrame[r][1], run.SurfaceFrame[r][2],
      run.SurfaceFrame[r][3]);
  }
  double b[6], size = 0;
  this->Surfaces->GetBounds(b);
  for (int a = 0; a < 3; ++a)
  {
    size = std::max({ size, b[2 * a + 1] - b[2 * a], run.M.Hi[a] - run.M.Lo[a] });
  }
  run.SurfaceEpsilon = static_cast<float>(RelativeSurfaceEpsilon * size);
  run.NodeCount = static_cast<int>(this->Surfaces->GetBVH()->GetNodes().size() / 8);
  return true;
}

//------------------------------------------------------------------------------
// Lobes only where they change the image: two lights or more over a medium that scatters with
// g != 0 (an isotropic phase function does not look at the direction).
void vtkLightRaySingleScattering::AssignLobes(Internals& run)
{
  const Medium& m = run.M;
  const int lights = run.LightCount;
  run.Lobes = lights >= 2 && run.AnyScattering && ScattersAnisotropically(m)
    ? std::min(this->MaximumRadianceLobes, lights)
    : 1;
  this->LastNumberOfLobes = run.Lobes;
  if (run.Lobes < 2)
  {
    return;
  }
  // Each light's travel direction at the medium's centre and its strength there.
  double centre[3];
  for (int a = 0; a < 3; ++a)
  {
    centre[a] = 0.5 * (m.Lo[a] + m.Hi[a]);
  }
  std::vector<std::array<double, 3>> travel(lights);
  std::vector<double> strength(lights);
  for (int l = 0; l < lights; ++l)
  {
    const cl_float4* light = &run.Lights[4 * static_cast<size_t>(l)];
    const bool positional = light[0].s[3] > 0.5f;
    for (int a = 0; a < 3; ++a)
    {
      travel[l][a] = positional ? centre[a] - light[0].s[a] : light[1].s[a];
    }
    const double r2 = Dot(travel[l].data(), travel[l].data());
    if (!Normalize(travel[l].data()))
    {
      travel[l] = { 0.0, 0.0, -1.0 }; // a light at the centre: any direction
    }
    // Irradiance E for a directional light, intensity I / r^2 for a positional one.
    const double colour = std::max({ light[2].s[0], light[2].s[1], light[2].s[2] });
    strength[l] =
      positional ? colour / std::max(r2, run.MinimumDistance * run.MinimumDistance) : colour;
  }
  const std::vector<int> lobe = GroupLightsByDirection(travel, strength, run.Lobes);
  for (int l = 0; l < lights; ++l)
  {
    run.Lights[4 * static_cast<size_t>(l) + 3].s[2] = static_cast<float>(lobe[l]);
  }
}

//------------------------------------------------------------------------------
bool vtkLightRaySingleScattering::Upload(Internals& run)
{
  vtkOpenCLContext* ctx = this->Context ? this->Context.Get() : vtkOpenCLContext::GetDefault();
  if (!ctx || !ctx->Initialize())
  {
    vtkErrorMacro("No OpenCL device: "
      << (ctx ? ctx->GetLastErrorMessage() : "no context")
      << "; the light-ray pass needs an OpenCL 1.2 device (REFRACTA_OPENCL_DEVICE).");
    return false;
  }
  run.Context = ctx;
  // Node-plane cuts where the photon pass makes them (LoadMedium decides for both): the same
  // optical depths.
  std::string options = run.M.NodeCuts ? "-DLR_NODE_CUTS=1" : "";
  if (run.Lobes > 1)
  {
    options += " -DLR_LOBES=" + std::to_string(run.Lobes);
  }
  run.Program = ctx->GetProgram(
    { "refracta_common.cl", "refracta_surfaces.cl", "light_rays.cl" }, options, this);
  if (!run.Program)
  {
    return false;
  }
  const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  const Medium& m = run.M;
  run.Extinction = ctx->CreateBuffer(
    in, m.Extinction.size() * sizeof(float), m.Extinction.data(), "extinction", this);
  run.ScatteringBuffer = ctx->CreateBuffer(
    in, run.Scattering.size() * sizeof(float), run.Scattering.data(), "scattering", this);
  run.MacroBuffer =
    ctx->CreateBuffer(in, run.Macro.size() * sizeof(float), run.Macro.data(), "macro cells", this);
  run.LightBuffer =
    ctx->CreateBuffer(in, run.Lights.size() * sizeof(cl_float4), run.Lights.data(), "lights", this);
  if (run.NodeCount > 0)
  {
    const auto& nodes = this->Surfaces->GetBVH()->GetNodes();
    const auto& triangles = this->Surfaces->GetBVH()->GetFloatTriangles();
    run.Nodes =
      ctx->CreateBuffer(in, nodes.size() * sizeof(float), nodes.data(), "surface BVH", this);
    run.Triangles = ctx->CreateBuffer(
      in, triangles.size() * sizeof(float), triangles.data(), "surface triangles", this);
  }
  else
  {
    run.Nodes = ctx->CreateBuffer(CL_MEM_READ_ONLY, 16, nullptr, "surface BVH (none)", this);
    run.Triangles =
      ctx->CreateBuffer(CL_MEM_READ_ONLY, 16, nullptr, "surface triangles (none)", this);
  }
  return run.Extinction && run.ScatteringBuffer && run.MacroBuffer && run.LightBuffer &&
    run.Nodes && run.Triangles;
}

//------------------------------------------------------------------------------
// Per-voxel light rays.
bool vtkLightRaySingleScattering::RunLightRays(Internals& run)
{
  vtkOpenCLContext* ctx = run.Context;
  const auto start = Clock::now();
  const size_t voxels = run.M.Voxels;
  const size_t bytes = run.Blocks() * 3 * voxels * sizeof(float);
  vtkOpenCLBuffer radiance = ctx->CreateBuffer(CL_MEM_WRITE_ONLY, bytes, nullptr, "radiance", this);
  vtkOpenCLBuffer direction =
    ctx->CreateBuffer(CL_MEM_WRITE_ONLY, bytes, nullptr, "direction", this);
  vtkOpenCLKernel kernel = ctx->CreateKernel(run.Program, "light_rays_voxels", this);
  const cl_ulong count = voxels;
  const float minDistance = static_cast<float>(run.MinimumDistance);
  if (!radiance || !direction || !kernel ||
    !ctx->Check(run.SetArgs(kernel.Get(), run.ScatteringBuffer.Get(), run.LightBuffer.Get(),
                  run.LightCount, minDistance, radiance.Get(), direction.Get(), count),
      "clSetKernelArg(light_rays_voxels)", this) ||
    !this->RunChunked(run, kernel.Get(), voxels, "light_rays_voxels", 0.0, 0.9))
  {
    return false;
  }
  if (run.Aborted)
  {
    return true;
  }
  if (!run.ReadBlocks(radiance.Get(), direction.Get(), this))
  {
    return false;
  }
  long long marched = 0;
  for (size_t v = 0; v < voxels; ++v)
  {
    marched +=
      (run.Scattering[3 * v] > 0 || run.Scattering[3 * v + 1] > 0 || run.Scattering[3 * v + 2] > 0);
  }
  this->NumberOfEvaluatedPoints = marched;
  this->VoxelSeconds = Seconds(start);
  return true;
}

//------------------------------------------------------------------------------
// Chunks of about 1/32 of the work (at least 4096 work-items): the abort is then seen within a
// chunk's time, and progress moves 32 times.
bool vtkLightRaySingleScattering::RunChunked(
  Internals& run, cl_kernel kernel, size_t count, const char* label, double first, double last)
{
  const size_t local = 64;
  const size_t chunk = std::max<size_t>(4096, (count / 32 + local - 1) / local * local);
  for (size_t offset = 0; offset < count; offset += chunk)
  {
    if (this->GetAbortExecute())
    {
      run.Aborted = true;
      return true;
    }
    const size_t size = std::min(chunk, count - offset);
    const size_t global = (size + local - 1) / local * local;
    if (!run.Context->RunKernel(kernel, 1, &global, &local, label, this, &offset) ||
      !run.Context->Finish(this))
    {
      return false;
    }
    this->UpdateProgress(first + (last - first) * static_cast<double>(offset + size) / count);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkLightRaySingleScattering::EvaluatePoints(Internals& run, const std::vector<float>& points,
  const void* lights, int lightCount, std::vector<std::vector<float>>& phi,
  std::vector<std::vector<float>>& flux)
{
  vtkOpenCLContext* ctx = run.Context;
  const int count = static_cast<int>(points.size() / 4);
  const int blocks = run.Blocks();
  phi.assign(blocks, std::vector<float>(4 * static_cast<size_t>(count), 0.0f));
  flux.assign(blocks, std::vector<float>(4 * static_cast<size_t>(count), 0.0f));
  if (count == 0)
  {
    return true;
  }
  const size_t bytes = points.size() * sizeof(float);
  vtkOpenCLBuffer in = ctx->CreateBuffer(
    CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes, points.data(), "sample points", this);
  vtkOpenCLBuffer lightBuffer = lights == nullptr
    ? vtkOpenCLBuffer()
    : ctx->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
        4 * sizeof(cl_float4) * std::max(lightCount, 1), lights, "view light", this);
  cl_mem lightMem = lights == nullptr ? run.LightBuffer.Get() : lightBuffer.Get();
  vtkOpenCLBuffer phiOut =
    ctx->CreateBuffer(CL_MEM_WRITE_ONLY, blocks * bytes, nullptr, "sample phi", this);
  vtkOpenCLBuffer fluxOut =
    ctx->CreateBuffer(CL_MEM_WRITE_ONLY, blocks * bytes, nullptr, "sample flux", this);
  vtkOpenCLKernel kernel = ctx->CreateKernel(run.Program, "light_rays_points", this);
  const float minDistance = static_cast<float>(run.MinimumDistance);
  if (!in || !phiOut || !fluxOut || !kernel || !lightMem ||
    !ctx->Check(run.SetArgs(kernel.Get(), in.Get(), count, lightMem, lightCount, minDistance,
                  phiOut.Get(), fluxOut.Get()),
      "clSetKernelArg(light_rays_points)", this) ||
    !Run1D(ctx, kernel.Get(), static_cast<size_t>(count), "light_rays_points", this))
  {
    return false;
  }
  for (int b = 0; b < blocks; ++b)
  {
    if (!ctx->ReadBuffer(phiOut.Get(), bytes, phi[b].data(), this, b * bytes) ||
      !ctx->ReadBuffer(fluxOut.Get(), bytes, flux[b].data(), this, b * bytes))
    {
      return false;
    }
  }
  this->NumberOfEvaluatedPoints += count;
  return true;
}

//------------------------------------------------------------------------------
void vtkLightRaySingleScattering::WriteOutput(Internals& run, vtkImageData* output)
{
  output->CopyStructure(run.Input);
  run.Radiance->SetName(vtkRefractaLightingVolume::RadianceName());
  run.Direction->SetName(vtkRefractaLightingVolume::RadianceDirectionName());
  output->GetPointData()->AddArray(run.Radiance);
  output->GetPointData()->SetScalars(run.Radiance);
  output->GetPointData()->AddArray(run.Direction);
  for (int k = 0; k < static_cast<int>(run.LobeRadiance.size()); ++k)
  {
    run.LobeRadiance[k]->SetName(vtkRefractaLightingVolume::RadianceLobeName(k));
    run.LobeDirection[k]->SetName(vtkRefractaLightingVolume::RadianceLobeDirectionName(k));
    output->GetPointData()->AddArray(run.LobeRadiance[k]);
    output->GetPointData()->AddArray(run.LobeDirection[k]);
  }
  vtkFieldData* fd = output->GetFieldData();
  vtkNew<vtkStringArray> method;
  method->SetName("SingleScatteringMethod");
  method->InsertNextValue(GetMethodName(this->Method));
  fd->AddArray(method);
  auto addCount = [&](const char* name, long long value)
  {
    vtkNew<vtkTypeInt64Array> a;
    a->SetName(name);
    a->InsertNextValue(value);
    fd->AddArray(a);
  };
  addCount("NumberOfSamples", this->NumberOfSamples);
  addCount("EvaluatedPoints", this->NumberOfEvaluatedPoints);
  addCount("UncoveredVoxels", this->NumberOfUncoveredVoxels);
  addCount("BoxMeanVoxels", this->NumberOfBoxMeanVoxels);
  addCount("RadianceLobes", run.Lobes);
}

//------------------------------------------------------------------------------
void vtkLightRaySingleScattering::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << GetMethodName(this->Method) << "\n";
  os << indent << "Lights: " << this->Lights->GetNumberOfItems() << "\n";
  os << indent << "Surfaces: " << (this->Surfaces ? "set" : "none") << "\n";
  os << indent << "LightRadius: " << this->LightRadius << "\n";
  os << indent << "DirectionalLightAngularRadius: " << this->DirectionalLightAngularRadius << "\n";
  os << indent << "MaximumRadianceLobes: " << this->MaximumRadianceLobes << "\n";
  os << indent << "LastNumberOfLobes: " << this->LastNumberOfLobes << "\n";
  os << indent << "LightQuadrature: " << this->LightQuadrature << "\n";
  os << indent << "ErrorTolerance: " << this->ErrorTolerance << "\n";
  os << indent << "CoarsestGridResolution: " << this->CoarsestGridResolution << "\n";
  os << indent << "MaximumGridResolution: " << this->MaximumGridResolution << "\n";
  os << indent << "SharpVoxelBoxMeans: " << this->SharpVoxelBoxMeans << "\n";
  os << indent << "LastRunAborted: " << this->LastRunAborted << "\n";
  os << indent << "UseViewPoint: " << this->UseViewPoint << " (" << this->ViewPoint[0] << ", "
     << this->ViewPoint[1] << ", " << this->ViewPoint[2] << ")\n";
  os << indent << "TotalSeconds: " << this->TotalSeconds << "\n";
  os << indent << "NumberOfSamples: " << this->NumberOfSamples << "\n";
  os << indent << "NumberOfEvaluatedPoints: " << this->NumberOfEvaluatedPoints << "\n";
  os << indent << "NumberOfBoxMeanVoxels: " << this->NumberOfBoxMeanVoxels << "\n";
  os << indent << "BoxMeanSeconds: " << this->BoxMeanSeconds << "\n";
  os << indent << "SurfaceSeconds: " << this->SurfaceSeconds << "\n";
  os << indent << "NumberOfSurfacePoints: " << this->NumberOfSurfacePoints << "\n";
}
