// Tests of vtkReferenceRenderer's surfaces (vtkRefractaSurfaceSet: two-sided Lambertian triangles)
// and of the background as a light (BackgroundIlluminates), against analytic answers.
//
// Statistic: the renderer reports each pixel's standard error of the mean (SE). For an image whose
// every pixel has an analytic value E_p, the pooled z-score
//   Z = sum_p (L_p - E_p) / sqrt(sum_p SE_p^2)
// (pixels independent) must satisfy |Z| <= 3 per channel (a false failure rate of 0.27% per
// comparison for a Gaussian mean; the seeds are fixed, so a run is reproducible), and every pixel
// |z_p| <= 5. Lights are spheres of radius 0.01 (the reference's LightRadius): a sphere of
// radiance I / (pi r^2) lying wholly above a surface point's horizon gives that point exactly the
// irradiance I cos(theta) / d^2 of the point light, so the answers below hold without an
// extent correction.
#include "ReferenceTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkReferenceRenderer.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

using namespace reftest;

namespace
{
// A vacuum medium box (the renderer needs one) of 2^3 voxels at `centre`, edge 0.2.
vtkSmartPointer<vtkImageData> VacuumBox(const double centre[3])
{
  const int dims[3] = { 2, 2, 2 };
  const double spacing[3] = { 0.1, 0.1, 0.1 };
  const double origin[3] = { centre[0] - 0.05, centre[1] - 0.05, centre[2] - 0.05 };
  return Homogeneous(dims, spacing, origin, Voxel());
}

// The square [-h, h]^2 in the plane z = z0 (normal +z), two triangles.
vtkSmartPointer<vtkPolyData> Square(double h, double z0)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-h, -h, z0);
  plane->SetPoint1(h, -h, z0);
  plane->SetPoint2(-h, h, z0);
  plane->Update();
  return plane->GetOutput();
}

vtkSmartPointer<vtkRefractaSurfaceSet> OneSurface(vtkPolyData* mesh, const double albedo[3])
{
  vtkNew<vtkRefractaSurfaceMaterial> material;
  material->SetAlbedo(albedo);
  auto set = vtkSmartPointer<vtkRefractaSurfaceSet>::New();
  set->AddSurface(mesh, material);
  return set;
}

vtkSmartPointer<vtkLight> PointLight(const double p[3], double intensity)
{
  auto l = vtkSmartPointer<vtkLight>::New();
  l->SetLightTypeToSceneLight();
  l->PositionalOn();
  l->SetPosition(p[0], p[1], p[2]);
  l->SetFocalPoint(p[0], p[1], p[2] - 1);
  l->SetConeAngle(90); // a point light
  l->SetIntensity(intensity);
  return l;
}

// A camera looking down -z at the square [-s, s]^2 of the plane z = 0 (parallel projection).
vtkSmartPointer<vtkCamera> DownCamera(double s)
{
  const double focal[3] = { 0, 0, 0 }, dop[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
  return ParallelCamera(focal, dop, up, s);
}

// World (x, y) of pixel (i, j)'s centre for DownCamera(s) and a square image of n pixels.
void PixelXY(int i, int j, int n, double s, double& x, double& y)
{
  x = (2 * (i + 0.5) / n - 1) * s;
  y = (2 * (j + 0.5) / n - 1) * s;
}

// Compares the renderer's square n x n output against expected(i, j, channel) with the pooled
// statistic of the file comment.
void ExpectImage(
  vtkImageData* out, int n, const std::function<double(int, int, int)>& expected, const char* what)
{
  vtkDataArray* hdr = out->GetPointData()->GetArray("HDR");
  vtkDataArray* se = out->GetPointData()->GetArray("StandardError");
  ASSERT_NE(hdr, nullptr) << what;
  ASSERT_NE(se, nullptr) << what;
  for (int c = 0; c < 3; ++c)
  {
    double diff = 0, var = 0, sumE = 0, worst = 0;
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const vtkIdType p = i + static_cast<vtkIdType>(n) * j;
        const double e = expected(i, j, c), l = hdr->GetComponent(p, c);
        const double s = se->GetComponent(p, c);
        diff += l - e;
        var += s * s;
        sumE += e;
        if (s > 0)
        {
          worst = std::max(worst, std::abs(l - e) / s);
        }
        else
        {
          EXPECT_NEAR(l, e, 1e-6 * std::max(1.0, e)) << what << " pixel " << i << ", " << j;
        }
      }
    }
    const double z =
      var > 0 ? diff / std::sqrt(var) : (diff == 0 ? 0 : std::numeric_limits<double>::infinity());
    std::cout << what << " channel " << c << ": mean " << (sumE + diff) / (n * n) << " expected "
              << sumE / (n * n) << " (relative SE " << std::sqrt(var) / std::max(sumE, 1e-300)
              << "), pooled z " << z << ", worst pixel |z| " << worst << "\n";
    EXPECT_LE(std::abs(z), 3.0) << what << " channel " << c;
    EXPECT_LE(worst, 5.0) << what << " channel " << c;
  }
}
} // namespace

// ---------------------------------------------------------------------------------------------
// A diffuse plane (albedo per channel (0.8, 0.5, 0.2)) under a point light at height h: the
// radiance it reflects is albedo I cos(theta) / (pi r^2) with cos(theta) = h / r. The plane does
// not see itself, so there is exactly one bounce. No medium in the way (a vacuum box elsewhere).
TEST(ReferenceSurfaces, DiffusePlaneUnderPointLight)
{
  const double albedo[3] = { 0.8, 0.5, 0.2 }, h = 1.0, I = 2.0, s = 1.0;
  const double lp[3] = { 0, 0, h }, boxCentre[3] = { 4, 4, 3 };
  const int n = 8;
  auto surfaces = OneSurface(Square(5, 0), albedo);
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(VacuumBox(boxCentre));
  r->SetCamera(DownCamera(s));
  r->AddLight(PointLight(lp, I));
  r->SetLightRadius(0.01);
  r->SetSurfaces(surfaces);
  r->SetImageSize(n, n);
  r->SetSamplesPerPixel(Spp(256));
  r->SetSeed(3);
  r->Update();
  ExpectImage(
    r->GetOutput(), n,
    [&](int i, int j, int c)
    {
      double x, y;
      PixelXY(i, j, n, s, x, y);
      const double r2 = x * x + y * y + h * h;
      return albedo[c] * I * (h / std::sqrt(r2)) / (Pi * r2);
    },
    "plane under a point light");

  // The surface set is part of the renderer's state: without it the image is black.
  r->SetSurfaces(nullptr);
  r->Update();
  EXPECT_EQ(Pool(r->GetOutput()).Mean[0], 0.0);
}

// ---------------------------------------------------------------------------------------------
// A directional light of irradiance E (on a plane perpendicular to it) from 36.87 degrees off the
// normal (direction (0.6, 0, 0.8)): the plane's radiance is albedo E 0.8 / pi everywhere. The
// light is a disc of angular radius 0.5 degree, reached by connections that escape; the
// irradiance it gives a tilted plane differs from E cos(theta) by O(delta^2) = 1e-5 relative.
TEST(ReferenceSurfaces, DiffusePlaneUnderDirectionalLight)
{
  const double albedo[3] = { 0.3, 0.6, 0.9 }, E = 1.5, towards[3] = { 0.6, 0, 0.8 };
  const double boxCentre[3] = { 4, 4, 3 };
  const int n = 4;
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(VacuumBox(boxCentre));
  r->SetCamera(DownCamera(1.0));
  r->AddLight(Directional(towards, E));
  r->SetSurfaces(OneSurface(Square(5, 0), albedo));
  r->SetImageSize(n, n);
  r->SetSamplesPerPixel(Spp(256));
  r->SetSeed(19);
  r->Update();
  ExpectImage(
    r->GetOutput(), n, [&](int, int, int c) { return albedo[c] * E * 0.8 / Pi; },
    "plane under a directional light");
}

// ---------------------------------------------------------------------------------------------
// An opaque square (half-size 0.3, at z = 0.5) between the point light (z = 1) and the floor,
// single scattering only (MaximumScatteringDepth 1): the camera sees the square's lit top where
// |x|, |y| < 0.3 (albedo I cos / (pi r^2) with the light 0.5 above it), the floor's umbra (exactly
// 0: no connection gets past the square) where the square's shadow |x|, |y| < 0.6 falls, and the
// lit floor elsewhere. The pixel centres are at least 0.025 from the shadow's edge, wider than the
// penumbra of the light's radius 0.01.
TEST(ReferenceSurfaces, OpaqueSquareCastsShadow)
{
  const double albedo[3] = { 0.8, 0.8, 0.8 }, I = 2.0, s = 1.0;
  const double lp[3] = { 0, 0, 1 }, boxCentre[3] = { 4, 4, 3 };
  const int n = 8;
  auto surfaces = OneSurface(Square(5, 0), albedo);
  vtkNew<vtkRefractaSurfaceMaterial> material;
  material->SetAlbedo(albedo);
  surfaces->AddSurface(Square(0.3, 0.5), material);
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(VacuumBox(boxCentre));
  r->SetCamera(DownCamera(s));
  r->AddLight(PointLight(lp, I));
  r->SetLightRadius(0.01);
  r->SetSurfaces(surfaces);
  r->SetMaximumScatteringDepth(1);
  r->SetImageSize(n, n);
  r->SetSamplesPerPixel(Spp(256));
  r->SetSeed(23);
  r->Update();
  ExpectImage(
    r->GetOutput(), n,
    [&](int i, int j, int c)
    {
      double x, y;
      PixelXY(i, j, n, s, x, y);
      const double m = std::max(std::abs(x), std::abs(y));
      const double h = m < 0.3 ? 0.5 : 1.0; // the light's height above what the pixel sees
      if (m >= 0.3 && m < 0.6)
      {
        return 0.0;
      }
      const double r2 = x * x + y * y + h * h;
      return albedo[c] * I * (h / std::sqrt(r2)) / (Pi * r2);
    },
    "floor shadowed by an opaque square");
}

// ---------------------------------------------------------------------------------------------
// The same plane under an absorbing slab (sigma_t = 2 per unit, albedo 0, z in [0.4, 0.6],
// laterally far wider than the image): the light reaching a point crosses the slab obliquely
// (Beer-Lambert factor exp(-sigma dz / cos(theta))) and the vertical view ray crosses it once
// more (exp(-sigma dz)).
TEST(ReferenceSurfaces, PlaneUnderAbsorbingSlab)
{
  const double albedo[3] = { 0.7, 0.7, 0.7 }, h = 1.0, I = 2.0, s = 0.8, sigma = 2.0, dz = 0.2;
  const double lp[3] = { 0, 0, h };
  const int dims[3] = { 4, 4, 2 };
  const double spacing[3] = { 1.0, 1.0, 0.1 }, origin[3] = { -1.5, -1.5, 0.45 };
  Voxel v;
  for (double& x : v.Sigma)
  {
    x = sigma;
  }
  const int n = 6;
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(Homogeneous(dims, spacing, origin, v));
  r->SetCamera(DownCamera(s));
  r->AddLight(PointLight(lp, I));
  r->SetLightRadius(0.01);
  r->SetSurfaces(OneSurface(Square(5, 0), albedo));
  r->SetImageSize(n, n);
  r->SetSamplesPerPixel(Spp(512));
  r->SetSeed(5);
  r->Update();
  ExpectImage(
    r->GetOutput(), n,
    [&](int i, int j, int c)
    {
      double x, y;
      PixelXY(i, j, n, s, x, y);
      const double r2 = x * x + y * y + h * h, cosT = h / std::sqrt(r2);
      return albedo[c] * I * cosT / (Pi * r2) * std::exp(-sigma * dz / cosT) *
        std::exp(-sigma * dz);
    },
    "plane under an absorbing slab");
}

// ---------------------------------------------------------------------------------------------
// The plane inside an absorbing medium whose index varies by 7e-7 (n = 1 + 1e-7 k in voxel layer
// k): the view and
// light rays are integrated by the RK5(4) steps and the surface is met on their chords; the answer
// is the straight-ray one (the bending is ~1e-7 of the path) with the path lengths inside the box
// (z in [-0.2, 0.6]): exp(-sigma 0.6 (1 + 1 / cos(theta))).
TEST(ReferenceSurfaces, PlaneInsideCurvedAbsorbingMedium)
{
  const double albedo[3] = { 0.6, 0.6, 0.6 }, h = 1.0, I = 2.0, s = 0.5, sigma = 1.0;
  const double lp[3] = { 0, 0, h };
  const int dims[3] = { 5, 5, 8 }; // the box is [-1, 1]^2 x [-0.2, 0.6]
  const double spacing[3] = { 0.4, 0.4, 0.1 }, origin[3] = { -0.8, -0.8, -0.15 };
  auto medium = MakeMedium(dims, spacing, origin,
    [&](int, int, int k, Voxel& v)
    {
      v.N = 1 + 1e-7 * k;
      for (double& x : v.Sigma)
      {
        x = sigma;
      }
    });
  const int n = 4;
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(medium);
  r->SetCamera(DownCamera(s));
  r->AddLight(PointLight(lp, I));
  r->SetLightRadius(0.01);
  r->SetSurfaces(OneSurface(Square(5, 0), albedo));
  r->SetImageSize(n, n);
  r->SetSamplesPerPixel(Spp(2048));
  r->SetSeed(7);
  r->Update();
  ExpectImage(
    r->GetOutput(), n,
    [&](int i, int j, int c)
    {
      double x, y;
      PixelXY(i, j, n, s, x, y);
      const double r2 = x * x + y * y + h * h, cosT = h / std::sqrt(r2);
      return albedo[c] * I * cosT / (Pi * r2) * std::exp(-sigma * 0.6 * (1 + 1 / cosT));
    },
    "plane inside a curved-ray absorbing medium");
}

// ---------------------------------------------------------------------------------------------
// An integrating sphere: a closed sphere of radius R and albedo a with a point light of intensity
// I at its centre. In a sphere every wall element sees every other with the form factor
// dA / (4 pi R^2), so the wall's irradiance is uniform, E = I / R^2 + a E, and its radiance
// a I / (pi R^2 (1 - a)): every bounce counts (a = 0.5 doubles the direct light). With
// MaximumScatteringDepth 1 only the direct term a I / (pi R^2) remains. The mesh has 128 x 128
// facets (its largest deviation from the sphere, 1 - cos(pi / 128) = 3e-4, is far below the
// tolerance); it is closed, and the watertight test lets no path out through its edges.
TEST(ReferenceSurfaces, IntegratingSphere)
{
  const double a = 0.5, R = 1.0, I = 3.0;
  const double albedo[3] = { a, a, a }, centre[3] = { 0, 0, 0 }, boxCentre[3] = { 0, 0.5, 0 };
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(R);
  sphere->SetThetaResolution(128);
  sphere->SetPhiResolution(128);
  sphere->Update();
  vtkNew<vtkCamera> cam;
  cam->SetPosition(0.3, 0.1, 0);
  cam->SetFocalPoint(-1, 0.1, 0);
  cam->SetViewUp(0, 1, 0);
  cam->SetViewAngle(40);
  const int n = 4;
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(VacuumBox(boxCentre));
  r->SetCamera(cam);
  r->AddLight(PointLight(centre, I));
  r->SetLightRadius(0.01);
  r->SetSurfaces(OneSurface(sphere->GetOutput(), albedo));
  r->SetImageSize(n, n);
  r->SetSamplesPerPixel(Spp(1024));
  r->SetSeed(11);
  r->Update();
  ExpectImage(
    r->GetOutput(), n, [&](int, int, int) { return a * I / (Pi * R * R * (1 - a)); },
    "integrating sphere");
  EXPECT_EQ(r->GetOutput()->GetFieldData()->GetArray("TruncatedPaths")->GetComponent(0, 0), 0);

  r->SetMaximumScatteringDepth(1);
  r->Update();
  ExpectImage(
    r->GetOutput(), n, [&](int, int, int) { return a * I / (Pi * R * R); },
    "integrating sphere, direct light only");
}

// ---------------------------------------------------------------------------------------------
// A uniform sky of radiance L over a plane of albedo a: the plane sees the whole upper hemisphere
// (a flat surface never sees itself), its irradiance is pi L and its radiance a L. The sky is
// sampled by next-event estimation (uniform sphere) mixed with the cosine-weighted BRDF sampling.
// With BackgroundIlluminates off the sky is only seen, and the plane is black.
TEST(ReferenceSurfaces, UniformSkyOverPlane)
{
  const double albedo[3] = { 0.9, 0.6, 0.3 }, L[3] = { 0.5, 0.8, 1.2 }, s = 1.0;
  const double boxCentre[3] = { 4, 4, 3 };
  const int n = 4;
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(VacuumBox(boxCentre));
  r->SetCamera(DownCamera(s));
  r->SetSurfaces(OneSurface(Square(5, 0), albedo));
  r->SetBackgroundColor(L[0], L[1], L[2]);
  r->BackgroundIlluminatesOn();
  r->SetImageSize(n, n);
  r->SetSamplesPerPixel(Spp(256));
  r->SetSeed(13);
  r->Update();
  ExpectImage(
    r->GetOutput(), n, [&](int, int, int c) { return albedo[c] * L[c]; },
    "uniform sky over a plane");

  r->BackgroundIlluminatesOff();
  r->Update();
  const Pooled dark = Pool(r->GetOutput());
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_EQ(dark.Mean[c], 0.0) << "channel " << c;
  }
}

// ---------------------------------------------------------------------------------------------
// An environment map (16 x 8 random texels, one of them 200 times brighter: a "sun") over a
// plane of albedo a with its normal along the map's up: the plane's radiance is
// (a / pi) int_{upper hemisphere} L(w) cos(theta) dw. The integral is computed here by midpoint
// quadrature of the map's own bilinear lookup (vtkRefractaEnvironmentMap::Sample) on a
// 4096 x 1024 grid in (longitude, latitude), independent of the renderer's luminance sampling,
// whose pdf must be exactly that of the texels it draws for this to agree.
TEST(ReferenceSurfaces, EnvironmentMapOverPlane)
{
  const int W = 16, H = 8;
  std::vector<double> rgb(3 * W * H);
  std::mt19937 gen(42);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (double& x : rgb)
  {
    x = uni(gen);
  }
  for (int c = 0; c < 3; ++c)
  {
    rgb[3 * (6 * W + 5) + c] *= 200; // a bright texel above the horizon
  }
  vtkNew<vtkImageData> env;
  env->SetDimensions(W, H, 1);
  vtkNew<vtkDoubleArray> scalars;
  scalars->SetNumberOfComponents(3);
  scalars->SetNumberOfTuples(W * H);
  for (int i = 0; i < 3 * W * H; ++i)
  {
    scalars->SetValue(i, rgb[i]);
  }
  env->GetPointData()->SetScalars(scalars);
  const double up[3] = { 0, 0, 1 }, right[3] = { 1, 0, 0 };
  // Quadrature over the upper hemisphere (latitude > 0 about `up`): dw = cos(lat) dlat dlon and
  // cos(theta) = sin(lat).
  double E[3] = { 0, 0, 0 };
  const int nLon = 4096, nLat = 1024;
  for (int b = 0; b < nLat; ++b)
  {
    const double lat = (b + 0.5) / nLat * (Pi / 2);
    const double weight = std::sin(lat) * std::cos(lat) * (Pi / 2 / nLat) * (2 * Pi / nLon);
    for (int k = 0; k < nLon; ++k)
    {
      const double uv[2] = { (k + 0.5) / nLon, lat / Pi + 0.5 };
      double l[3];
      vtkRefractaEnvironmentMap::Sample(rgb.data(), W, H, uv[0], uv[1], l);
      for (int c = 0; c < 3; ++c)
      {
        E[c] += weight * l[c];
      }
    }
  }
  const double albedo[3] = { 0.5, 0.5, 0.5 }, boxCentre[3] = { 4, 4, 3 }, s = 1.0;
  const int n = 4;
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(VacuumBox(boxCentre));
  r->SetCamera(DownCamera(s));
  r->SetSurfaces(OneSurface(Square(5, 0), albedo));
  r->SetEnvironmentMap(env);
  r->SetEnvironmentUp(up[0], up[1], up[2]);
  r->SetEnvironmentRight(right[0], right[1], right[2]);
  r->BackgroundIlluminatesOn();
  r->SetImageSize(n, n);
  r->SetSamplesPerPixel(Spp(1024));
  r->SetSeed(17);
  r->Update();
  ExpectImage(
    r->GetOutput(), n, [&](int, int, int c) { return albedo[c] / Pi * E[c]; },
    "environment map over a plane");
}

// ---------------------------------------------------------------------------------------------
// Bad surfaces: a mesh with a NaN vertex is rejected by the set with an error naming it, the
// other surfaces still render; an empty set renders like none.
TEST(ReferenceSurfaces, BadSurfacesAreReportedAndSkipped)
{
  const double albedo[3] = { 0.8, 0.8, 0.8 }, h = 1.0, I = 2.0, s = 1.0;
  const double lp[3] = { 0, 0, h }, boxCentre[3] = { 4, 4, 3 };
  auto surfaces = OneSurface(Square(5, 0), albedo);
  vtkSmartPointer<vtkPolyData> bad = Square(1, 0.5);
  bad->GetPoints()->SetPoint(0, std::nan(""), 0, 0.5);
  surfaces->AddSurface(bad);
  vtkNew<vtkTest::ErrorObserver> setErrors;
  surfaces->AddObserver(vtkCommand::ErrorEvent, setErrors);
  const int n = 4;
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(VacuumBox(boxCentre));
  r->SetCamera(DownCamera(s));
  r->AddLight(PointLight(lp, I));
  r->SetLightRadius(0.01);
  r->SetSurfaces(surfaces);
  r->SetImageSize(n, n);
  r->SetSamplesPerPixel(Spp(256));
  r->Update();
  EXPECT_TRUE(setErrors->GetError());
  ExpectImage(
    r->GetOutput(), n,
    [&](int i, int j, int c)
    {
      double x, y;
      PixelXY(i, j, n, s, x, y);
      const double r2 = x * x + y * y + h * h;
      return albedo[c] * I * (h / std::sqrt(r2)) / (Pi * r2);
    },
    "plane beside a rejected NaN surface");

  vtkNew<vtkRefractaSurfaceSet> empty;
  r->SetSurfaces(empty);
  r->Update();
  EXPECT_EQ(Pool(r->GetOutput()).Mean[1], 0.0);
}
