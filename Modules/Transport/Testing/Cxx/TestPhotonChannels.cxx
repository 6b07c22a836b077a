// Layouts of the photon pass that must not change its answer. Grey media: where every voxel's
// three channels of sigma_t (or of the albedo) are equal, the device holds one value per voxel and
// the march gathers a third as much (REFRACTA_GREY_EXTINCTION, REFRACTA_GREY_ALBEDO). The coherent
// photon order (vtkPhotonTracer::CoherentPhotonOrder): the same photons, marched in another order.
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"

#include "PhotonTestUtilities.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace photontest;

namespace
{
// A refracting fog ball (sigma_t varies, so every trilinear gather matters) with the albedo
// `albedo` everywhere, lit by a white directional light; the deposits after smoothing.
vtkSmartPointer<vtkImageData> TraceFog(std::array<double, 3> albedo)
{
  auto medium = RefractingFog(20, 18, 16, 1.0, 0.8, { 1, 1, 1 }, albedo);
  vtkNew<vtkPhotonTracer> tracer;
  tracer->AddLight(Directional({ -1, 0.3, 0.2 }, { 0.5, 0.45, 0.4 }, 1.0));
  tracer->SetNumberOfPhotons(1 << 14);
  tracer->SetSeed(11);
  tracer->SetInputData(medium);
  tracer->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(tracer->GetOutput());
  return out;
}
}

// A grey medium (one value per voxel on the device) against the same medium with its albedo's
// blue halved (three values per voxel): the albedo only splits each piece's loss into scattered
// and absorbed, so the photons' paths and power are the same in both runs, red and green deposit
// the same, and blue deposits exactly half (halving is exact in binary, and the trilinear
// albedo and the smoothing are linear). Tolerance 1e-5 relative to the brightest voxel: the two
// layouts' arithmetic may differ in contraction (fma), nothing more; reading the grey layout with
// the RGB stride (or the reverse) would miss by O(1).
TEST(PhotonChannels, GreyLayoutMatchesTheRgbLayout)
{
  auto grey = TraceFog({ 0.8, 0.8, 0.8 });
  auto coloured = TraceFog({ 0.8, 0.8, 0.4 });
  vtkDataArray* a = grey->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName());
  vtkDataArray* b = coloured->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName());
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples());
  double peak = 0.0;
  for (vtkIdType v = 0; v < a->GetNumberOfTuples(); ++v)
  {
    peak = std::max(peak, a->GetComponent(v, 0));
  }
  ASSERT_GT(peak, 0.0);
  double worst[3] = { 0, 0, 0 };
  for (vtkIdType v = 0; v < a->GetNumberOfTuples(); ++v)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double expected = (c == 2 ? 0.5 : 1.0) * a->GetComponent(v, c);
      worst[c] = std::max(worst[c], std::abs(b->GetComponent(v, c) - expected) / peak);
    }
  }
  std::printf("peak %g; largest difference / peak: red %.2e, green %.2e, blue (x 1/2) %.2e\n", peak,
    worst[0], worst[1], worst[2]);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_LT(worst[c], 1e-5) << "channel " << c;
  }
}

// The coherent order only moves photons between slots: each keeps its lattice point and its
// random stream, and deposits and books are integer sums, so every array (Radiance, its direction,
// the split's S_ms) and every book and counter must be the same to the bit. A light whose
// lattice is sorted (a directional one), a spot with an extent (points map to a cone and a disc),
// the first-collision split (random scattering decisions), both march kernels (one launch per
// photon and the chunked march). A slot given a wrong point or stream fails it at O(1).
TEST(PhotonChannels, CoherentOrderGivesTheSameBits)
{
  auto medium = RefractingFog(20, 18, 16, 2.0, 1.5, { 1, 0.9, 0.7 }, { 0.9, 0.8, 0.85 });
  for (int chunked : { 0, 1 })
  {
    vtkSmartPointer<vtkImageData> out[2];
    for (int coherent : { 0, 1 })
    {
      vtkNew<vtkPhotonTracer> tracer;
      tracer->AddLight(Directional({ -1, 0.3, 0.2 }, { 0.5, 0.45, 0.4 }, 1.0));
      auto spot = Positional({ 0.5, 1.6, 0.4 }, { 0.5, 0.4, 0.4 }, 25.0, 2.0, 3.0);
      tracer->AddLight(spot);
      tracer->SetLightRadius(0.1);
      tracer->SetNumberOfPhotons(3 << 12);
      tracer->SetScatteringOrders(2);
      tracer->SetStepsPerChunk(chunked ? 16 : 0);
      tracer->SetSeed(3);
      tracer->SetCoherentPhotonOrder(coherent != 0);
      tracer->SetInputData(medium);
      tracer->Update();
      out[coherent] = vtkSmartPointer<vtkImageData>::New();
      out[coherent]->DeepCopy(tracer->GetOutput());
    }
    const std::string where = chunked ? " (chunked march)" : " (one launch per photon)";
    ExpectSameBits(out[0]->GetPointData(), out[1]->GetPointData(), where);
    ExpectSameBits(out[0]->GetFieldData(), out[1]->GetFieldData(), where);
    EXPECT_GT(Field(out[1], "TotalVoxelPieces"), 0);
  }
}

// The step lengths are in voxels, scaled by the grid's spacing in the kernel, and the caustic
// atlas's offset is a kernel argument: one compiled program serves every grid and surface set
// with the same features. The same medium on a grid of twice the spacing, with sigma_t halved
// (the same optical depth per voxel) and the index field unchanged per voxel (its gradient
// halved: the ray equation draws the same curves in voxel units), is the same scene in voxel
// units: the photons take the same steps and walk the same voxel pieces, up to float rounding,
// and no program is built or loaded for it. Step lengths left in world units would take twice
// the steps on the coarse grid (or cost a build per spacing).
TEST(PhotonChannels, OneProgramServesEveryVoxelSize)
{
  vtkNew<vtkOpenCLContext> context;
  double counts[2][2] = { { 0, 0 }, { 0, 0 } };
  int programs[2] = { 0, 0 };
  for (int scaled : { 0, 1 })
  {
    auto medium = RefractingFog(20, 18, 16, 1.0, 0.8, { 1, 1, 1 }, { 0.8, 0.8, 0.8 });
    if (scaled)
    {
      medium->SetSpacing(0.1, 0.1, 0.1);
      auto* extinction =
        vtkFloatArray::SafeDownCast(medium->GetPointData()->GetArray("Extinction"));
      ASSERT_NE(extinction, nullptr);
      float* values = extinction->GetPointer(0);
      for (vtkIdType v = 0; v < extinction->GetNumberOfValues(); ++v)
      {
        values[v] *= 0.5f;
      }
      extinction->Modified();
    }
    const double k = scaled ? 2.0 : 1.0;
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetContext(context);
    tracer->AddLight(Directional({ -k, 0.3 * k, 0.2 * k }, { 0.5 * k, 0.45 * k, 0.4 * k }, 1.0));
    tracer->SetNumberOfPhotons(1 << 13);
    tracer->SetSeed(5);
    tracer->SetInputData(medium);
    tracer->Update();
    counts[scaled][0] = Field(tracer->GetOutput(), "TotalSteps");
    counts[scaled][1] = Field(tracer->GetOutput(), "TotalVoxelPieces");
    programs[scaled] = context->GetNumberOfSourceBuilds() + context->GetNumberOfBinaryLoads();
    std::printf("spacing %.2f: %.0f steps, %.0f voxel pieces, %d programs built or loaded\n",
      0.05 * k, counts[scaled][0], counts[scaled][1], programs[scaled]);
  }
  ASSERT_GT(counts[0][0], 1 << 13);
  for (int c = 0; c < 2; ++c)
  {
    EXPECT_NEAR(counts[1][c] / counts[0][c], 1.0, 0.002) << (c ? "voxel pieces" : "steps");
  }
  EXPECT_GT(programs[0], 0);
  EXPECT_EQ(programs[1], programs[0]) << "the coarse grid needed programs of its own";
}
