// Private to vtkRefractaViewPass (not installed): the state the view pass keeps between renders
// (the medium, lighting volume, environment and surfaces on the device, the empty-space
// occupancy), shared by vtkRefractaViewPass.cxx (rendering) and vtkRefractaViewPassInputs.cxx
// (validation and upload of the inputs).
#ifndef vtkRefractaViewPassInternals_h
#define vtkRefractaViewPassInternals_h

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkRefractaGridFrame.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRefractaViewPass.h"
#include "vtkRefractaViewPassOccupancy.h"
#include "vtkRefractaViewPassSurfaces.h"
#include "vtkSmartPointer.h"

#include <chrono>
#include <cstdint>
#include <vector>

struct vtkRefractaViewPass::Internals
{
  vtkSmartPointer<vtkOpenCLContext> Context;
  vtkSmartPointer<vtkImageData> Environment;

  // Medium on the device. Held (not just remembered) because SetLighting() and Render() read its
  // grid after SetMedium() returns, and a caller may let its own reference go.
  vtkSmartPointer<vtkImageData> Medium;
  vtkMTimeType MediumTime = 0;
  int Dims[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  vtkNew<vtkRefractaGridFrame> Grid;
  bool HasEmission = false;
  // Extinction is the same in every channel: `Extinction` holds (sigma, emission RGB) per voxel
  // and `Emission` is empty (the kernel's REFRACTA_PACKED_MEDIUM).
  bool PackedMedium = false;
  bool Refractive = false;
  // Some grad n sample is non-zero. A medium whose n jumps only across exact interfaces (the
  // voxelizer writes grad n = 0 there) bends rays at the surfaces alone: straight rays between.
  bool Bends = false;
  double UniformIndex = 1.0; // the index where it does not vary (sources then count 1 / n^2)
  vtkOpenCLBuffer Extinction, Emission, Anisotropy, Index, Gradient;

  // Lighting on the device.
  vtkSmartPointer<vtkImageData> Lighting;
  vtkMTimeType LightingTime = 0;
  bool HasSingle = false;
  bool HasMultiple = false;
  bool HasMultipleDirection = false; // then Multiple holds S_ms and after it F / phi_ms
  // S1 in lobes (vtkRefractaLightingVolume::RadianceLobeName): their count K >= 2, Radiance then
  // holding per voxel each lobe's S1 and direction (6 K floats) and RadianceDirection none; 0:
  // Radiance and RadianceDirection, one field each.
  int RadianceLobes = 0;
  vtkOpenCLBuffer Radiance, RadianceDirection, Multiple;
  // The volume caustic: c (1: none), each voxel's brick, the fine S1 and directions.
  int VolumeCausticSub = 1;
  vtkOpenCLBuffer CausticBricks, CausticRadiance, CausticDirection;

  // Environment on the device.
  vtkSmartPointer<vtkImageData> EnvironmentUploaded;
  vtkMTimeType EnvironmentTime = 0;
  int EnvironmentSize[2] = { 0, 0 }; // texels, or a checkerboard's squares
  bool EnvironmentIsChecker = false; // procedural (vtkRefractaEnvironmentMap::MakeChecker)
  vtkOpenCLBuffer EnvironmentBuffer;

  // Empty space: per-voxel flags of the medium and of the lighting volume (SourceFlag,
  // GradientFlag), and the macro-cell occupancy built from them when either changes.
  std::vector<uint8_t> MediumFlags, LightingFlags;
  bool OccupancyDirty = true;
  int OccupancyCellSize = 0;
  vtkRefractaViewPassDetail::MacroCellGrid Cells; // the occupancy on the host, and its active cells
  vtkOpenCLBuffer Occupancy;
  double BuildSeconds = 0.0;

  // Surfaces: the set given, and its arrays and irradiance on the device.
  vtkSmartPointer<vtkRefractaSurfaceSet> SurfaceSet;
  vtkRefractaViewPassDetail::SurfaceBuffers Surfaces;

  vtkOpenCLBuffer Dummy;

  // Host images of the render in progress. Render() swaps them with the caller's vectors at the
  // end, so the next render writes into memory that is already mapped (a fresh 1024^2 HDR image
  // costs 4096 page faults, more than the kernel at that size).
  std::vector<float> ImageScratch, TransmittanceScratch, BackgroundScratch, SurfaceDepthScratch;
  std::vector<cl_uint> StepScratch;

  // Device bytes of each uploaded buffer (medium, lighting, environment, occupancy).
  std::vector<double> UploadedBytes() const
  {
    std::vector<double> sizes;
    for (const vtkOpenCLBuffer* b : { &this->Extinction, &this->Emission, &this->Anisotropy,
           &this->Index, &this->Gradient, &this->Radiance, &this->RadianceDirection,
           &this->Multiple, &this->CausticBricks, &this->CausticRadiance, &this->CausticDirection,
           &this->EnvironmentBuffer, &this->Occupancy, &this->Dummy })
    {
      if (const size_t size = vtkOpenCLBufferBytes(b->Get()))
      {
        sizes.push_back(static_cast<double>(size));
      }
    }
    return sizes;
  }

  // Builds the macro-cell occupancy (BuildMacroCellGrid) when the flags or b changed, and
  // uploads it.
  bool BuildOccupancy(int b, vtkObject* owner)
  {
    if (!this->OccupancyDirty && this->OccupancyCellSize == b && this->Occupancy)
    {
      return true;
    }
    const auto start = std::chrono::steady_clock::now();
    this->Cells = vtkRefractaViewPassDetail::BuildMacroCellGrid(
      this->Dims, b, this->MediumFlags, this->LightingFlags);
    this->Occupancy = this->GetContext()->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
      this->Cells.Cells.size(), this->Cells.Cells.data(), "empty-space occupancy", owner);
    if (!this->Occupancy)
    {
      return false;
    }
    this->OccupancyCellSize = b;
    this->OccupancyDirty = false;
    this->BuildSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return true;
  }

  vtkOpenCLContext* GetContext()
  {
    if (!this->Context)
    {
      this->Context = vtkOpenCLContext::GetDefault();
    }
    return this->Context;
  }
};

#endif
