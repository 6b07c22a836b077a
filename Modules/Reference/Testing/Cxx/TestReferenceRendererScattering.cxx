// Tests of vtkReferenceRenderer's scattering against analytic answers: single scattering by slabs
// under directional, point and spot lights, multiple scattering in a semi-infinite medium
// (Chandrasekhar's H function), and curved view rays. Monte Carlo comparisons use the standard
// error the renderer reports, as in TestReferenceRenderer.cxx.
#include "ReferenceTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkReferenceRenderer.h"
#include "vtkSMPTools.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace reftest;

// ---------------------------------------------------------------------------------------------
// Single scattering (MaximumScatteringDepth = 1) by a laterally wide slab lit by a directional
// light: reflected radiance w E p(Theta) mu0 / (mu + mu0) (1 - exp(-tau (1/mu + 1/mu0))) and
// transmitted w E p(Theta) mu0 / (mu0 - mu) (exp(-tau/mu0) - exp(-tau/mu)), HG phase g = 0.5,
// per channel.
TEST(ReferenceRenderer, SlabSingleScatteringDirectionalLight)
{
  const int dims[3] = { 3, 3, 4 };
  const double spacing[3] = { 40, 40, 0.25 }, origin[3] = { -40, -40, 0 };
  // Non-grey (one path per channel): optical thickness and albedo differ per channel.
  const double tauC[3] = { 1.0, 0.5, 2.0 }, wC[3] = { 0.8, 0.6, 0.9 }, g = 0.5, E = 3.0;
  Voxel v;
  v.G = g;
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = tauC[c] / 1.0; // thickness 4 * 0.25 = 1
    v.Albedo[c] = wC[c];
  }
  auto medium = Homogeneous(dims, spacing, origin, v);
  const double zc = 0.5 * (-0.125 + 0.875); // slab from z = -0.125 to 0.875
  const double th0 = vtkMath::RadiansFromDegrees(30.0);
  const double towards[3] = { std::sin(th0), 0, std::cos(th0) };
  const double mu0 = std::cos(th0);
  const double travelIn[3] = { -towards[0], -towards[1], -towards[2] };
  for (int reflect = 1; reflect >= 0; --reflect)
  {
    const double thv = vtkMath::RadiansFromDegrees(reflect ? 50.0 : 40.0);
    const double mu = std::cos(thv);
    // Camera direction of projection: looks down (reflection) or up (transmission), azimuth 90.
    const double dop[3] = { 0, std::sin(thv), reflect ? -mu : mu };
    const double focal[3] = { 0, 0, zc }, up[3] = { 1, 0, 0 };
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->AddLight(Directional(towards, E, 1.0, 0.5, 0.25));
    r->SetImageSize(16, 16);
    r->SetSamplesPerPixel(Spp(48));
    r->SetMaximumScatteringDepth(1);
    r->SetSeed(11);
    r->Update();
    // Outgoing travel direction towards the camera is -dop.
    const double out[3] = { -dop[0], -dop[1], -dop[2] };
    const double p = vtkReferenceRenderer::HenyeyGreensteinPhase(g, vtkMath::Dot(travelIn, out));
    const Pooled pl = Pool(r->GetOutput());
    const double colour[3] = { 1.0, 0.5, 0.25 };
    for (int c = 0; c < 3; ++c)
    {
      const double tau = tauC[c], w = wC[c];
      const double expected = reflect
        ? w * E * p * mu0 / (mu + mu0) * (1 - std::exp(-tau * (1 / mu + 1 / mu0)))
        : w * E * p * mu0 / (mu0 - mu) * (std::exp(-tau / mu0) - std::exp(-tau / mu));
      std::cout << (reflect ? "reflected" : "transmitted") << " channel " << c << ": " << pl.Mean[c]
                << " +- " << pl.Error[c] << ", analytic " << expected * colour[c] << "\n";
      EXPECT_NEAR(pl.Mean[c], expected * colour[c], 4 * pl.Error[c]);
      EXPECT_LT(pl.Error[c], 0.05 * expected * colour[c]); // the test has power
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Single scattering from a point light and a spot light inside a thin medium, against quadrature
// along each view ray: L = int T_cam sigma_s p I(w) / r^2 T_light dt (a uniform sphere's
// irradiance is exactly I / r^2, whatever its radius).
TEST(ReferenceRenderer, PointAndSpotLightSingleScattering)
{
  const int dims[3] = { 5, 5, 5 };
  const double spacing[3] = { 0.25, 0.25, 0.25 }, origin[3] = { 0, 0, 0 };
  const double sigma = 0.6, w = 0.9, g = 0.3;
  Voxel v;
  v.G = g;
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = sigma;
    v.Albedo[c] = w;
  }
  auto medium = Homogeneous(dims, spacing, origin, v);
  const double lo = -0.125, hi = 1.125;
  for (int spot = 0; spot <= 1; ++spot)
  {
    const double lp[3] = { 0.5, 1.6, 0.5 }; // outside the box, above in y
    const double lf[3] = { 0.5, 0.0, 0.5 };
    const double I = 2.0, cone = 25.0, expo = 2.0;
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->PositionalOn();
    light->SetPosition(lp[0], lp[1], lp[2]);
    light->SetFocalPoint(lf[0], lf[1], lf[2]);
    light->SetIntensity(I);
    light->SetConeAngle(spot ? cone : 90.0);
    light->SetExponent(expo);
    const double focal[3] = { 0.5, 0.5, 0.5 }, dop[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
    auto cam = ParallelCamera(focal, dop, up, 0.6);
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(cam);
    r->AddLight(light);
    r->SetLightRadius(0.01);
    r->SetImageSize(12, 12);
    r->SetSamplesPerPixel(Spp(96));
    r->SetMaximumScatteringDepth(1);
    r->Update();
    vtkImageData* out = r->GetOutput();
    vtkDataArray* hdr = out->GetPointData()->GetArray("HDR");
    vtkDataArray* se = out->GetPointData()->GetArray("StandardError");
    // Quadrature reference per pixel (the camera ray is along -z through x, y).
    auto boxLen = [&](const double o[3], const double d[3], double tmax)
    {
      double t0 = 0, t1 = tmax;
      for (int a = 0; a < 3; ++a)
      {
        if (d[a] == 0)
        {
          continue;
        }
        double ta = (lo - o[a]) / d[a], tb = (hi - o[a]) / d[a];
        if (ta > tb)
        {
          std::swap(ta, tb);
        }
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
      }
      return std::max(0.0, t1 - t0);
    };
    double resid = 0, var = 0, sumRef = 0;
    for (int j = 0; j < 12; ++j)
    {
      for (int i = 0; i < 12; ++i)
      {
        const double x = 0.5 + (2 * (i + 0.5) / 12 - 1) * 0.6;
        const double y = 0.5 + (2 * (j + 0.5) / 12 - 1) * 0.6;
        double ref = 0;
        const int m = 2000;
        const double h = (hi - lo) / m;
        for (int q = 0; q < m; ++q)
        {
          const double z = hi - (q + 0.5) * h; // distance from the top face: (q + 0.5) h
          const double tcam = std::exp(-sigma * (q + 0.5) * h);
          const double p[3] = { x, y, z };
          double toL[3] = { lp[0] - x, lp[1] - y, lp[2] - z };
          const double r2 = vtkMath::Dot(toL, toL), rl = std::sqrt(r2);
          const double dl[3] = { toL[0] / rl, toL[1] / rl, toL[2] / rl };
          const double tl = std::exp(-sigma * boxLen(p, dl, rl));
          // Scattering: incoming travel direction -dl, outgoing +z (towards the camera).
          const double cosT = -dl[2];
          double Iw = I;
          if (spot)
          {
            double axis[3] = { lf[0] - lp[0], lf[1] - lp[1], lf[2] - lp[2] };
            vtkMath::Normalize(axis);
            const double ca = -vtkMath::Dot(dl, axis);
            Iw = ca >= std::cos(vtkMath::RadiansFromDegrees(cone)) ? I * std::pow(ca, expo) : 0;
          }
          ref += tcam * sigma * w * vtkReferenceRenderer::HenyeyGreensteinPhase(g, cosT) * Iw / r2 *
            tl * h;
        }
        const vtkIdType id = i + 12 * j;
        resid += hdr->GetComponent(id, 0) - ref;
        var += se->GetComponent(id, 0) * se->GetComponent(id, 0);
        sumRef += ref;
      }
    }
    std::cout << (spot ? "spot" : "point") << ": mean " << (sumRef + resid) / 144 << " +- "
              << std::sqrt(var) / 144 << ", quadrature " << sumRef / 144 << "\n";
    EXPECT_LT(std::abs(resid), 4 * std::sqrt(var));
    EXPECT_LT(std::sqrt(var), 0.05 * sumRef);
  }
}

// ---------------------------------------------------------------------------------------------
// Multiple scattering: a thick isotropic slab (tau = 30, albedo 0.9, effectively semi-infinite)
// under a normal directional beam; reflected radiance E w mu0 H(mu) H(mu0) / (4 pi (mu + mu0))
// (Chandrasekhar), H computed here by iteration.
TEST(ReferenceRenderer, SemiInfiniteMultipleScatteringChandrasekhar)
{
  EXPECT_NEAR(HFunction(1.0, 1.0), 2.9078, 5e-3); // tabulated (Chandrasekhar 1950); 64 nodes
  const double w = 0.9, E = 1.0;
  auto medium = IsotropicSlab(w, 100, 10);
  const double top = 25.0;
  const double towards[3] = { 0, 0, 1 };
  for (double thv : { 0.0, 60.0 })
  {
    const double t = vtkMath::RadiansFromDegrees(thv), mu = std::cos(t);
    const double dop[3] = { std::sin(t), 0, -mu }, focal[3] = { 0, 0, top }, up[3] = { 0, 1, 0 };
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->AddLight(Directional(towards, E));
    r->SetImageSize(16, 16);
    r->SetSamplesPerPixel(Spp(24));
    r->SetSeed(3);
    r->Update();
    const Pooled p = Pool(r->GetOutput());
    const double expected =
      E * w * 1.0 * HFunction(w, mu) * HFunction(w, 1.0) / (4 * Pi * (mu + 1.0));
    std::cout << "semi-infinite w = " << w << ", mu = " << mu << ": " << p.Mean[0] << " +- "
              << p.Error[0] << ", Chandrasekhar " << expected << ", seconds "
              << FieldValue(r->GetOutput(), "RenderSeconds") << "\n";
    EXPECT_NEAR(p.Mean[0], expected, 4 * p.Error[0]);
    EXPECT_LT(p.Error[0], 0.05 * expected);
    EXPECT_EQ(p.Mean[0], p.Mean[1]); // grey: one path carries RGB
  }
}

// ---------------------------------------------------------------------------------------------
// Total diffuse reflectance (plane albedo) of the semi-infinite isotropic medium under a normal
// beam: A = 1 - H(1) sqrt(1 - w) (Chandrasekhar 1950; van de Hulst 1980). The reflected flux
// 2 pi int I(mu) mu dmu / E is integrated from renders at 6 Gauss-Legendre view angles; the same
// quadrature applied to the exact I(mu) checks that the quadrature error is negligible.
TEST(ReferenceRenderer, SemiInfinitePlaneAlbedo)
{
  const double w = 0.8;
  auto medium = IsotropicSlab(w, 100, 10);
  const double towards[3] = { 0, 0, 1 };
  std::vector<double> mu, wt;
  GaussLegendre(6, mu, wt);
  double albedoMC = 0, var = 0, albedoQuad = 0;
  for (size_t q = 0; q < mu.size(); ++q)
  {
    const double t = std::acos(mu[q]);
    const double dop[3] = { std::sin(t), 0, -mu[q] }, focal[3] = { 0, 0, 25 }, up[3] = { 0, 1, 0 };
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->AddLight(Directional(towards, 1.0));
    r->SetImageSize(8, 8);
    r->SetSamplesPerPixel(Spp(64));
    r->SetSeed(static_cast<unsigned int>(q));
    r->Update();
    const Pooled p = Pool(r->GetOutput());
    const double f = 2 * Pi * wt[q] * mu[q];
    albedoMC += f * p.Mean[0];
    var += f * f * p.Error[0] * p.Error[0];
    albedoQuad += f * w * HFunction(w, mu[q]) * HFunction(w, 1.0) / (4 * Pi * (mu[q] + 1));
  }
  const double published = 1 - HFunction(w, 1.0) * std::sqrt(1 - w);
  std::cout << "plane albedo w = " << w << ": Monte Carlo " << albedoMC << " +- " << std::sqrt(var)
            << ", quadrature of exact I " << albedoQuad << ", 1 - H(1) sqrt(1 - w) = " << published
            << "\n";
  EXPECT_NEAR(albedoQuad, published, 1e-3);
  EXPECT_NEAR(albedoMC, albedoQuad, 4 * std::sqrt(var));
  EXPECT_LT(std::sqrt(var), 0.03 * published);
}

// ---------------------------------------------------------------------------------------------
// Rendering along curved rays: an emission-absorption medium with n = n0 + a y seen along +x by a
// parallel camera. A view ray entering horizontally at height y0 bends upwards; its arc length
// to the far face is s = sinh(k dx) / k with k = a / n(y0), and n = n(y0) cosh(k x) along it, so
// per pixel (emission counting 1 / n^2, ds = cosh(k x) dx)
// L = eps / n(y0)^2 int_0^dx exp(-sigma sinh(k x) / k) / cosh(k x) dx + L_bg exp(-sigma s).
// (A straight-line answer is off by up to 30%.)
TEST(ReferenceRenderer, CurvedViewRaysEmissionAbsorption)
{
  const double n0 = 1.0, a = 0.3, sigma = 0.1, eps = 0.5, bg = 0.2;
  const int dims[3] = { 11, 21, 3 };
  const double spacing[3] = { 0.5, 0.5, 0.5 }, origin[3] = { 0, 0, 0 };
  auto medium = MakeMedium(dims, spacing, origin,
    [&](int, int j, int, Voxel& v)
    {
      v.N = n0 + a * j * spacing[1];
      for (int c = 0; c < 3; ++c)
      {
        v.Sigma[c] = sigma;
        v.Emission[c] = eps;
      }
    });
  const int W = 2, H = 16;
  const double focal[3] = { 2.5, 4.5, 0.5 }, dop[3] = { 1, 0, 0 }, up[3] = { 0, 1, 0 };
  const double scale = 3.5;
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(medium);
  r->SetCamera(ParallelCamera(focal, dop, up, scale));
  r->SetImageSize(W, H);
  r->SetSamplesPerPixel(Spp(64));
  r->SetBackgroundColor(bg, bg, bg);
  r->Update();
  vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
  vtkDataArray* se = r->GetOutput()->GetPointData()->GetArray("StandardError");
  ASSERT_NE(hdr, nullptr);
  const double dx = 5.5; // from x = -0.25 to 5.25
  double resid = 0, var = 0, z2 = 0, maxRelStraight = 0;
  int count = 0;
  for (int j = 0; j < H; ++j)
  {
    const double y0 = focal[1] + (2 * (j + 0.5) / H - 1) * scale;
    const double ns = n0 + a * y0, k = a / ns;
    const double yEnd = (ns * std::cosh(k * dx) - n0) / a;
    ASSERT_LT(yEnd, (dims[1] - 1) * spacing[1]); // stays where n is exactly linear
    const double s = std::sinh(k * dx) / k;
    const double T = std::exp(-sigma * s);
    double emitted = 0; // Simpson's rule
    const int q = 2000;
    for (int i = 0; i <= q; ++i)
    {
      const double x = dx * i / q, w = (i == 0 || i == q) ? 1 : (i % 2 ? 4 : 2);
      emitted += w * std::exp(-sigma * std::sinh(k * x) / k) / std::cosh(k * x);
    }
    emitted *= eps / (ns * ns) * dx / (3 * q);
    const double expected = emitted + bg * T;
    const double straight =
      eps / (ns * ns * sigma) * (1 - std::exp(-sigma * dx)) + bg * std::exp(-sigma * dx);
    maxRelStraight = std::max(maxRelStraight, std::abs(straight - expected) / expected);
    for (int i = 0; i < W; ++i)
    {
      const double got = hdr->GetComponent(i + W * j, 0), err = se->GetComponent(i + W * j, 0);
      ASSERT_GT(err, 0);
      resid += got - expected;
      var += err * err;
      z2 += (got - expected) * (got - expected) / (err * err);
      ++count;
    }
  }
  std::cout << "curved view rays: pooled residual " << resid / count << " +- "
            << std::sqrt(var) / count << ", mean z^2 " << z2 / count
            << ", straight-line answer off by up to " << 100 * maxRelStraight << "%\n";
  EXPECT_GT(maxRelStraight, 0.1);
  EXPECT_LT(std::abs(resid), 4 * std::sqrt(var));
  EXPECT_LT(z2 / count, 1.8);
}

// ---------------------------------------------------------------------------------------------
// The curved-ray machinery (RK5(4) view rays, curved light connections with chord-sphere tests
// and exit discs, straight moves through flat blocks) against the straight-line fast path, in a
// multiple-scattering scene with a point light inside the medium and a directional light:
// variant 1, n = 1 + 1e-7 y, takes RK steps everywhere; variant 2, a bump of 1e-7 in one corner
// voxel, takes RK steps near it and crosses the other (flat) blocks in straight moves. Rays bend
// by less than 1e-6, so with the same seed the images must agree with the n = 1 image to far
// better than their standard errors.
TEST(ReferenceRenderer, CurvedMachineryMatchesStraightPathInTheLimit)
{
  const int dims[3] = { 10, 10, 10 };
  const double spacing[3] = { 0.12, 0.12, 0.12 }, origin[3] = { 0, 0, 0 };
  auto build = [&](int variant)
  {
    return MakeMedium(dims, spacing, origin,
      [&](int i, int j, int k, Voxel& v)
      {
        v.N = 1.0 + (variant == 1 ? 1e-7 * j * spacing[1] : 0.0) +
          (variant == 2 && i == 9 && j == 9 && k == 0 ? 1e-7 : 0.0);
        v.G = 0.3;
        for (int c = 0; c < 3; ++c)
        {
          v.Sigma[c] = 1.0 + 0.5 * ((i + k) % 3);
          v.Albedo[c] = 0.8;
        }
      });
  };
  vtkNew<vtkLight> pl;
  pl->PositionalOn();
  pl->SetConeAngle(180);
  pl->SetPosition(0.5, 0.5, 0.5);
  pl->SetIntensity(0.5);
  const double towards[3] = { 0.3, 0.2, 0.93 };
  vtkNew<vtkCamera> cam;
  cam->SetPosition(0.5, -2.0, 1.2);
  cam->SetFocalPoint(0.5, 0.5, 0.5);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(40);
  Pooled p[3];
  std::vector<double> img[3];
  for (int variant = 0; variant <= 2; ++variant)
  {
    auto medium = build(variant);
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(cam);
    r->AddLight(pl);
    r->AddLight(Directional(towards, 1.0));
    r->SetLightRadius(0.05);
    r->SetImageSize(12, 12);
    r->SetSamplesPerPixel(Spp(16));
    r->SetSeed(9);
    r->Update();
    p[variant] = Pool(r->GetOutput());
    vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
    for (vtkIdType i = 0; i < 144; ++i)
    {
      img[variant].push_back(hdr->GetComponent(i, 0));
    }
  }
  EXPECT_GT(p[0].Mean[0], 0);
  // The flat blocks are really crossed in straight moves: a ray along x at y = z = 0.3 needs one
  // move per block (3) with the bump, one RK step per voxel length without flat blocks, and ends
  // exactly where the straight line does.
  {
    vtkNew<vtkReferenceRenderer> r;
    const double o[3] = { -0.06, 0.3, 0.3 }, d[3] = { 1, 0, 0 };
    double e1[3], ed1[3], e2[3], ed2[3];
    const int stepsRK = r->TraceRay(build(1), o, d, 1.0, e1, ed1);
    const int stepsFlat = r->TraceRay(build(2), o, d, 1.0, e2, ed2);
    std::cout << "ray across the box: " << stepsRK << " RK steps, " << stepsFlat
              << " moves with flat blocks\n";
    EXPECT_GE(stepsRK, 8);
    EXPECT_LE(stepsFlat, 4);
    EXPECT_NEAR(e2[0], 0.94, 1e-12);
    EXPECT_EQ(e2[1], 0.3);
    EXPECT_EQ(e2[2], 0.3);
  }
  for (int variant = 1; variant <= 2; ++variant)
  {
    int identical = 0;
    for (int i = 0; i < 144; ++i)
    {
      identical +=
        std::abs(img[0][i] - img[variant][i]) <= 1e-4 * std::abs(img[0][i]) + 1e-12 ? 1 : 0;
    }
    std::cout << "straight " << p[0].Mean[0] << " +- " << p[0].Error[0]
              << (variant == 1 ? ", RK everywhere " : ", flat blocks + RK near a bump ")
              << p[variant].Mean[0] << " +- " << p[variant].Error[0]
              << ", pixels equal to 1e-4: " << identical << " / 144\n";
    EXPECT_NEAR(p[variant].Mean[0], p[0].Mean[0], 0.1 * p[0].Error[0]);
    EXPECT_GE(identical, 120);
  }
}
