// Refracta.PipelineAgainstReference: the render pipeline (vtkRefractaRenderPipeline through its
// vtkImageAlgorithm front end vtkRefractaImageRenderer) at the DRAFT preset against the unbiased
// reference renderer (vtkReferenceRenderer: CPU, double precision, Monte Carlo; its output has the
// image `HDR` and the per-pixel standard error of the mean `StandardError`) on three small scenes
// where the reference converges in seconds:
// 1. the heterogeneous cloud of the accuracy benchmark (scattering, single and multiple), 32^3;
// 2. an emission-absorption medium (the cloud's density, no scattering, no lights), 32^3: the
//    pipeline has no Monte Carlo and no model error there, so the tolerance is tight;
// 3. the dense high-albedo cube of the accuracy benchmark (optical depth 24, albedo 0.99/0.97),
//    48^3 (see "Resolutions" below for why not coarser); about 50 s on 2 cores, so it runs as
//    Refracta.PipelineAgainstReferenceDenseCube under the label `long`.
// For each scene two statistics over the values (pixel x channel) that see the medium (the
// reference's standard error is > 1e-6 of its value; background pixels are exact in both):
// (a) per value: |pipeline - reference| <= K_SIGMA * SE_ref + b * max(|reference|, RMS_ref),
//     with b = the error BenchmarkAccuracyTime measured for that scene at the draft preset (the
//     larger of its image and region-of-interest figures, the region being where it is worst)
//     plus the draft preset's claimed error; RMS_ref is the root mean square of the reference over
//     the same values: the benchmark's errors are RMS errors relative to the image's RMS, so a
//     pixel far dimmer than the image (the cube's silhouette, where a ray grazes the one-voxel
//     boundary layer) is held to that absolute scale, not to its own tiny value. At most
//     MAX_FAILED_FRACTION of the values may fail;
// (b) relative RMSE with the reference's variance taken out (exactly BenchmarkAccuracyTime's
//     RelativeError: sqrt(max(0, sum (p - r)^2 - sum SE^2) / sum r^2)) <= the benchmark's image
//     error for that scene + the draft preset's claimed error + a margin for the noise of the
//     variance subtraction.
// Each statistic is also applied to a perturbed pipeline image (scaled by 1.1 or 1.02, or rendered
// without multiple scattering), which must FAIL the same bounds: the test can fail.
// Finally the draft and production presets on the cloud must agree within the draft preset's
// claimed "error vs finest" (the presets' claims are asserted, not only printed).
//
// Sources of the numbers (Documentation/Benchmarks.md, "Accuracy and time", run recorded in
// Testing/Benchmarks/Results/accuracy: presets.csv and benchmark_output.txt; 64^3 media, 64 x 64
// pixels, references converged to 0.29% (cloud) and 1.3% (cube) noise):
// - draft preset error vs reference: cloud 0.94% image, 6.3% region (presets.csv 0.009358,
//   0.06343); dense cube 9.9% image, 9.8% region (0.09895, 0.09833);
// - draft preset's claimed error vs the finest setting, max over the four scenes: 2.5% (the
//   presets table "error vs finest setting (max over scenes)"; presets.csv max 0.02546, GRIN);
//   production's: 0.27% (0.002676, cube).
// Resolutions: the benchmark's numbers are at 64^3; this test uses smaller grids to stay within
// ~1 minute. On the cloud that changes nothing measurable (1.2% here against 0.94%). The cube's
// error against the reference grows as its grid gets coarser (the lattice's diffusion-like
// transport of multiple scattering resolves the cube's boundary layer worse): measured with this
// test's statistic 17% at 24^3, 13.5% at 32^3 and 8.6% at 48^3 (draft, 24 x 24 pixels), so the
// cube is rendered at 48^3, the coarsest grid where the benchmark's 64^3 figure holds.
//
// Determinism: the reference's random streams are seeded per pixel (Seed 1; bit-identical for any
// number of threads) and the photon tracer's Seed is its default 1 with 64-bit fixed-point
// deposits, so on one OpenCL device every run of this test gives the same numbers; on another
// device the pipeline's photon streams and float rounding differ (the bounds leave room for that).
#include "RefractaReferenceImages.h"
#include "RefractaScenes.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkReferenceRenderer.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using refracta::bench::Image;
using refracta::bench::ReadImage;
using refracta::bench::RenderReference;
using refracta::scenes::Scene;

double Since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Image RenderPipeline(const Scene& scene, int size, int quality, bool multipleScattering,
  std::string* summary = nullptr)
{
  const auto start = std::chrono::steady_clock::now();
  vtkNew<vtkRefractaImageRenderer> renderer;
  vtkRefractaRenderPipeline* pipeline = renderer->GetPipeline();
  pipeline->SetQuality(quality);
  pipeline->SetMultipleScattering(multipleScattering);
  for (const auto& light : scene.Lights)
  {
    renderer->AddLight(light);
  }
  pipeline->GetPhotonTracer()->SetLightRadius(scene.LightRadius);
  pipeline->GetPhotonTracer()->SetDirectionalLightAngularRadius(scene.LightAngularRadius);
  renderer->SetInputData(scene.Medium);
  renderer->SetCamera(scene.Camera);
  renderer->SetImageSize(size, size);
  renderer->SetBackgroundColor(scene.Background[0], scene.Background[1], scene.Background[2]);
  renderer->Update();
  Image image = ReadImage(renderer->GetOutput());
  image.Seconds = Since(start);
  if (summary)
  {
    *summary = pipeline->GetEffectPlan()->GetSummary();
  }
  return image;
}

std::vector<bool> SeenPixels(const Image& reference)
{
  std::vector<bool> seen(reference.Value.size() / 3, false);
  for (size_t v = 0; v < reference.Value.size(); ++v)
  {
    seen[v / 3] = seen[v / 3] || reference.Error[v] > 1e-6 * reference.Value[v];
  }
  return seen;
}

struct Statistics
{
  double RelativeError = 0.0;
  double Noise = 0.0;
  double FailedFraction = 0.0;
  int Values = 0;
  double Bias = 0.0; // sum(p - r) / sum(r)
};

// Statistics (a) and (b) of `image` against `reference` over the `seen` pixels; the per-value
// tolerance is k SE + b max(|r|, RMS of r).
Statistics Measure(
  const Image& image, const Image& reference, const std::vector<bool>& seen, double k, double b)
{
  Statistics s;
  double diff = 0.0, sum = 0.0;
  int failed = 0;
  double rms = 0.0;
  int count = 0;
  for (size_t v = 0; v < reference.Value.size(); ++v)
  {
    if (seen[v / 3])
    {
      rms += reference.Value[v] * reference.Value[v];
      ++count;
    }
  }
  rms = count ? std::sqrt(rms / count) : 0.0;
  for (size_t v = 0; v < reference.Value.size(); ++v)
  {
    if (!seen[v / 3])
    {
      continue;
    }
    const double r = reference.Value[v], d = image.Value[v] - r;
    diff += d;
    sum += r;
    ++s.Values;
    failed += std::abs(d) > k * reference.Error[v] + b * std::max(std::abs(r), rms) ? 1 : 0;
  }
  s.RelativeError = refracta::bench::RelativeError(image, reference, seen);
  s.Noise = refracta::bench::NoiseLevel(reference, seen);
  s.FailedFraction = s.Values ? double(failed) / s.Values : 1.0;
  s.Bias = sum > 0 ? diff / sum : 0.0;
  return s;
}

Image Scaled(Image image, double factor)
{
  for (double& v : image.Value)
  {
    v *= factor;
  }
  return image;
}

void Report(const std::string& what, const Statistics& s)
{
  std::cout << "  " << what << ": relative RMSE " << 100 * s.RelativeError << "% (reference noise "
            << 100 * s.Noise << "%), mean bias " << 100 * s.Bias << "%, failed "
            << 100 * s.FailedFraction << "% of " << s.Values << " values" << std::endl;
}

// Emission-absorption medium: the cloud's density with half its extinction (sigma_t up to 6, grey),
// albedo 0 and an emission eps = sigma_t x (a colour going from blue at the bottom to warm at the
// top), in front of a dark blue background and without lights: what reaches the camera is
// integral T eps ds + T bg, which the reference estimates by delta tracking.
Scene EmissionAbsorption(int n)
{
  Scene scene = refracta::scenes::HeterogeneousCloud(n);
  scene.Name = "emission-absorption";
  scene.Lights.clear();
  vtkImageData* m = scene.Medium;
  vtkDataArray* ext = m->GetPointData()->GetArray("Extinction");
  vtkDataArray* alb = m->GetPointData()->GetArray("Albedo");
  vtkDataArray* em = m->GetPointData()->GetArray("Emission");
  for (vtkIdType p = 0; p < m->GetNumberOfPoints(); ++p)
  {
    double x[3];
    m->GetPoint(p, x);
    const double sigma = ext->GetComponent(p, 0) / 2.0;
    const double warm = std::max(0.0, std::min(1.0, 1.5 * x[1]));
    for (int c = 0; c < 3; ++c)
    {
      ext->SetComponent(p, c, sigma);
      alb->SetComponent(p, c, 0.0);
    }
    em->SetComponent(p, 0, sigma * (0.2 + 0.8 * warm));
    em->SetComponent(p, 1, sigma * 0.5);
    em->SetComponent(p, 2, sigma * (1.0 - 0.8 * warm));
  }
  scene.Background[0] = 0.05;
  scene.Background[1] = 0.1;
  scene.Background[2] = 0.2;
  return scene;
}

// Per-value check (a): how many values lie outside K_SIGMA standard errors plus the bias budget.
// K_SIGMA = 4: for a Gaussian error of the stated standard error 4 sigma is exceeded with
// probability 6e-5, i.e. ~0.1 of the 1000-3000 values of an image; the standard error is itself
// estimated from the samples (and the estimator is heavy-tailed in scattering media), which the
// allowed failed fraction absorbs.
constexpr double K_SIGMA = 4.0;
constexpr double MAX_FAILED_FRACTION = 0.02;

// The draft preset's claimed error vs the finest setting, max over scenes (see the header).
constexpr double DRAFT_CLAIMED_ERROR = 0.025;
// The production preset's claimed error vs the finest setting.
constexpr double PRODUCTION_CLAIMED_ERROR = 0.0027;

// The bounds of one scene from the benchmark's draft errors for it (see the header): per-value bias
// b = max(image, region) + the draft claim; RMSE bound = image + the draft claim + `margin` (for
// the noise of the variance subtraction).
struct Bounds
{
  double PerValueBias;
  double RmseBound;
};

Bounds FromBenchmark(double imageError, double regionError, double margin)
{
  return { std::max(imageError, regionError) + DRAFT_CLAIMED_ERROR,
    imageError + DRAFT_CLAIMED_ERROR + margin };
}

// Pipeline and reference of one scene, the two statistics and their bounds.
struct Comparison
{
  Image Reference, Draft;
  std::vector<bool> Seen;
  double PerValueBias = 0.0; // b
  double RmseBound = 0.0;
  Statistics Measured;
};

Comparison Compare(const Scene& scene, int size, int spp, const Bounds& bounds)
{
  Comparison c;
  std::string summary;
  c.Reference = RenderReference(scene, size, spp, 1);
  c.Draft = RenderPipeline(scene, size, vtkEffectPlan::DRAFT, true, &summary);
  c.Seen = SeenPixels(c.Reference);
  c.PerValueBias = bounds.PerValueBias;
  c.RmseBound = bounds.RmseBound;
  std::cout << scene.Name << ": reference " << spp << " samples per pixel, " << size << " x "
            << size << " pixels, " << c.Reference.Seconds << " s; pipeline at DRAFT "
            << c.Draft.Seconds << " s; plan: " << summary << std::endl;
  if (c.Draft.Value.size() == c.Reference.Value.size())
  {
    c.Measured = Measure(c.Draft, c.Reference, c.Seen, K_SIGMA, c.PerValueBias);
    Report("draft", c.Measured);
    std::cout << "  bounds: relative RMSE <= " << 100 * c.RmseBound << "%, per value " << K_SIGMA
              << " SE + " << 100 * c.PerValueBias << "% with at most " << 100 * MAX_FAILED_FRACTION
              << "% failing" << std::endl;
  }
  return c;
}

// The two statistics (a) and (b) of `s` pass the bounds of `c`.
bool Passes(
  const Statistics& s, const Comparison& c, bool* perValue = nullptr, bool* rmse = nullptr)
{
  const bool a = s.Values > 0 && s.FailedFraction <= MAX_FAILED_FRACTION;
  const bool b = s.Values > 0 && s.RelativeError <= c.RmseBound;
  if (perValue)
  {
    *perValue = a;
  }
  if (rmse)
  {
    *rmse = b;
  }
  return a && b;
}

void ExpectConsistent(const Comparison& c)
{
  ASSERT_EQ(c.Draft.Value.size(), c.Reference.Value.size()) << "pipeline image has the wrong size";
  ASSERT_GT(c.Measured.Values, 100) << "too few pixels see the medium";
  EXPECT_LE(c.Measured.RelativeError, c.RmseBound) << "relative RMSE against the reference";
  EXPECT_LE(c.Measured.FailedFraction, MAX_FAILED_FRACTION)
    << "fraction of values outside " << K_SIGMA << " SE + " << c.PerValueBias << " x |reference|";
}

// A perturbed image must fail both statistics.
void ExpectRejected(const std::string& what, const Image& perturbed, const Comparison& c)
{
  ASSERT_EQ(perturbed.Value.size(), c.Reference.Value.size());
  const Statistics s = Measure(perturbed, c.Reference, c.Seen, K_SIGMA, c.PerValueBias);
  Report("perturbed: " + what, s);
  bool perValue = true, rmse = true;
  Passes(s, c, &perValue, &rmse);
  EXPECT_FALSE(perValue) << what << " passes the per-value check: the test cannot see it";
  EXPECT_FALSE(rmse) << what << " passes the RMSE bound: the test cannot see it";
}
}

// (1) Heterogeneous cloud, 32^3, 32 x 32 pixels, 1024 samples per pixel (reference noise ~1.3%).
// Measured here: relative RMSE 1.2%, no value outside the per-value bound.
TEST(PipelineAgainstReference, HeterogeneousCloud)
{
  const Scene scene = refracta::scenes::HeterogeneousCloud(32);
  // Margin 1%: the variance subtraction's own noise is ~noise^2 sqrt(2 / values) ~ (0.25%)^2 here,
  // and the benchmark's figure was measured at 64^3 (see the header).
  const Comparison c = Compare(scene, 32, 1024, FromBenchmark(0.0094, 0.0634, 0.01));
  ExpectConsistent(c);
  // Every pixel 10% too bright, and the image without multiple scattering (~6% darker on average,
  // up to ~15% in the core), must both be rejected.
  ExpectRejected("pipeline x 1.1", Scaled(c.Draft, 1.1), c);
  ExpectRejected("no multiple scattering",
    RenderPipeline(scene, 32, vtkEffectPlan::DRAFT, /*multipleScattering=*/false), c);

  // The presets' claim: draft is within 2.5% of the finest setting on every scene; production is
  // within 0.27% of it, so draft and production differ by at most 2.5% + 0.27% (+ 0.5% for the
  // photon noise of a deterministic but different photon count at another grid). The pipeline is
  // deterministic, so no reference noise enters. Measured here: 0.012% (the cloud is the scene
  // where the presets differ least; at 64^3 the benchmark measured 0.028% vs the finest).
  const Image production = RenderPipeline(scene, 32, vtkEffectPlan::PRODUCTION, true);
  ASSERT_EQ(production.Value.size(), c.Draft.Value.size());
  const Statistics presets = Measure(c.Draft, production, c.Seen, 0.0, 0.0);
  std::cout << "  production preset: " << production.Seconds << " s" << std::endl;
  std::cout << "  draft vs production: relative RMSE " << 100 * presets.RelativeError << "% (bound "
            << 100 * (DRAFT_CLAIMED_ERROR + PRODUCTION_CLAIMED_ERROR + 0.005) << "%)" << std::endl;
  EXPECT_LE(presets.RelativeError, DRAFT_CLAIMED_ERROR + PRODUCTION_CLAIMED_ERROR + 0.005);
}

// (2) Emission-absorption, 32^3, 32 x 32 pixels, 1024 samples per pixel (reference noise ~2.1%).
// No benchmark number exists for it: the pipeline has no model error and no Monte Carlo here,
// only the view pass's quadrature at the draft view step (0.5 voxel) of the same trilinear fields
// the reference samples, and float arithmetic. The benchmark measured the view step knob's own
// error at 0.5 voxel as <= 0.12% on the non-refractive scenes (Benchmarks.md, knob table: cloud
// 0.006%, cube 0.12%), so the bias budget is 1% per value, and the RMSE bound 1% is set by the
// reference's noise: the variance subtraction leaves ~noise^2 sqrt(2 / values) ~ (0.4%)^2 and
// its 3-sigma excursion ~0.7%. Measured here: 0.59%, no value failing.
TEST(PipelineAgainstReference, EmissionAbsorption)
{
  const Scene scene = EmissionAbsorption(32);
  // Tight bounds instead of the benchmark's scattering-scene errors and the draft claim.
  const Comparison c = Compare(scene, 32, 1024, { 0.01, 0.01 });
  ExpectConsistent(c);
  // A 10% and even a 2% error in brightness must be rejected.
  ExpectRejected("pipeline x 1.1", Scaled(c.Draft, 1.1), c);
  ExpectRejected("pipeline x 1.02", Scaled(c.Draft, 1.02), c);
}

// (3) Dense high-albedo cube, 48^3, 24 x 24 pixels, 1024 samples per pixel (reference noise ~4%;
// three paths per sample since its albedo is not grey). Margin 1.5%: the variance subtraction's
// noise with ~400 values at ~4% noise is ~(1%)^2. Measured here: relative RMSE 8.9%, 0.8% of the
// values outside the per-value bound (they sit on the silhouette).
TEST(PipelineAgainstReference, DenseCube)
{
  const Scene scene = refracta::scenes::DenseObject(48);
  const Comparison c = Compare(scene, 24, 1024, FromBenchmark(0.0990, 0.0983, 0.015));
  ExpectConsistent(c);
  // Without multiple scattering the cube loses most of its light (the dominant transport at
  // optical depth 24 and albedo 0.99). A uniform scale is not used here: the cube's error is
  // spatially structured (bright and dark regions of either sign), so scaling by 10% can lower
  // its RMSE.
  ExpectRejected("no multiple scattering",
    RenderPipeline(scene, 24, vtkEffectPlan::DRAFT, /*multipleScattering=*/false), c);
}
