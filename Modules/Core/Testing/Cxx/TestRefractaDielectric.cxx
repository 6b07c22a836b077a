// Tests of vtkRefractaDielectric (the host twin of the interface optics in
// Kernels/refracta_surfaces.cl) against independent analytic forms, and of the dielectric surfaces
// of vtkRefractaSurfaceSet (kinds, texels, the interface table, corner normals).
#include "vtkCubeSource.h"
#include "vtkPlaneSource.h"
#include "vtkPolyData.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaDielectric.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSphereSource.h"

#include "refracta_surfaces.cl"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace
{
const double Pi = 3.14159265358979323846;

// Fresnel's own sine and tangent laws (Born and Wolf 1.5.3), a form independent of the one the
// class uses: Rs = sin^2(i - t) / sin^2(i + t), Rp = tan^2(i - t) / tan^2(i + t); at normal
// incidence ((n1 - n2) / (n1 + n2))^2.
double AnalyticReflectance(double incidence, double n1, double n2)
{
  if (incidence == 0.0)
  {
    return std::pow((n1 - n2) / (n1 + n2), 2);
  }
  const double t = std::asin(n1 / n2 * std::sin(incidence));
  const double rs = std::pow(std::sin(incidence - t) / std::sin(incidence + t), 2);
  const double rp = std::pow(std::tan(incidence - t) / std::tan(incidence + t), 2);
  return 0.5 * (rs + rp);
}

// Transmittance from the amplitude transmission coefficients (energy flux through the
// interface), T = (n2 cos t / n1 cos i) (ts^2 + tp^2) / 2: R + T = 1 is then a real check.
double AnalyticTransmittance(double incidence, double n1, double n2)
{
  const double ci = std::cos(incidence);
  const double ct = std::sqrt(1.0 - std::pow(n1 / n2 * std::sin(incidence), 2));
  const double ts = 2 * n1 * ci / (n1 * ci + n2 * ct);
  const double tp = 2 * n1 * ci / (n1 * ct + n2 * ci);
  return n2 * ct / (n1 * ci) * 0.5 * (ts * ts + tp * tp);
}

// Direction at `degrees` from -z towards +x (incident on the plane z = 0 from above).
void Incident(double degrees, double d[3])
{
  const double a = degrees * Pi / 180.0;
  d[0] = std::sin(a);
  d[1] = 0.0;
  d[2] = -std::cos(a);
}
}

TEST(RefractaDielectric, FresnelMatchesAnalyticLaws)
{
  const double angles[] = { 0, 10, 20, 30, 40, 45, 50, 56.31, 60, 70, 80, 85, 89 };
  for (double a : angles)
  {
    const double i = a * Pi / 180.0;
    EXPECT_NEAR(vtkRefractaDielectric::FresnelReflectance(std::cos(i), 1.0, 1.5),
      AnalyticReflectance(i, 1.0, 1.5), 1e-3)
      << a << " degrees, 1 -> 1.5";
    if (a < 41)
    {
      EXPECT_NEAR(vtkRefractaDielectric::FresnelReflectance(std::cos(i), 1.5, 1.0),
        AnalyticReflectance(i, 1.5, 1.0), 1e-3)
        << a << " degrees, 1.5 -> 1";
    }
  }
  // Textbook values: 4% at normal incidence, Rp = 0 at Brewster's angle (atan 1.5).
  EXPECT_NEAR(vtkRefractaDielectric::FresnelReflectance(1.0, 1.0, 1.5), 0.04, 1e-12);
  const double brewster = std::atan(1.5);
  const double ct = std::cos(std::asin(std::sin(brewster) / 1.5));
  const double rs = std::pow((std::cos(brewster) - 1.5 * ct) / (std::cos(brewster) + 1.5 * ct), 2);
  EXPECT_NEAR(
    vtkRefractaDielectric::FresnelReflectance(std::cos(brewster), 1.0, 1.5), 0.5 * rs, 1e-12);
}

TEST(RefractaDielectric, ReflectedPlusTransmittedIsIncident)
{
  for (double a = 0; a < 90; a += 2.5)
  {
    const double i = a * Pi / 180.0;
    for (const auto& pair :
      { std::make_pair(1.0, 1.5), std::make_pair(1.33, 1.0), std::make_pair(1.5, 2.4) })
    {
      if (pair.first / pair.second * std::sin(i) >= 1.0)
      {
        continue;
      }
      const double r =
        vtkRefractaDielectric::FresnelReflectance(std::cos(i), pair.first, pair.second);
      EXPECT_NEAR(r + AnalyticTransmittance(i, pair.first, pair.second), 1.0, 1e-12) << a;
    }
  }
}

TEST(RefractaDielectric, TotalInternalReflectionLeaksNothing)
{
  const double ng[3] = { 0, 0, 1 }; // outward normal; the ray comes from inside (below)
  for (int a = 42; a <= 89; ++a)
  {
    const double i = a * Pi / 180.0;
    EXPECT_EQ(vtkRefractaDielectric::FresnelReflectance(std::cos(i), 1.5, 1.0), 1.0) << a;
    const double d[3] = { std::sin(i), 0.0, std::cos(i) }; // upwards, from the glass
    double t[3];
    EXPECT_FALSE(vtkRefractaDielectric::Refract(d, ng, 1.5, t)) << a;
    for (double xi : { 0.0, 0.5, 0.999999 })
    {
      const auto e = vtkRefractaDielectric::Sample(d, ng, ng, 1.5, 1.0, xi);
      EXPECT_FALSE(e.Transmitted) << a;
      EXPECT_NEAR(e.Direction[2], -d[2], 1e-15);
      EXPECT_NEAR(e.Direction[0], d[0], 1e-15);
    }
  }
}

TEST(RefractaDielectric, SnellAndSides)
{
  const double ng[3] = { 0, 0, 1 };
  for (double a = 0; a < 90; a += 7)
  {
    double d[3];
    Incident(a, d);
    // Entering the glass: refracted with xi at R (R < xi transmits), reflected with xi just below.
    const double r = vtkRefractaDielectric::FresnelReflectance(std::cos(a * Pi / 180), 1.0, 1.5);
    const auto t = vtkRefractaDielectric::Sample(d, ng, ng, 1.5, 1.0, std::min(0.999, r + 1e-9));
    ASSERT_TRUE(t.Transmitted);
    EXPECT_EQ(t.EtaFrom, 1.0);
    EXPECT_EQ(t.EtaTo, 1.5);
    EXPECT_NEAR(1.0 * std::sin(a * Pi / 180), 1.5 * t.Direction[0], 1e-12); // n1 sin i = n2 sin t
    EXPECT_NEAR(t.Direction[1], 0.0, 1e-15);
    EXPECT_LT(t.Direction[2], 0.0);
    if (r > 1e-6)
    {
      const auto m = vtkRefractaDielectric::Sample(d, ng, ng, 1.5, 1.0, r * 0.999);
      ASSERT_FALSE(m.Transmitted);
      EXPECT_NEAR(m.Direction[2], -d[2], 1e-15);
    }
  }
}

TEST(RefractaDielectric, ShadingNormalNeverTunnels)
{
  // A shading normal tilted 40 degrees from the geometric one, light at 70 degrees on the side
  // the tilt leans away from: the mirror direction about the shading normal goes through the
  // plane, so the choice is redone about the geometric normal.
  const double ng[3] = { 0, 0, 1 };
  const double tilt = 40 * Pi / 180;
  const double ns[3] = { -std::sin(tilt), 0, std::cos(tilt) };
  double d[3];
  Incident(70, d);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int reflected = 0;
  for (int k = 0; k < 2000; ++k)
  {
    const auto e = vtkRefractaDielectric::Sample(d, ng, ns, 1.5, 1.0, unit(rng));
    const double side = e.Direction[2];
    EXPECT_TRUE(e.Transmitted ? side < 0 : side > 0);
    reflected += e.Transmitted ? 0 : 1;
  }
  EXPECT_GT(reflected, 0);
}

TEST(RefractaDielectric, SurfaceSetDescribesInterfaces)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(16);
  sphere->SetRadius(1.0);
  sphere->Update();
  vtkNew<vtkCubeSource> cube;
  cube->SetCenter(5, 0, 0);
  cube->Update();
  vtkNew<vtkPlaneSource> floor;
  floor->SetOrigin(-5, -5, -2);
  floor->SetPoint1(10, -5, -2);
  floor->SetPoint2(-5, 5, -2);
  floor->SetResolution(4, 4);
  floor->Update();
  vtkNew<vtkRefractaSurfaceMaterial> glass;
  glass->SetKindToDielectric();
  glass->SetIndexInside(1.5);
  glass->SetIndexOutside(1.2);
  vtkNew<vtkRefractaSurfaceMaterial> flatGlass;
  flatGlass->DeepCopy(glass);
  EXPECT_EQ(flatGlass->GetKind(), vtkRefractaSurfaceMaterial::DIELECTRIC);
  EXPECT_EQ(flatGlass->GetIndexOutside(), 1.2);
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(floor->GetOutput());
  set->AddSurface(sphere->GetOutput(), glass);
  set->AddSurface(cube->GetOutput(), flatGlass);
  ASSERT_TRUE(set->Build());
  const vtkIdType sphereTriangles = sphere->GetOutput()->GetNumberOfCells();
  EXPECT_EQ(set->GetNumberOfDielectricTriangles(), sphereTriangles + 12);
  const auto& interfaces = set->GetSurfaceInterfaces();
  ASSERT_EQ(interfaces.size(), size_t(3 * REFRACTA_SURFACE_INTERFACE_FLOATS));
  EXPECT_EQ(interfaces[0], 1.0f);
  EXPECT_EQ(interfaces[1], 1.0f);
  EXPECT_EQ(interfaces[2], 1.5f);
  EXPECT_EQ(interfaces[3], 1.2f);
  const auto& info = set->GetTriangleInfo();
  const auto& normals = set->GetTriangleNormals();
  ASSERT_EQ(normals.size(), size_t(REFRACTA_TRIANGLE_NORMAL_FLOATS * set->GetNumberOfTriangles()));
  const auto& bvhTri = set->GetBVH()->GetTriangles();
  vtkIdType dielectricTexels = 0;
  for (vtkIdType k = 0; k < set->GetNumberOfTriangles(); ++k)
  {
    const int* in = &info[REFRACTA_TRIANGLE_INFO_INTS * k];
    const int surface = in[REFRACTA_TRIANGLE_INFO_SURFACE];
    EXPECT_EQ(in[REFRACTA_TRIANGLE_INFO_KIND],
      surface == 0 ? REFRACTA_SURFACE_LAMBERTIAN : REFRACTA_SURFACE_DIELECTRIC);
    if (surface != 0)
    {
      EXPECT_EQ(in[REFRACTA_TRIANGLE_INFO_SUBDIVISION], 1); // no deposits: one texel
      ++dielectricTexels;
    }
    for (int corner = 0; corner < 3; ++corner)
    {
      const float* n = &normals[REFRACTA_TRIANGLE_NORMAL_FLOATS * k + 4 * corner];
      EXPECT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-6);
      const double* o = set->GetBVH()->GetFrameOrigin();
      const double* q = &bvhTri[9 * k + 3 * corner];
      const double p[3] = { q[0] + o[0], q[1] + o[1], q[2] + o[2] }; // world
      if (surface == 1)
      {
        // The sphere: the corner normal is the radial direction (outward) within the
        // tessellation's error.
        const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        EXPECT_GT((n[0] * p[0] + n[1] * p[1] + n[2] * p[2]) / r, 0.995);
      }
      else if (surface == 2)
      {
        // The cube: corners at 54.7 degrees from every face keep the face normal (an axis).
        EXPECT_NEAR(std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]), 1.0, 1e-6);
        const double c[3] = { p[0] - 5, p[1], p[2] };
        EXPECT_GT(n[0] * c[0] + n[1] * c[1] + n[2] * c[2], 0.0); // outward
      }
    }
  }
  EXPECT_EQ(dielectricTexels, sphereTriangles + 12);
  // The floor's texels are laid out as before: the dielectric triangles took one each.
  EXPECT_GT(set->GetNumberOfTexels(), dielectricTexels + 32);
}
