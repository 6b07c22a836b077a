// vtkLightRaySingleScattering::ComputeSurfaceIrradiance: the direct light on the surfaces' texels
// by straight light rays (light_rays_surface_points), the noise-free part of what photons deposit
// there (Documentation/Physics.md, "Direct light on surfaces").
#include "vtkLightRaySingleScattering.h"
#include "vtkLightRaySingleScatteringInternals.h"

#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMediumValidator.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaSurfaceSet.h"

#include "refracta_surfaces.cl" // the triangle info layout, shared with the kernels

#include <cmath>

using namespace vtkPhotonTracerDetail;

//------------------------------------------------------------------------------
void vtkLightRaySingleScattering::MakeTexelSamples(
  Internals& run, std::vector<float>& points, std::vector<float>& normals)
{
  vtkRefractaSurfaceSet* set = this->Surfaces;
  const std::vector<double>& triangles = set->GetBVH()->GetTriangles();
  const std::vector<int>& info = set->GetTriangleInfo();
  // Surface frame -> grid-local: x = A^-1 (p - t), and normals by A^T (the inverse transpose).
  double a[9], inverse[9];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      a[3 * r + c] = run.SurfaceFrame[r][c];
    }
  }
  vtkMatrix3x3::Invert(a, inverse);
  const vtkIdType texels = set->GetNumberOfTexels();
  points.assign(16 * static_cast<size_t>(texels), 0.0f);
  normals.assign(16 * static_cast<size_t>(texels), 0.0f);
  const size_t count = info.size() / REFRACTA_TRIANGLE_INFO_INTS;
  for (size_t k = 0; k < count; ++k)
  {
    const int* ti = &info[REFRACTA_TRIANGLE_INFO_INTS * k];
    if (ti[REFRACTA_TRIANGLE_INFO_KIND] != REFRACTA_SURFACE_LAMBERTIAN)
    {
      continue; // glass: its light is the photons' (and its texel stays 0)
    }
    const double* v = &triangles[9 * k];
    double e1[3], e2[3], ns[3], n[3];
    for (int c = 0; c < 3; ++c)
    {
      e1[c] = v[3 + c] - v[c];
      e2[c] = v[6 + c] - v[c];
    }
    vtkMath::Cross(e1, e2, ns);
    for (int c = 0; c < 3; ++c)
    {
      n[c] = a[c] * ns[0] + a[3 + c] * ns[1] + a[6 + c] * ns[2]; // A^T ns
    }
    if (vtkMath::Normalize(n) == 0.0)
    {
      continue; // a degenerate triangle has no area to light
    }
    const int first = ti[REFRACTA_TRIANGLE_INFO_TEXEL];
    const int subdivision = ti[REFRACTA_TRIANGLE_INFO_SUBDIVISION];
    for (int texel = 0; texel < subdivision * subdivision; ++texel)
    {
      double uv[8];
      vtkRefractaSurfaceSet::GetTexelSamplePoints(texel, subdivision, uv);
      for (int q = 0; q < 4; ++q)
      {
        const size_t at = 4 * (4 * (static_cast<size_t>(first) + texel) + q);
        double p[3];
        for (int c = 0; c < 3; ++c)
        {
          p[c] = v[c] + uv[2 * q] * e1[c] + uv[2 * q + 1] * e2[c] - run.SurfaceFrame[c][3];
        }
        for (int r = 0; r < 3; ++r)
        {
          points[at + r] = static_cast<float>(
            inverse[3 * r] * p[0] + inverse[3 * r + 1] * p[1] + inverse[3 * r + 2] * p[2]);
          normals[at + r] = static_cast<float>(n[r]);
        }
      }
    }
  }
}

//------------------------------------------------------------------------------
bool vtkLightRaySingleScattering::ComputeSurfaceIrradiance(
  vtkImageData* medium, std::vector<float>& irradiance)
{
  const auto start = Clock::now();
  irradiance.clear();
  this->SurfaceSeconds = 0;
  this->NumberOfSurfacePoints = 0;
  vtkNew<vtkMediumValidator> validator;
  if (!medium || !validator->Validate(medium))
  {
    vtkErrorMacro("ComputeSurfaceIrradiance needs a valid Refracta medium: "
      << (medium ? validator->GetErrorMessage() : "none given")
      << "; a vtkImageData with vtkRefractaMedium's arrays is needed.");
    return false;
  }
  if (!this->Surfaces || this->Surfaces->GetNumberOfSurfaces() == 0)
  {
    vtkErrorMacro("ComputeSurfaceIrradiance needs surfaces (SetSurfaces() with a set that holds "
                  "at least one surface).");
    return false;
  }
  Internals run;
  run.Input = medium;
  if (!this->SetUp(run))
  {
    return false;
  }
  const vtkIdType texels = this->Surfaces->GetNumberOfTexels();
  constexpr int sides = vtkRefractaLightingVolume::NUMBER_OF_SURFACE_SIDES;
  irradiance.assign(3 * sides * static_cast<size_t>(texels), 0.0f);
  if (run.LightCount == 0 || texels == 0 || run.NodeCount == 0)
  {
    return true; // no light, or nothing to light
  }
  std::vector<float> points, normals;
  this->MakeTexelSamples(run, points, normals);
  if (!this->Upload(run))
  {
    return false;
  }
  vtkOpenCLContext* ctx = run.Context;
  const size_t count = points.size() / 4;
  const size_t bytes = points.size() * sizeof(float);
  const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  vtkOpenCLBuffer pointBuffer = ctx->CreateBuffer(in, bytes, points.data(), "texel points", this);
  vtkOpenCLBuffer normalBuffer =
    ctx->CreateBuffer(in, bytes, normals.data(), "texel normals", this);
  // One float4 per point and side.
  vtkOpenCLBuffer out =
    ctx->CreateBuffer(CL_MEM_WRITE_ONLY, sides * bytes, nullptr, "texel irradiance", this);
  vtkOpenCLKernel kernel = ctx->CreateKernel(run.Program, "light_rays_surface_points", this);
  const cl_int pointCount = static_cast<cl_int>(count);
  const float minDistance = static_cast<float>(run.MinimumDistance);
  std::vector<float> values(sides * points.size());
  if (!pointBuffer || !normalBuffer || !out || !kernel ||
    !ctx->Check(run.SetArgs(kernel.Get(), pointBuffer.Get(), normalBuffer.Get(), pointCount,
                  run.LightBuffer.Get(), run.LightCount, minDistance, out.Get()),
      "clSetKernelArg(light_rays_surface_points)", this) ||
    !this->RunChunked(run, kernel.Get(), count, "light_rays_surface_points", 0.0, 1.0))
  {
    return false;
  }
  if (run.Aborted)
  {
    irradiance.clear();
    return false; // an abort: no result, no message
  }
  if (!ctx->ReadBuffer(out.Get(), values.size() * sizeof(float), values.data(), this))
  {
    return false;
  }
  // A texel side's irradiance: the mean of its four points (a float4 per point and side).
  constexpr size_t perPoint = 4 * sides;
  for (size_t t = 0; t < static_cast<size_t>(texels); ++t)
  {
    for (int c = 0; c < 3 * sides; ++c)
    {
      const float* v = &values[4 * perPoint * t + 4 * (c / 3) + c % 3];
      irradiance[3 * sides * t + c] =
        0.25f * (v[0] + v[perPoint] + v[2 * perPoint] + v[3 * perPoint]);
    }
  }
  this->NumberOfSurfacePoints = static_cast<long long>(count);
  this->SurfaceSeconds = Seconds(start);
  return true;
}
