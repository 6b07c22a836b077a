// Layouts of the photon pass that must not change its answer. Grey media: where every voxel's
// three channels of sigma_t (or of the albedo) are equal, the device holds one value per voxel and
// the march gathers a third as much (REFRACTA_GREY_EXTINCTION, REFRACTA_GREY_ALBEDO). The coherent
// photon order (vtkPhotonTracer::CoherentPhotonOrder): the same photons, marched in another order.
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"

#include "PhotonTestUtilities.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace photontest;

namespace
{
// A refracting fog ball (sigma_t varies, so every trilinear gather matters) with the albedo
// `albedo` everywhere, lit by a white directional light; the deposits after smoothing.
vtkSmartPointer<vtkImageData> TraceFog(std::array<double, 3> albedo)
{
  auto medium = MakeMedium(20, 18, 16, 0.05,
    [albedo](double x, double y, double z)
    {
      Voxel v;
      const double r2 = (x - 0.5) * (x - 0.5) + (y - 0.45) * (y - 0.45) + (z - 0.4) * (z - 0.4);
      v.N = r2 < 0.06 ? 1.3 : 1.0;
      const double fog = 1.0 + 0.8 * std::sin(6 * x) * std::cos(4 * z);
      v.Extinction = { fog, fog, fog };
      v.Albedo = albedo;
      return v;
    });
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
  auto medium = MakeMedium(20, 18, 16, 0.05,
    [](double x, double y, double z)
    {
      Voxel v;
      const double r2 = (x - 0.5) * (x - 0.5) + (y - 0.45) * (y - 0.45) + (z - 0.4) * (z - 0.4);
      v.N = r2 < 0.06 ? 1.3 : 1.0;
      const double fog = 2.0 + 1.5 * std::sin(6 * x) * std::cos(4 * z);
      v.Extinction = { fog, 0.9 * fog, 0.7 * fog };
      v.Albedo = { 0.9, 0.8, 0.85 };
      return v;
    });
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
    for (vtkFieldData* fd :
      { static_cast<vtkFieldData*>(out[0]->GetPointData()), out[0]->GetFieldData() })
    {
      vtkFieldData* other = fd == out[0]->GetFieldData()
        ? out[1]->GetFieldData()
        : static_cast<vtkFieldData*>(out[1]->GetPointData());
      ASSERT_EQ(fd->GetNumberOfArrays(), other->GetNumberOfArrays());
      for (int i = 0; i < fd->GetNumberOfArrays(); ++i)
      {
        vtkDataArray* a = fd->GetArray(i);
        vtkDataArray* b = a ? other->GetArray(a->GetName()) : nullptr;
        if (!a || !b || std::string(a->GetName()).find("Seconds") != std::string::npos)
        {
          continue; // timings differ
        }
        ASSERT_EQ(a->GetNumberOfValues(), b->GetNumberOfValues()) << a->GetName();
        vtkIdType differing = 0;
        for (vtkIdType v = 0; v < a->GetNumberOfValues(); ++v)
        {
          differing += a->GetVariantValue(v).ToDouble() != b->GetVariantValue(v).ToDouble();
        }
        EXPECT_EQ(differing, 0) << a->GetName() << (chunked ? " (chunked)" : "");
      }
    }
    EXPECT_GT(Field(out[1], "TotalVoxelPieces"), 0);
  }
}
