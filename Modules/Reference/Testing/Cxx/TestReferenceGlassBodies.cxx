// Glass bodies in the reference renderer (vtkReferenceWalk, Physics.md "Glass bodies"): a path
// refracted into a dielectric surface with an inside medium is tracked in that medium, not the
// grid's, so the ground truth agrees with the OpenCL passes.
//
// A uniform emitting, absorbing grid (sigma 0.5, emission 2, albedo 0) holds a ball (radius 0.3)
// whose surface is an interface of index 1 on both sides (straight paths, no reflection). Along a
// ray crossing the box over 2a + c (c the ball's chord) the radiance is analytic, as in
// ViewPassGlassBodies: without an inside medium the grid's e / sigma (1 - e^{-sigma (2a + c)});
// with a clear body only the outer runs, run (1 + e^{-sigma a}), run = e / sigma (1 - e^{-sigma
// a}); with an absorbing, emitting body (sigma_b, e_b) run + e^{-sigma a} e_b / sigma_b (1 -
// e^{-sigma_b c}) + e^{-sigma a - sigma_b c} run.
#include "ReferenceTestUtilities.h"

#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <iostream>

namespace
{
using namespace reftest;

const double R = 0.3, Sigma = 0.5, E = 2.0;
const double Y = 0.013, Z = 0.021; // the rays' offset from the centre (off the vertex rings)

// The pooled mean and standard error of the image (channel 0) for the ball's inside `use`
// (sigma_b, e_b).
Pooled Render(bool use, double sigmaB, double emissionB)
{
  const int dims[3] = { 11, 11, 11 };
  const double spacing[3] = { 0.1, 0.1, 0.1 }, origin[3] = { -0.5, -0.5, -0.5 };
  Voxel v;
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = Sigma;
    v.Emission[c] = E;
  }
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(R);
  sphere->SetThetaResolution(256);
  sphere->SetPhiResolution(128);
  sphere->Update();
  vtkNew<vtkRefractaSurfaceMaterial> glass;
  glass->SetKindToDielectric();
  glass->SetIndexInside(1.0);
  glass->SetIndexOutside(1.0);
  glass->SetUseInsideMedium(use);
  glass->SetInsideExtinction(sigmaB, sigmaB, sigmaB);
  glass->SetInsideEmission(emissionB, emissionB, emissionB);
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(sphere->GetOutput(), glass);
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(Homogeneous(dims, spacing, origin, v));
  const double focal[3] = { 0, Y, Z }, dop[3] = { -1, 0, 0 }, up[3] = { 0, 0, 1 };
  r->SetCamera(ParallelCamera(focal, dop, up, 0.002)); // every ray within 0.003 of (Y, Z)
  r->SetSurfaces(set);
  r->SetImageSize(4, 4);
  r->SetSamplesPerPixel(Spp(256));
  r->SetSeed(7);
  r->Update();
  return Pool(r->GetOutput());
}
}

TEST(ReferenceGlassBodies, InsideMediumReplacesTheGridAlongTheRay)
{
  const double c = 2 * std::sqrt(R * R - Y * Y - Z * Z), a = 0.5 * (1.1 - c);
  const double ta = std::exp(-Sigma * a), run = E / Sigma * (1 - ta);
  const double sb = 4.0, eb = 3.0, tb = std::exp(-sb * c);
  struct Case
  {
    const char* what;
    bool use;
    double sigma, emission, expected;
  };
  const Case cases[] = { { "grid inside", false, 0, 0,
                           E / Sigma * (1 - std::exp(-Sigma * (2 * a + c))) },
    { "clear body", true, 0, 0, run * (1 + ta) },
    { "absorbing, emitting body", true, sb, eb, run + ta * eb / sb * (1 - tb) + ta * tb * run } };
  for (const Case& k : cases)
  {
    const Pooled p = Render(k.use, k.sigma, k.emission);
    std::cout << k.what << ": " << p.Mean[0] << " +- " << p.Error[0] << " (expected " << k.expected
              << ")\n";
    // Collision estimates of the emission: 4 standard errors; the rays' offsets (within 0.003)
    // change the chord by < 2e-4 of the path.
    EXPECT_NEAR(p.Mean[0], k.expected, 4 * p.Error[0] + 2e-3 * k.expected) << k.what;
  }
}
