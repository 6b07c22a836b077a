// Refracta.ParticlesAgainstReference: a particle medium lit by its illumination network
// (vtkIlluminationNetwork, papers/002) and rendered the shipping way (vtkParticleMediumDeposit onto
// a grid, vtkRefractaImageRenderer with the deposit's lighting volume) against the unbiased
// reference renderer on the same particles (their exact deposit on a finer grid, sphere occupancy
// sampled 4^3 per voxel: the reference renders grids). The cloud is the paper's (RefractaScenes.h,
// ParticleCloud: 256 particles of volume fraction 1, 20 collisions across, albedo 0.9) under a
// directional light.
//
// The bound is what BenchmarkParticleRendering measured (Documentation/Benchmarks.md, "Particle
// media: deposit or splatting"): the network's own model error is 13% relative RMSE on 1024
// particles (8% too dark; D from 32 to 256 and the rendering method change it by < 1 point) and
// 18.8% on this smaller cloud of larger, more opaque particles (2.7% reference noise); the bound
// allows a margin for the variance subtraction. The same image without the network's multiple
// scattering (57%) and 20% darker (about 33%) must fail it, so that the test can fail.
#include "RefractaReferenceImages.h"
#include "RefractaScenes.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkIlluminationNetwork.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkParticleMediumDeposit.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaRenderPipeline.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

namespace
{
constexpr int Particles = 256;
constexpr int Pixels = 32;
constexpr int Grid = 48;
constexpr int ReferenceGrid = 64;
constexpr int ReferenceSpp = 2048;
// Relative RMSE bound (see above).
constexpr double Bound = 0.22;

// The deposit's image through the shipping front end (vtkRefractaImageRenderer with the deposit's
// lighting volume on its port 1: the light passes are skipped), RGB per pixel, row 0 at the
// bottom, and the plan's refraction reason; `multiple` false drops the network's multiple
// scattering from the lighting volume.
std::vector<double> Render(vtkImageData* medium, vtkImageData* lighting, vtkCamera* camera,
  bool multiple, std::string* refraction = nullptr)
{
  vtkNew<vtkImageData> light;
  light->ShallowCopy(lighting);
  if (!multiple)
  {
    light->GetPointData()->RemoveArray(vtkRefractaLightingVolume::MultipleScatteringName());
  }
  vtkNew<vtkRefractaImageRenderer> renderer;
  renderer->SetInputData(medium);
  renderer->SetLightingData(light);
  renderer->SetCamera(camera);
  renderer->SetImageSize(Pixels, Pixels);
  renderer->Update();
  if (refraction)
  {
    *refraction = renderer->GetPipeline()->GetEffectPlan()->GetReason(vtkEffectPlan::REFRACTION);
  }
  std::vector<double> rgb;
  if (vtkDataArray* hdr = renderer->GetOutput()->GetPointData()->GetArray("HDR"))
  {
    for (vtkIdType p = 0; p < hdr->GetNumberOfTuples(); ++p)
    {
      rgb.insert(
        rgb.end(), { hdr->GetComponent(p, 0), hdr->GetComponent(p, 1), hdr->GetComponent(p, 2) });
    }
  }
  return rgb;
}
}

TEST(ParticlesAgainstReference, NetworkAndDepositWithinTheMeasuredError)
{
  const double* travel = refracta::scenes::ParticleLightTravel;
  vtkNew<vtkIlluminationNetwork> network;
  network->SetInputData(refracta::scenes::ParticleCloud(Particles));
  network->SetLightType(vtkIlluminationNetwork::DIRECTIONAL_LIGHT);
  network->SetLightDirection(travel[0], travel[1], travel[2]);
  network->SetLightIntensity(1, 1, 1);
  network->SetNumberOfDirections(32);
  network->SetNumberOfRotations(4);
  network->SetTolerance(1e-4);
  vtkNew<vtkParticleMediumDeposit> deposit;
  deposit->SetInputConnection(network->GetOutputPort());
  deposit->SetSampleDimensions(Grid, Grid, Grid);
  deposit->Update();

  refracta::scenes::Scene scene = refracta::scenes::ParticleCloudView();
  vtkNew<vtkParticleMediumDeposit> fine;
  fine->SetInputData(refracta::scenes::ParticleCloud(Particles));
  fine->SetSampleDimensions(ReferenceGrid, ReferenceGrid, ReferenceGrid);
  fine->SetSamplesPerAxis(4);
  fine->Update();
  scene.Medium = fine->GetMediumOutput();
  const refracta::bench::Image reference =
    refracta::bench::RenderReference(scene, Pixels, ReferenceSpp, 1);
  std::vector<bool> seen(reference.Value.size() / 3, false);
  for (size_t v = 0; v < reference.Value.size(); ++v)
  {
    seen[v / 3] = seen[v / 3] || reference.Error[v] > 1e-6 * reference.Value[v];
  }

  refracta::bench::Image image;
  std::string refraction;
  image.Value = Render(
    deposit->GetMediumOutput(), deposit->GetLightingOutput(), scene.Camera, true, &refraction);
  EXPECT_NE(refraction.find("refraction does not apply to particles"), std::string::npos)
    << refraction;
  ASSERT_EQ(image.Value.size(), reference.Value.size());
  image.Error.assign(image.Value.size(), 0.0);
  refracta::bench::Image single = image, darker = image;
  single.Value =
    Render(deposit->GetMediumOutput(), deposit->GetLightingOutput(), scene.Camera, false);
  ASSERT_EQ(single.Value.size(), reference.Value.size());
  for (double& v : darker.Value)
  {
    v *= 0.8;
  }
  const double error = refracta::bench::RelativeError(image, reference, seen);
  const double errorSingle = refracta::bench::RelativeError(single, reference, seen);
  const double errorDarker = refracta::bench::RelativeError(darker, reference, seen);
  std::printf("network + deposit against the reference: %.4f (reference noise %.4f, %.1f s); "
              "without multiple scattering %.4f, 20%% darker %.4f; network %d iterations\n",
    error, refracta::bench::NoiseLevel(reference, seen), reference.Seconds, errorSingle,
    errorDarker, network->GetIterations());
  EXPECT_LT(error, Bound);
  EXPECT_GT(errorSingle, Bound);
  EXPECT_GT(errorDarker, Bound);
}
