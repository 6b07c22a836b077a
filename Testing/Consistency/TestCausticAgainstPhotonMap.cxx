// Refracta.CausticAgainstPhotonMap: the render pipeline at the DRAFT preset against a stored,
// converged ground truth on a small caustic scene, a glass ball lens (n = 1.5) focusing a parallel
// beam onto a scattering slab in faint fog, where the unbiased vtkReferenceRenderer does not
// converge (issue #19). The truth, Testing/Baselines/CausticBallLensSlab.vti (48 x 48, float `HDR`
// and its `StandardError`), was computed once by vtkReferencePhotonMapper (stochastic progressive
// photon mapping: TruthPasses = 128 passes of 50 000 photons and 16 view rays per pixel, seed 1;
// 1218 s on the loaded 2-core machine; relative noise 1.65% over the image, 1.17% in the
// caustic); regenerate it by running this test with REFRACTA_WRITE_CAUSTIC_TRUTH=<file.vti>.
//
// Checks:
// 1. the stored truth still matches the code: a 16 x 16 image of the same camera (its pixel
//    centres are those of the 48 x 48 pixels (3 i + 1, 3 j + 1)) by the photon mapper at 4 passes
//    of half the photons
//    must agree with the stored pixels within 4 combined standard errors plus the kernel bias of
//    the short run (CheckBias relative to the image's RMS), on all but 5% of the values, and its
//    relative RMSE (variances taken out) must stay below CheckRmse;
// 2. the pipeline at the draft preset: relative RMSE against the truth (the truth's variance taken
//    out) <= DraftTolerance, over the pixels that see the medium, and over the caustic's region;
// 3. the check can fail: the pipeline's image scaled by 1.25 must fail statistic 2.
// Tolerances come from the measured errors (printed), see Documentation/Benchmarks.md.
#include "RefractaReferenceImages.h"
#include "RefractaScenes.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkEffectPlan.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkSmartPointer.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using refracta::bench::Image;
using refracta::bench::ReadImage;
using refracta::scenes::Scene;

constexpr int TruthSize = 48, CheckSize = 16, Grid = 24;
constexpr int TruthPasses = 128, TruthPhotons = 50000, TruthViews = 16;
constexpr int CheckPasses = 4;
// Set from the measured errors (see the printed numbers and Documentation/Benchmarks.md).
// Measured (pocl CPU device): recheck 0 of 600 values outside 4 SE + 0.05 RMS, relative RMSE 0
// after the variances are taken out; draft pipeline 16.5% over the image, 14.6% in the caustic
// (the truth's own noise: 1.65% and 1.17%). The draft bounds leave a third on top for other
// devices' photon streams and rounding.
constexpr double CheckBias = 0.05, CheckRmse = 0.05;
constexpr double DraftTolerance = 0.22, DraftRegionTolerance = 0.20;

// The scene: a 24^3 grid over the unit cube; glass ball (n = 1.5, radius 0.2, centre
// (0.5, 0.55, 0.5), tanh edge 1.5 voxels wide, clear) whose paraxial focus n R / (2 (n - 1)) = 0.3
// below its centre lies on the top of a scattering slab (y < 0.25, sigma_t 6, albedo 0.9,
// g 0.2) in faint fog (sigma_t 0.2, albedo 0.9); a directional light from +y (0.5 degree disc).
Scene CausticBallLensSlab()
{
  Scene scene;
  scene.Name = "caustic-ball-lens-slab";
  auto m = vtkSmartPointer<vtkImageData>::New();
  m->SetDimensions(Grid, Grid, Grid);
  const double s = 1.0 / Grid;
  m->SetSpacing(s, s, s);
  m->SetOrigin(0.5 * s, 0.5 * s, 0.5 * s);
  const vtkIdType n = static_cast<vtkIdType>(Grid) * Grid * Grid;
  auto make = [&](const char* name, int components)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(components);
    a->SetNumberOfTuples(n);
    m->GetPointData()->AddArray(a);
    return a.Get();
  };
  vtkDoubleArray* index = make(vtkRefractaMedium::RefractiveIndexName(), 1);
  vtkDoubleArray* sigma = make(vtkRefractaMedium::ExtinctionName(), 3);
  vtkDoubleArray* albedo = make(vtkRefractaMedium::AlbedoName(), 3);
  vtkDoubleArray* g = make(vtkRefractaMedium::AnisotropyName(), 1);
  for (int k = 0; k < Grid; ++k)
  {
    for (int j = 0; j < Grid; ++j)
    {
      for (int i = 0; i < Grid; ++i)
      {
        const double x = (i + 0.5) * s, y = (j + 0.5) * s, z = (k + 0.5) * s;
        const double r =
          std::sqrt((x - 0.5) * (x - 0.5) + (y - 0.55) * (y - 0.55) + (z - 0.5) * (z - 0.5));
        const double glass = 0.5 * (1 - std::tanh((r - 0.2) / (1.5 * s)));
        const bool slab = y < 0.25;
        const vtkIdType id = i + Grid * (j + static_cast<vtkIdType>(Grid) * k);
        index->SetValue(id, 1 + 0.5 * glass);
        g->SetValue(id, 0.2);
        for (int c = 0; c < 3; ++c)
        {
          sigma->SetComponent(id, c, (1 - glass) * (slab ? 6.0 : 0.2));
          albedo->SetComponent(id, c, 0.9);
        }
      }
    }
  }
  scene.Medium = m;
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->PositionalOff();
  light->SetPosition(0.5, 2.0, 0.5);
  light->SetFocalPoint(0.5, 0.0, 0.5);
  light->SetIntensity(1.0);
  scene.Lights.push_back(light);
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetPosition(0.5, 1.5, 2.6);
  camera->SetFocalPoint(0.5, 0.35, 0.5);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(35);
  scene.Camera = camera;
  scene.LightAngularRadius = 0.5;
  return scene;
}

Image RenderDraft(const Scene& scene)
{
  vtkNew<vtkRefractaImageRenderer> renderer;
  vtkRefractaRenderPipeline* pipeline = renderer->GetPipeline();
  pipeline->SetQuality(vtkEffectPlan::DRAFT);
  for (const auto& light : scene.Lights)
  {
    renderer->AddLight(light);
  }
  pipeline->GetPhotonTracer()->SetDirectionalLightAngularRadius(scene.LightAngularRadius);
  renderer->SetInputData(scene.Medium);
  renderer->SetCamera(scene.Camera);
  renderer->SetImageSize(TruthSize, TruthSize);
  renderer->Update();
  return ReadImage(renderer->GetOutput());
}

std::string BaselinePath()
{
  const char* dir = std::getenv("REFRACTA_BASELINE_DIR");
  return std::string(dir ? dir : ".") + "/CausticBallLensSlab.vti";
}

// The pixels that see the medium (the truth's error is > 1e-6 of its value) and the caustic's
// region (the brightest 10% of those).
void Masks(const Image& truth, std::vector<bool>& seen, std::vector<bool>& region)
{
  const size_t pixels = truth.Value.size() / 3;
  seen.assign(pixels, false);
  std::vector<double> lum;
  for (size_t p = 0; p < pixels; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      seen[p] = seen[p] || truth.Error[3 * p + c] > 1e-6 * truth.Value[3 * p + c];
    }
    if (seen[p])
    {
      lum.push_back(truth.Value[3 * p]);
    }
  }
  std::sort(lum.begin(), lum.end());
  const double threshold = lum.empty() ? 0 : lum[lum.size() * 9 / 10];
  region.assign(pixels, false);
  for (size_t p = 0; p < pixels; ++p)
  {
    region[p] = seen[p] && truth.Value[3 * p] >= threshold;
  }
}
} // namespace

TEST(CausticAgainstPhotonMap, DraftPipelineMatchesTheStoredTruth)
{
  const Scene scene = CausticBallLensSlab();
  if (const char* write = std::getenv("REFRACTA_WRITE_CAUSTIC_TRUTH"))
  {
    vtkNew<vtkImageData> output;
    const char* passes = std::getenv("REFRACTA_CAUSTIC_TRUTH_PASSES"); // for trial runs
    const Image truth = refracta::bench::RenderPhotonReference(scene, TruthSize,
      passes ? std::atoi(passes) : TruthPasses, TruthPhotons, TruthViews, 1, output);
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetInputData(output);
    writer->SetFileName(write);
    writer->Write();
    std::cout << "truth written to " << write << " in " << truth.Seconds << " s; noise "
              << refracta::bench::NoiseLevel(truth, std::vector<bool>(TruthSize * TruthSize, true))
              << std::endl;
    return;
  }
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(BaselinePath().c_str());
  reader->Update();
  const Image truth = ReadImage(reader->GetOutput());
  ASSERT_EQ(truth.Value.size(), 3u * TruthSize * TruthSize) << "cannot read " << BaselinePath();
  std::vector<bool> seen, region;
  Masks(truth, seen, region);
  std::cout << "truth noise: image " << refracta::bench::NoiseLevel(truth, seen) << ", caustic "
            << refracta::bench::NoiseLevel(truth, region) << std::endl;

  // 1. The stored truth still matches the code.
  const Image check = refracta::bench::RenderPhotonReference(
    scene, CheckSize, CheckPasses, TruthPhotons / 2, TruthViews, 7);
  Image stored, fresh = check;
  std::vector<bool> checkSeen(CheckSize * CheckSize, false);
  double rms = 0;
  int count = 0;
  for (int j = 0; j < CheckSize; ++j)
  {
    for (int i = 0; i < CheckSize; ++i)
    {
      const size_t q = 3 * ((3 * i + 1) + TruthSize * (3 * j + 1));
      checkSeen[i + CheckSize * j] = seen[q / 3];
      for (int c = 0; c < 3; ++c)
      {
        stored.Value.push_back(truth.Value[q + c]);
        stored.Error.push_back(truth.Error[q + c]);
        if (seen[q / 3])
        {
          rms += truth.Value[q + c] * truth.Value[q + c];
          ++count;
        }
      }
    }
  }
  rms = std::sqrt(rms / std::max(count, 1));
  int failed = 0, values = 0;
  double d2 = 0, var = 0, norm = 0;
  for (size_t v = 0; v < stored.Value.size(); ++v)
  {
    if (!checkSeen[v / 3])
    {
      continue;
    }
    const double d = fresh.Value[v] - stored.Value[v];
    const double se =
      std::sqrt(fresh.Error[v] * fresh.Error[v] + stored.Error[v] * stored.Error[v]);
    failed += std::abs(d) > 4 * se + CheckBias * rms ? 1 : 0;
    ++values;
    d2 += d * d;
    var += fresh.Error[v] * fresh.Error[v] + stored.Error[v] * stored.Error[v];
    norm += stored.Value[v] * stored.Value[v];
  }
  const double checkRmse = std::sqrt(std::max(0.0, d2 - var) / norm);
  std::cout << "recheck (" << CheckSize << "^2 pixels, " << CheckPasses << " passes, "
            << check.Seconds << " s): relative RMSE " << checkRmse << ", " << failed << " of "
            << values << " values outside 4 SE + " << CheckBias << " RMS" << std::endl;
  EXPECT_LE(failed, values / 20);
  EXPECT_LE(checkRmse, CheckRmse);

  // 2. The pipeline at the draft preset.
  const Image draft = RenderDraft(scene);
  ASSERT_EQ(draft.Value.size(), truth.Value.size());
  const double image = refracta::bench::RelativeError(draft, truth, seen);
  const double caustic = refracta::bench::RelativeError(draft, truth, region);
  std::cout << "draft pipeline against the truth: relative RMSE " << image << " (caustic "
            << caustic << ")" << std::endl;
  EXPECT_LE(image, DraftTolerance);
  EXPECT_LE(caustic, DraftRegionTolerance);

  // 3. The statistic can fail.
  Image brighter = draft;
  for (double& v : brighter.Value)
  {
    v *= 1.25;
  }
  EXPECT_GT(refracta::bench::RelativeError(brighter, truth, seen), DraftTolerance);
}
