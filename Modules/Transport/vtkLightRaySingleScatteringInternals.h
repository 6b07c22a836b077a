// Private to vtkLightRaySingleScattering (not installed): the per-run state that
// vtkLightRaySingleScattering.cxx (set-up, light rays), vtkLightRayInterpolation.cxx (dynamic
// sampling, eq. 4) and vtkLightRaySurfaceIrradiance.cxx (texels' direct light) share.
#ifndef vtkLightRaySingleScatteringInternals_h
#define vtkLightRaySingleScatteringInternals_h

#include "vtkFloatArray.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkPhotonTracerInternals.h" // Medium, LoadMedium, Float4, Run1D

#include <vector>

struct vtkLightRaySingleScattering::Internals
{
  vtkImageData* Input = nullptr;
  vtkPhotonTracerDetail::Medium M;
  std::vector<float> Scattering; // sigma_s = albedo x sigma_t, RGB per voxel
  bool AnyScattering = false;
  std::vector<float> Macro; // largest sigma_t per macro cell (light_rays.cl, LR_MACRO)
  int MacroDims[3] = { 1, 1, 1 };
  std::vector<cl_float4> Lights; // LR_LIGHT_FLOAT4S per light
  int LightCount = 0;
  double MinimumDistance = 0; // half the smallest spacing: the delta light's clamp
  vtkOpenCLContext* Context = nullptr;
  cl_program Program = nullptr;
  vtkOpenCLBuffer Extinction, MacroBuffer, ScatteringBuffer, LightBuffer, Nodes, Triangles;
  int NodeCount = 0;
  cl_float4 Frame[3];
  double SurfaceFrame[3][4] = {}; // grid-local -> surface frame, the rows of Frame in double
  float SurfaceEpsilon = 0;
  vtkNew<vtkFloatArray> Radiance, Direction;
  bool Aborted = false; // AbortExecute was seen: stop, empty output, no error

  // Sets the scene arguments (LR_SCENE_ARGS of light_rays.cl) and then `rest`.
  template <typename... Rest>
  cl_int SetArgs(cl_kernel kernel, const Rest&... rest)
  {
    const cl_int4 dims = vtkPhotonTracerDetail::Int4(this->M.Dims);
    const cl_int4 macroDims = vtkPhotonTracerDetail::Int4(this->MacroDims);
    const cl_float4 spacing = vtkPhotonTracerDetail::Float4(this->M.Spacing);
    return vtkOpenCLSetKernelArgs(kernel, this->Extinction.Get(), this->MacroBuffer.Get(), dims,
      macroDims, spacing, this->Nodes.Get(), this->Triangles.Get(), this->NodeCount, this->Frame[0],
      this->Frame[1], this->Frame[2], this->SurfaceEpsilon, rest...);
  }
};

#endif
