// The photon pass's grey media: where every voxel's three channels of sigma_t (or of the albedo)
// are equal, the device holds one value per voxel and the march gathers a third as much
// (REFRACTA_GREY_EXTINCTION, REFRACTA_GREY_ALBEDO). The answer must not depend on which layout ran.
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
