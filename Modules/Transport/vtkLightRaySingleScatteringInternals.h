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
#include "vtkSmartPointer.h"

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
  // The lobes (MaximumRadianceLobes; light_rays.cl's LR_LOBES): 1 (none stored), or K >= 2 with
  // each lobe's S1 and direction in LobeRadiance[k] and LobeDirection[k].
  int Lobes = 1;
  std::vector<vtkSmartPointer<vtkFloatArray>> LobeRadiance, LobeDirection;
  bool Aborted = false; // AbortExecute was seen: stop, empty output, no error

  // The blocks of light_rays.cl's outputs: all lights, then each lobe (one without lobes).
  int Blocks() const { return this->Lobes > 1 ? this->Lobes + 1 : 1; }
  // Block b's S1 (or its direction) among the output arrays.
  vtkFloatArray* Block(int b, bool direction)
  {
    return b == 0 ? (direction ? this->Direction.Get() : this->Radiance.Get())
                  : (direction ? this->LobeDirection : this->LobeRadiance)[b - 1].Get();
  }
  float* BlockValues(int b, bool direction) { return this->Block(b, direction)->GetPointer(0); }
  // Sizes the output arrays (3 components, every voxel) for Blocks() blocks.
  void AllocateOutput()
  {
    this->LobeRadiance.resize(this->Lobes > 1 ? this->Lobes : 0);
    this->LobeDirection.resize(this->LobeRadiance.size());
    for (auto* arrays : { &this->LobeRadiance, &this->LobeDirection })
    {
      for (auto& a : *arrays)
      {
        a = vtkSmartPointer<vtkFloatArray>::New();
      }
    }
    for (int b = 0; b < this->Blocks(); ++b)
    {
      for (bool direction : { false, true })
      {
        vtkFloatArray* a = this->Block(b, direction);
        a->SetNumberOfComponents(3);
        a->SetNumberOfTuples(static_cast<vtkIdType>(this->M.Voxels));
      }
    }
  }
  // Reads every block of a per-voxel output (`radiance`, `direction`: Blocks() blocks of 3
  // floats per voxel) into the output arrays.
  bool ReadBlocks(cl_mem radiance, cl_mem direction, vtkObject* reporter)
  {
    const size_t bytes = 3 * this->M.Voxels * sizeof(float);
    for (int b = 0; b < this->Blocks(); ++b)
    {
      if (!this->Context->ReadBuffer(
            radiance, bytes, this->BlockValues(b, false), reporter, b * bytes) ||
        !this->Context->ReadBuffer(
          direction, bytes, this->BlockValues(b, true), reporter, b * bytes))
      {
        return false;
      }
    }
    return true;
  }

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
