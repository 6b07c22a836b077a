// Glass bodies in the view pass (Kernels/view_pass.cl, Physics.md "Glass bodies"): a view ray
// refracted into a dielectric surface with an inside medium sees that medium, not the grid.
//
// A uniform grid (extinction 0.5, in-scattered source S = M / (4 pi) from a constant
// MultipleScattering M) holds a ball (radius 0.3) whose surface is an interface of index 1 on
// both sides (straight rays, no reflection). Along a ray that crosses the box over 2a + c, c the
// ball's chord, the radiance (background black) is analytic:
//   grid inside the ball (no inside medium): S (1 - e^{-sigma (2a + c)}) / sigma;
//   clear glass body (sigma_b = 0): the two outer runs only, S/sigma (1 - e^{-sigma a}) (1 +
//   e^{-sigma a}); milky body (sigma_b, albedo > 0): the outer runs and S / sigma_b (1 -
//   e^{-sigma_b c}) between them, attenuated by e^{-sigma a} and followed by e^{-sigma a - sigma_b
//   c}; an absorbing body (albedo 0): the outer runs, the second attenuated by e^{-sigma_b c}.
#include "RenderingTestUtilities.h"

#include "vtkCamera.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRefractaViewPass.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

namespace
{
const double Pi = 3.14159265358979323846;
const double R = 0.3, Sigma = 0.5, M = 4 * Pi * 2.0; // S = M / (4 pi) = 2
const int Size = 31;                                 // odd: the centre pixel's ray is the axis

struct Body
{
  bool Use;
  double Sigma, Albedo;
};

// The centre pixel's radiance (first channel) with the ball's inside `body`.
double Render(const Body& body)
{
  const double origin[3] = { -0.5, -0.5, -0.5 };
  auto medium = refracta_test::MakeGrid(21, 21, 21, 0.05, origin);
  refracta_test::AddConstant(medium, vtkRefractaMedium::ExtinctionName(), 3, Sigma, Sigma, Sigma);
  auto lighting = refracta_test::MakeGrid(21, 21, 21, 0.05, origin);
  refracta_test::AddConstant(
    lighting, vtkRefractaLightingVolume::MultipleScatteringName(), 3, M, M, M);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(R);
  sphere->SetThetaResolution(256);
  sphere->SetPhiResolution(128);
  sphere->Update();
  vtkNew<vtkRefractaSurfaceMaterial> glass;
  glass->SetKindToDielectric();
  glass->SetIndexInside(1.0);
  glass->SetIndexOutside(1.0);
  glass->SetUseInsideMedium(body.Use);
  glass->SetInsideExtinction(body.Sigma, body.Sigma, body.Sigma);
  glass->SetInsideAlbedo(body.Albedo, body.Albedo, body.Albedo);
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(sphere->GetOutput(), glass);
  vtkNew<vtkRefractaViewPass> pass;
  pass->SetBackgroundColor(0, 0, 0);
  EXPECT_TRUE(pass->SetMedium(medium));
  EXPECT_TRUE(pass->SetLighting(lighting));
  pass->SetSurfaces(set);
  // Along x, off the sphere's vertex rings (a ray through a vertex is fine, but the chord of
  // the facets is then the sphere's to 1e-4 only by luck).
  vtkNew<vtkCamera> camera;
  camera->SetPosition(3, 0.013, 0.021);
  camera->SetFocalPoint(0, 0.013, 0.021);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(20);
  std::vector<float> hdr;
  EXPECT_TRUE(pass->Render(camera, Size, Size, nullptr, nullptr, hdr));
  const size_t centre = (Size / 2) + static_cast<size_t>(Size) * (Size / 2);
  return hdr.size() > 4 * centre ? hdr[4 * centre] : -1.0;
}
}

TEST(ViewPassGlassBodies, InsideMediumReplacesTheGridAlongTheRay)
{
  const double b2 = 0.013 * 0.013 + 0.021 * 0.021;
  // The box of 21 voxels of 0.05 spans half a voxel beyond the outer voxel centres: 1.05.
  const double c = 2 * std::sqrt(R * R - b2), a = 0.5 * (1.05 - c);
  const double S = M / (4 * Pi);
  const double ta = std::exp(-Sigma * a), run = S / Sigma * (1 - ta);

  const double grid = Render({ false, 0, 0 });
  const double gridExpected = S / Sigma * (1 - std::exp(-Sigma * (2 * a + c)));
  const double clear = Render({ true, 0, 0 });
  const double clearExpected = run * (1 + ta);
  const double sb = 4.0;
  const double tb = std::exp(-sb * c);
  const double milky = Render({ true, sb, 0.5 });
  const double milkyExpected = run + ta * S / sb * (1 - tb) + ta * tb * run;
  const double absorbing = Render({ true, sb, 0.0 });
  const double absorbingExpected = run + ta * tb * run;
  std::cout << "grid " << grid << " (" << gridExpected << "), clear body " << clear << " ("
            << clearExpected << "), milky " << milky << " (" << milkyExpected << "), absorbing "
            << absorbing << " (" << absorbingExpected << ")\n";
  // The steps integrate a constant medium exactly; the tessellated sphere's chord is within
  // 1e-4 R of the sphere's; float: 5e-4.
  EXPECT_NEAR(grid, gridExpected, 5e-4 * gridExpected);
  EXPECT_NEAR(clear, clearExpected, 5e-4 * clearExpected);
  EXPECT_NEAR(milky, milkyExpected, 5e-4 * milkyExpected);
  EXPECT_NEAR(absorbing, absorbingExpected, 5e-4 * absorbingExpected);
  // The clear glass adds no in-scattered light: the difference from the grid is the ball's run.
  EXPECT_GT(grid - clear, 0.5 * S * c * ta);
}
