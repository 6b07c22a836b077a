// Longer convergence runs of vtkReferenceRenderer (ctest label `long`): the same analytic
// comparisons as the default suite with many more samples, where the tolerance (4 reported
// standard errors) becomes a fraction of a percent, and conservative-limit scattering.
#include "ReferenceTestUtilities.h"

#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkReferenceRenderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace reftest;

// Semi-infinite isotropic medium near the conservative limit (albedo 0.99: long paths, Russian
// roulette active) and at albedo 0.5, normal incidence, three view angles.
TEST(ReferenceConvergence, SemiInfiniteChandrasekhar)
{
  for (double w : { 0.5, 0.99 })
  {
    auto medium = IsotropicSlab(w, 300, 40);
    const double top = 100.0;
    const double towards[3] = { 0, 0, 1 };
    for (double thv : { 0.0, 45.0, 75.0 })
    {
      const double t = vtkMath::RadiansFromDegrees(thv), mu = std::cos(t);
      const double dop[3] = { std::sin(t), 0, -mu }, focal[3] = { 0, 0, top }, up[3] = { 0, 1, 0 };
      vtkNew<vtkReferenceRenderer> r;
      r->SetInputData(medium);
      r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
      r->AddLight(Directional(towards, 1.0));
      r->SetImageSize(32, 32);
      r->SetSamplesPerPixel(Spp(w > 0.9 ? 128 : 256));
      r->Update();
      const Pooled p = Pool(r->GetOutput());
      const double expected = w * HFunction(w, mu) * HFunction(w, 1.0) / (4 * Pi * (mu + 1.0));
      std::cout << "w " << w << " mu " << mu << ": " << p.Mean[0] << " +- " << p.Error[0] << " ("
                << 100 * p.Error[0] / expected << "%), Chandrasekhar " << expected << ", rel. diff "
                << (p.Mean[0] - expected) / expected << "\n";
      EXPECT_NEAR(p.Mean[0], expected, 4 * p.Error[0]);
      EXPECT_LT(p.Error[0], 0.01 * expected);
    }
  }
}

// Single scattering by a slab, both sides, many samples: the 0.5 degree light disc's bias
// (O(delta^2) ~ 1e-4) stays below the statistical resolution.
TEST(ReferenceConvergence, SlabSingleScattering)
{
  const int dims[3] = { 3, 3, 4 };
  const double spacing[3] = { 40, 40, 0.25 }, origin[3] = { -40, -40, 0 };
  const double tau = 1.0, w = 0.8, g = -0.4;
  Voxel v;
  v.G = g;
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = tau;
    v.Albedo[c] = w;
  }
  auto medium = Homogeneous(dims, spacing, origin, v);
  const double th0 = vtkMath::RadiansFromDegrees(20.0);
  const double towards[3] = { std::sin(th0), 0, std::cos(th0) };
  const double mu0 = std::cos(th0);
  const double travelIn[3] = { -towards[0], -towards[1], -towards[2] };
  for (int reflect = 1; reflect >= 0; --reflect)
  {
    const double thv = vtkMath::RadiansFromDegrees(reflect ? 35.0 : 55.0);
    const double mu = std::cos(thv);
    const double dop[3] = { -std::sin(thv), 0, reflect ? -mu : mu };
    const double focal[3] = { 0, 0, 0.375 }, up[3] = { 0, 1, 0 };
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->AddLight(Directional(towards, 1.0));
    r->SetImageSize(32, 32);
    r->SetSamplesPerPixel(Spp(256));
    r->SetMaximumScatteringDepth(1);
    r->Update();
    const double out[3] = { -dop[0], -dop[1], -dop[2] };
    const double p = vtkReferenceRenderer::HenyeyGreensteinPhase(g, vtkMath::Dot(travelIn, out));
    const double expected = reflect
      ? w * p * mu0 / (mu + mu0) * (1 - std::exp(-tau * (1 / mu + 1 / mu0)))
      : w * p * mu0 / (mu0 - mu) * (std::exp(-tau / mu0) - std::exp(-tau / mu));
    const Pooled pl = Pool(r->GetOutput());
    std::cout << (reflect ? "reflected " : "transmitted ") << pl.Mean[0] << " +- " << pl.Error[0]
              << " (" << 100 * pl.Error[0] / expected << "%), analytic " << expected << "\n";
    EXPECT_NEAR(pl.Mean[0], expected, 4 * pl.Error[0]);
    EXPECT_LT(pl.Error[0], 0.01 * expected);
  }
}

// Light extent: with a directional light of angular radius delta the single-scattered radiance of
// a slab differs from the delta-light answer by O(delta^2); measured for delta = 16, 8, 4, 0.5
// degrees.
TEST(ReferenceConvergence, DirectionalLightExtent)
{
  const int dims[3] = { 3, 3, 4 };
  const double spacing[3] = { 40, 40, 0.25 }, origin[3] = { -40, -40, 0 };
  const double tau = 1.0, w = 0.8, g = 0.7;
  Voxel v;
  v.G = g;
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = tau;
    v.Albedo[c] = w;
  }
  auto medium = Homogeneous(dims, spacing, origin, v);
  const double th0 = vtkMath::RadiansFromDegrees(30.0);
  const double towards[3] = { std::sin(th0), 0, std::cos(th0) };
  const double mu0 = std::cos(th0);
  const double travelIn[3] = { -towards[0], -towards[1], -towards[2] };
  const double thv = vtkMath::RadiansFromDegrees(40.0), mu = std::cos(thv);
  const double dop[3] = { 0, std::sin(thv), -mu };
  const double focal[3] = { 0, 0, 0.375 }, up[3] = { 1, 0, 0 };
  const double out[3] = { -dop[0], -dop[1], -dop[2] };
  const double p = vtkReferenceRenderer::HenyeyGreensteinPhase(g, vtkMath::Dot(travelIn, out));
  const double exact = w * p * mu0 / (mu + mu0) * (1 - std::exp(-tau * (1 / mu + 1 / mu0)));
  double previous = 0;
  for (double delta : { 16.0, 8.0, 4.0, 0.5 })
  {
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->AddLight(Directional(towards, 1.0));
    r->SetDirectionalLightAngularRadius(delta);
    r->SetImageSize(32, 32);
    r->SetSamplesPerPixel(Spp(2048));
    r->SetMaximumScatteringDepth(1);
    r->Update();
    const Pooled pl = Pool(r->GetOutput());
    const double rel = (pl.Mean[0] - exact) / exact;
    std::cout << "delta " << delta << " deg: " << pl.Mean[0] << " +- " << pl.Error[0]
              << ", relative difference to the delta light " << rel << " +- " << pl.Error[0] / exact
              << "\n";
    if (delta == 16.0)
    {
      EXPECT_GT(std::abs(pl.Mean[0] - exact), 4 * pl.Error[0]); // the extent is visible
      previous = rel;
    }
    if (delta == 0.5)
    {
      EXPECT_NEAR(pl.Mean[0], exact, 4 * pl.Error[0]); // O(delta^2) ~ 1e-4: below resolution
      EXPECT_GT(previous, 0);
    }
  }
}
