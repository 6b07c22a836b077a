// Photon pass with dielectric interfaces (vtkRefractaSurfaceMaterial::DIELECTRIC, issue 20): a
// glass slab reflects the Fresnel fraction per interface event and the books close (reflected +
// transmitted = incident at every interface, emitted = escaped); a right-angle prism reflects
// totally at its hypotenuse (nothing below it) and sends T / (1 + R) of the beam out of its leg;
// a sharp ball lens focuses a parallel beam where an independent Snell trace puts the focus.
#include "PhotonTestUtilities.h"
#include "SharpSphereTrace.h"

#include "vtkCellArray.h"
#include "vtkCubeSource.h"
#include "vtkDiskSource.h"
#include "vtkMatrix4x4.h"
#include "vtkPhotonTracer.h"
#include "vtkPlaneSource.h"
#include "vtkPoints.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSphereSource.h"

#include "refracta_surfaces.cl" // the triangle info layout

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <vector>

namespace
{
vtkSmartPointer<vtkRefractaSurfaceMaterial> Glass(double n)
{
  auto m = vtkSmartPointer<vtkRefractaSurfaceMaterial>::New();
  m->SetKindToDielectric();
  m->SetIndexInside(n);
  m->SetIndexOutside(1.0);
  return m;
}

vtkSmartPointer<vtkRefractaSurfaceMaterial> Black()
{
  auto m = vtkSmartPointer<vtkRefractaSurfaceMaterial>::New();
  m->SetAlbedo(0, 0, 0);
  return m;
}

vtkSmartPointer<vtkImageData> Vacuum()
{
  auto medium = photontest::MakeMedium(
    8, 8, 8, 0.5, [](double, double, double) { return photontest::Voxel{}; });
  medium->SetOrigin(-2, -2, -2);
  return medium;
}

// Flux (first channel) deposited on the triangles of surface `surface`.
double SurfaceFlux(vtkRefractaSurfaceSet* set, vtkImageData* out, int surface)
{
  vtkDataArray* e =
    out->GetFieldData()->GetArray(vtkRefractaLightingVolume::SurfaceIrradianceName());
  double flux = 0;
  const auto& info = set->GetTriangleInfo();
  for (vtkIdType k = 0; k < set->GetNumberOfTriangles(); ++k)
  {
    if (info[4 * k + REFRACTA_TRIANGLE_INFO_SURFACE] != surface)
    {
      continue;
    }
    const int first = info[4 * k], n = info[4 * k + 1];
    for (int i = 0; i < n * n; ++i)
    {
      flux += photontest::TexelIrradiance(e, first + i) * set->GetTexelAreas()[first + i];
    }
  }
  return flux;
}

// A sharp glass ball of `radius` (256 x 128 sphere, index `index`) at the origin under a black
// disk at z = 1.3 with a hole of radius `aperture`: a beam from +z reaches the ball through the
// hole only, away from its axis.
void AddBallLens(vtkRefractaSurfaceSet* set, double radius, double index, double aperture)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(256);
  sphere->SetPhiResolution(128);
  sphere->Update();
  vtkNew<vtkDiskSource> disk;
  disk->SetInnerRadius(aperture);
  disk->SetOuterRadius(1.25);
  disk->SetCircumferentialResolution(96);
  disk->SetCenter(0, 0, 1.3);
  disk->Update();
  set->AddSurface(sphere->GetOutput(), Glass(index));
  set->AddSurface(disk->GetOutput(), Black());
}

// Every book closes to 1e-6 of the emitted power, and reflected + transmitted are the interface
// events' power.
void ExpectExactBooks(vtkImageData* out)
{
  using photontest::Energy;
  const auto emitted = Energy(out, "EnergyEmitted");
  const auto surface = Energy(out, "EnergySurface");
  const auto escaped = Energy(out, "EnergyEscaped");
  const auto absorbed = Energy(out, "EnergyAbsorbed");
  const auto remaining = Energy(out, "EnergyRemaining");
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(
      surface[c] + escaped[c] + absorbed[c] + remaining[c], emitted[c], 1e-6 * emitted[c]);
  }
}
}

TEST(PhotonInterfaces, SlabReflectsFresnelPerEvent)
{
  // A glass slab (n = 1.5) under a vertical beam: every event is at normal incidence, so the
  // power reflected per event is R = ((n - 1) / (n + 1))^2 = 0.04 of the power meeting the
  // interfaces, and nothing is lost.
  vtkNew<vtkCubeSource> slab;
  slab->SetBounds(-1, 1, -1, 1, -0.25, 0.25);
  slab->Update();
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(slab->GetOutput(), Glass(1.5));
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(Vacuum());
  tracer->SetSurfaces(set);
  tracer->AddLight(photontest::Directional({ 0, 0, 10 }, { 0, 0, 0 }, 1.0));
  tracer->SetNumberOfPhotons(1 << 18);
  tracer->Update();
  vtkImageData* out = tracer->GetOutput();
  ExpectExactBooks(out);
  const double reflected = photontest::Field(out, "EnergyInterfaceReflected");
  const double transmitted = photontest::Field(out, "EnergyInterfaceTransmitted");
  const double events = photontest::Field(out, "InterfaceReflections") +
    photontest::Field(out, "InterfaceTransmissions");
  ASSERT_GT(events, 1e5);
  const double r = reflected / (reflected + transmitted);
  const double se = std::sqrt(0.04 * 0.96 / events);
  std::cout << "slab: reflected fraction per event " << r << " (Fresnel 0.04, SE " << se << "), "
            << events << " events\n";
  EXPECT_NEAR(r, 0.04, 4 * se);
  // The glass deposits nothing and absorbs nothing.
  EXPECT_EQ(photontest::Field(out, "EnergySurface"), 0.0);
  EXPECT_EQ(photontest::Field(out, "SurfaceHits"), 0.0);
}

TEST(PhotonInterfaces, PrismReflectsTotally)
{
  // A right-angle prism (n = 1.5), cross-section (x, z) A = (0, 1), B = (1, 1), C = (0, 0),
  // extruded over y in [-1, 1]. A vertical beam enters the top AB at normal incidence, meets the
  // hypotenuse BC at 45 degrees (critical angle 41.8): total internal reflection towards -x, out
  // through the leg AC. A black plane below the hypotenuse sees nothing; a black plane left of
  // the leg receives T / (1 + R) of what enters the top (the series of internal reflections).
  auto points = vtkSmartPointer<vtkPoints>::New();
  const double p[6][3] = { { 0, -1, 1 }, { 1, -1, 1 }, { 0, -1, 0 }, { 0, 1, 1 }, { 1, 1, 1 },
    { 0, 1, 0 } };
  for (const auto& q : p)
  {
    points->InsertNextPoint(q);
  }
  // Outward winding: caps, top, leg, hypotenuse.
  const vtkIdType faces[8][3] = { { 0, 2, 1 }, { 3, 4, 5 }, { 0, 1, 4 }, { 0, 4, 3 }, { 0, 3, 5 },
    { 0, 5, 2 }, { 1, 2, 5 }, { 1, 5, 4 } };
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  for (const auto& f : faces)
  {
    cells->InsertNextCell(3, f);
  }
  auto prism = vtkSmartPointer<vtkPolyData>::New();
  prism->SetPoints(points);
  prism->SetPolys(cells);
  vtkNew<vtkRefractaSurfaceSet> set;
  set->SetTexelSize(0.1);
  set->AddSurface(prism, Glass(1.5));
  // Surface 1: under the hypotenuse (inside the prism's footprint only, so the direct beam
  // cannot reach it); 2: left of the leg; 3: a reference plane in the open beam.
  set->AddSurface(
    photontest::Rectangle({ 0.05, -0.9, -0.5 }, { 0.9, -0.9, -0.5 }, { 0.05, 0.9, -0.5 }), Black());
  set->AddSurface(
    photontest::Rectangle({ -0.3, -1.2, -0.2 }, { -0.3, 1.2, -0.2 }, { -0.3, -1.2, 1.2 }), Black());
  set->AddSurface(photontest::Rectangle({ 1.2, -1, 1 }, { 1.8, -1, 1 }, { 1.2, 1, 1 }), Black());
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(Vacuum());
  tracer->SetSurfaces(set);
  tracer->AddLight(photontest::Directional({ 0, 0, 10 }, { 0, 0, 0 }, 1.0));
  tracer->SetNumberOfPhotons(1 << 20);
  tracer->Update();
  vtkImageData* out = tracer->GetOutput();
  ExpectExactBooks(out);
  const double below = SurfaceFlux(set, out, 1);
  const double left = SurfaceFlux(set, out, 2);
  const double e0 = SurfaceFlux(set, out, 3) / (0.6 * 2.0); // the beam's irradiance
  const double entering = e0 * 2.0;                         // top face: 1 x 2
  const double r = 0.04;
  std::cout << "prism: below the hypotenuse " << below << ", left of the leg " << left / entering
            << " of the beam on the top (T / (1 + R) = " << (1 - r) / (1 + r) << ")\n";
  // Nothing crosses the hypotenuse; only photons that enter within the surface offset of the
  // edge B could pass beside it (none reach this plane, which ends 0.1 before B).
  EXPECT_EQ(below, 0.0);
  EXPECT_NEAR(left / entering, (1 - r) / (1 + r), 0.01);
}

TEST(PhotonInterfaces, SharpBallLensFocus)
{
  // The ball lens of PhotonSurfaces.BallLensFocus (n = 1.5, R = 1, annular aperture of inner
  // radius 0.3), now an exact interface (256 x 128 sphere, smooth normals) in vacuum: the best
  // focus must be the independent Snell trace's within 0.02 R.
  const double radius = 1.0, index = 1.5, aperture = 0.3;
  vtkNew<vtkRefractaSurfaceSet> set;
  set->SetTexelSize(0.01);
  vtkNew<vtkMatrix4x4> move;
  AddBallLens(set, radius, index, aperture);
  set->AddSurface(
    photontest::Rectangle({ -0.5, -0.5, 0 }, { 0.5, -0.5, 0 }, { -0.5, 0.5, 0 }), Black(), move);
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(Vacuum());
  tracer->AddLight(photontest::Directional({ 0, 0, 10 }, { 0, 0, 0 }, 1.0));
  tracer->SetNumberOfPhotons(1 << 19);
  tracer->SetSurfaces(set);
  std::vector<double> distances = { 1.3, 1.4, 1.5, 1.6, 1.7 };
  std::vector<double> rms;
  for (double D : distances)
  {
    move->SetElement(2, 3, -D);
    tracer->Update();
    vtkImageData* out = tracer->GetOutput();
    ExpectExactBooks(out);
    vtkDataArray* e =
      out->GetFieldData()->GetArray(vtkRefractaLightingVolume::SurfaceIrradianceName());
    const auto& info = set->GetTriangleInfo();
    vtkRefractaBVH* bvh = set->GetBVH();
    double m2 = 0, m0 = 0;
    for (vtkIdType k = 0; k < set->GetNumberOfTriangles(); ++k)
    {
      if (info[4 * k + REFRACTA_TRIANGLE_INFO_SURFACE] != 2)
      {
        continue;
      }
      const double* t = &bvh->GetTriangles()[9 * k];
      const int first = info[4 * k], n = info[4 * k + 1];
      for (int i = 0; i < n * n; ++i)
      {
        double c[6];
        vtkRefractaSurfaceSet::GetTexelCorners(i, n, c);
        const double u = (c[0] + c[2] + c[4]) / 3, v = (c[1] + c[3] + c[5]) / 3;
        double x[2];
        for (int a = 0; a < 2; ++a)
        {
          x[a] = (1 - u - v) * t[a] + u * t[3 + a] + v * t[6 + a] + bvh->GetFrameOrigin()[a];
        }
        const double flux =
          photontest::TexelIrradiance(e, first + i) * set->GetTexelAreas()[first + i];
        m2 += flux * (x[0] * x[0] + x[1] * x[1]);
        m0 += flux;
      }
    }
    ASSERT_GT(m0, 0);
    rms.push_back(std::sqrt(m2 / m0));
  }
  size_t best = 0;
  for (size_t i = 1; i < rms.size(); ++i)
  {
    best = rms[i] < rms[best] ? i : best;
  }
  ASSERT_GT(best, 0u);
  ASSERT_LT(best, rms.size() - 1);
  const double x[3] = { distances[best - 1], distances[best], distances[best + 1] };
  const double y[3] = { rms[best - 1], rms[best], rms[best + 1] };
  const double measured = photontest::ParabolaVertex(x, y);
  double sharpBest = 1.0, sharpRms = 1e300;
  for (double D = 1.0; D < 2.5; D += 0.001)
  {
    const double r = photontest::SharpSphereRms(aperture, radius, index, D);
    if (r < sharpRms)
    {
      sharpRms = r;
      sharpBest = D;
    }
  }
  std::cout << "sharp ball lens: RMS spot radius by plane distance:";
  for (size_t i = 0; i < rms.size(); ++i)
  {
    std::cout << " " << distances[i] << ": " << rms[i];
  }
  std::cout << "\nmeasured focus " << measured << ", exact trace " << sharpBest << " (RMS "
            << sharpRms << ")\n";
  EXPECT_NEAR(measured, sharpBest, 0.02 * radius);
  // Away from the focus, where the spot is many texels wide, its size is the trace's.
  for (size_t i : { size_t(0), rms.size() - 1 })
  {
    const double traced = photontest::SharpSphereRms(aperture, radius, index, distances[i]);
    std::cout << "D = " << distances[i] << ": RMS " << rms[i] << ", traced " << traced << "\n";
    EXPECT_NEAR(rms[i], traced, 0.1 * traced);
  }
}

TEST(PhotonInterfaces, TrappedLightEndsAtTheInterfaceCap)
{
  // A point light inside a glass ball (n = 1.5, R = 1), 0.9 R from its centre: a ray leaving it
  // at angle theta to the outward radius keeps meeting the sphere at sin(i) = 0.9 sin(theta), so
  // where 0.9 sin(theta) > 1 / n it circles by total internal reflection for ever. That is a
  // share cos(asin(1 / (0.9 n))) = 0.672 of the isotropic light. With
  // MaximumNumberOfInterfaceEvents = 50 those photons end after 50 events, booked as remaining
  // (step cap), so the pass costs about as many steps as events; without the cap they run to
  // MaximumNumberOfSteps.
  const double index = 1.5, r0 = 0.9;
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(192);
  sphere->SetPhiResolution(96);
  sphere->Update();
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(sphere->GetOutput(), Glass(index));
  auto trace = [&](int cap)
  {
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetInputData(Vacuum());
    tracer->SetSurfaces(set);
    tracer->AddLight(photontest::Positional({ r0, 0, 0 }, { 0, 0, 0 }, 180.0, 1.0, 1.0));
    tracer->SetNumberOfPhotons(1 << 13);
    tracer->SetMaximumNumberOfSteps(400);
    tracer->SetMaximumNumberOfInterfaceEvents(cap);
    tracer->Update();
    auto out = vtkSmartPointer<vtkImageData>::New();
    out->ShallowCopy(tracer->GetOutput());
    return out;
  };
  vtkSmartPointer<vtkImageData> capped = trace(50);
  ExpectExactBooks(capped);
  const double photons = photontest::Field(capped, "PhotonsMarched");
  const double trapped = photontest::Field(capped, "TerminatedStepCap") / photons;
  const double expected = std::sqrt(1.0 - std::pow(1.0 / (r0 * index), 2));
  const double se = std::sqrt(expected * (1 - expected) / photons);
  const double steps = photontest::Field(capped, "TotalSteps");
  std::cout << "trapped share " << trapped << " (expected " << expected << ", SE " << se << "), "
            << steps / photons << " steps per photon\n";
  // Light that is not trapped but starts near the critical angle reflects often (R near 1) and
  // a few such photons also reach 50 events: the share may exceed the trapped one slightly.
  EXPECT_GT(trapped, expected - 4 * se);
  EXPECT_LT(trapped, expected + 0.03);
  EXPECT_LT(steps / photons, 3.0 * 50);

  vtkSmartPointer<vtkImageData> uncapped = trace(100000);
  ExpectExactBooks(uncapped);
  const double uncappedSteps = photontest::Field(uncapped, "TotalSteps");
  std::cout << "without the cap " << uncappedSteps / photons << " steps per photon\n";
  EXPECT_GT(uncappedSteps, 5.0 * steps);
}

namespace
{
// RMS radius about the z axis and flux (first channel) of the irradiance array `e` on the
// triangles of surface `surface`, its texels those of subdivision n c (c = 1: the atlas).
std::array<double, 3> SpotRms(
  vtkRefractaSurfaceSet* set, vtkDataArray* e, int surface, int c, double rEnc)
{
  double enclosed = 0;
  const auto& info = set->GetTriangleInfo();
  vtkRefractaBVH* bvh = set->GetBVH();
  double m2 = 0, m0 = 0;
  for (vtkIdType k = 0; k < set->GetNumberOfTriangles(); ++k)
  {
    if (info[4 * k + REFRACTA_TRIANGLE_INFO_SURFACE] != surface)
    {
      continue;
    }
    const double* t = &bvh->GetTriangles()[9 * k];
    const int first = info[4 * k] * c * c, n = info[4 * k + 1] * c;
    const double area = set->GetTexelAreas()[info[4 * k]] / (c * c);
    for (int i = 0; i < n * n; ++i)
    {
      double corners[6];
      vtkRefractaSurfaceSet::GetTexelCorners(i, n, corners);
      const double u = (corners[0] + corners[2] + corners[4]) / 3;
      const double v = (corners[1] + corners[3] + corners[5]) / 3;
      double x[2];
      for (int a = 0; a < 2; ++a)
      {
        x[a] = (1 - u - v) * t[a] + u * t[3 + a] + v * t[6 + a] + bvh->GetFrameOrigin()[a];
      }
      const double flux = photontest::TexelIrradiance(e, first + i) * area;
      const double r2 = x[0] * x[0] + x[1] * x[1];
      m2 += flux * r2;
      m0 += flux;
      enclosed += r2 < rEnc * rEnc ? flux : 0.0;
    }
  }
  return { m0 > 0 ? std::sqrt(m2 / m0) : 0.0, m0, m0 > 0 ? enclosed / m0 : 0.0 };
}
}

TEST(PhotonInterfaces, CausticAtlasResolvesTheFocus)
{
  // The ball lens of SharpBallLensFocus with its black screen near the best focus: all the light
  // on the screen crossed the glass (caustic photons), so the caustic atlas (c = 4) holds the
  // screen's whole flux, texel by texel within the coarse atlas; its spot is measured at a quarter
  // of the atlas texel and must be the exact trace's; a glass-free scene gets no caustic array.
  const double radius = 1.0, index = 1.5, aperture = 0.3, D = 1.2;
  vtkNew<vtkRefractaSurfaceSet> set;
  set->SetTexelSize(0.02);
  AddBallLens(set, radius, index, aperture);
  set->AddSurface(
    photontest::Rectangle({ -0.5, -0.5, -D }, { 0.5, -0.5, -D }, { -0.5, 0.5, -D }), Black());
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(Vacuum());
  tracer->AddLight(photontest::Directional({ 0, 0, 10 }, { 0, 0, 0 }, 1.0));
  tracer->SetNumberOfPhotons(1 << 19);
  tracer->SetSurfaces(set);
  EXPECT_EQ(tracer->GetCausticSubdivision(), 4); // the default
  // This atlas (517k texels of 0.02) needs 8.3M fine texels at c = 4: above the default budget.
  tracer->SetMaximumNumberOfCausticTexels(vtkIdType(1) << 24);
  tracer->Update();
  EXPECT_EQ(tracer->GetLastCausticSubdivision(), 4);
  vtkImageData* out = tracer->GetOutput();
  ExpectExactBooks(out);
  vtkDataArray* coarse =
    out->GetFieldData()->GetArray(vtkRefractaLightingVolume::SurfaceIrradianceName());
  vtkDataArray* fine =
    out->GetFieldData()->GetArray(vtkRefractaLightingVolume::SurfaceCausticIrradianceName());
  ASSERT_NE(fine, nullptr);
  const vtkIdType texels = set->GetNumberOfTexels();
  ASSERT_EQ(fine->GetNumberOfTuples(), 16 * texels);
  // Books, on each side: every fine texel's flux lies in its coarse texel, and on the screen all
  // of it.
  const auto& info = set->GetTriangleInfo();
  using photontest::SideIrradiance;
  double worst = 0, screen = 0;
  for (vtkIdType k = 0; k < set->GetNumberOfTriangles(); ++k)
  {
    if (info[4 * k + REFRACTA_TRIANGLE_INFO_SURFACE] != 2)
    {
      continue;
    }
    // The fine texels of a triangle (subdivision 4 n) cut each coarse texel into 16: each one's
    // centroid finds its coarse texel.
    const int first = info[4 * k], n = info[4 * k + 1];
    for (int side = 0; side < vtkRefractaLightingVolume::NUMBER_OF_SURFACE_SIDES; ++side)
    {
      std::vector<double> sum(n * n, 0.0);
      for (int f = 0; f < 16 * n * n; ++f)
      {
        double corners[6];
        vtkRefractaSurfaceSet::GetTexelCorners(f, 4 * n, corners);
        const float u = static_cast<float>((corners[0] + corners[2] + corners[4]) / 3);
        const float v = static_cast<float>((corners[1] + corners[3] + corners[5]) / 3);
        sum[vtkRefractaSurfaceSet::TexelIndex(u, v, n)] +=
          SideIrradiance(fine, 16 * first + f, side) / 16;
      }
      for (int i = 0; i < n * n; ++i)
      {
        const double e = SideIrradiance(coarse, first + i, side);
        worst = std::max(worst, std::fabs(sum[i] - e));
        screen = std::max(screen, e);
      }
    }
  }
  EXPECT_LT(worst, 1e-4 * screen);
  // Every photon on the black screen came through the glass (Fresnel's choice by roulette keeps
  // its power) and ended there, so each screen texel's flux is its caustic photon count times the
  // one photon power (the black aperture above the lens counts the light the ball reflects).
  vtkDataArray* counts =
    out->GetFieldData()->GetArray(vtkRefractaLightingVolume::SurfaceCausticPhotonsName());
  ASSERT_NE(counts, nullptr);
  ASSERT_EQ(counts->GetNumberOfTuples(), texels);
  const std::vector<double>& areas = set->GetTexelAreas();
  double landed = 0, lowest = 1e300, highest = 0, uncounted = 0;
  for (vtkIdType k = 0; k < set->GetNumberOfTriangles(); ++k)
  {
    const int first = info[4 * k], n = info[4 * k + 1];
    const bool onScreen = info[4 * k + REFRACTA_TRIANGLE_INFO_SURFACE] == 2;
    for (int t = first; t < first + n * n; ++t)
    {
      for (int side = 0; side < vtkRefractaLightingVolume::NUMBER_OF_SURFACE_SIDES; ++side)
      {
        const double count = vtkRefractaLightingVolume::GetSurfaceSideValue(counts, t, side, 0, 1);
        const double flux = SideIrradiance(coarse, t, side) * areas[t];
        landed += count;
        if (!onScreen || count == 0)
        {
          uncounted += onScreen ? flux : 0.0;
          continue;
        }
        lowest = std::min(lowest, flux / count);
        highest = std::max(highest, flux / count);
      }
    }
  }
  EXPECT_GT(landed, 5000);
  EXPECT_EQ(uncounted, 0.0);
  EXPECT_LT(highest, lowest * (1 + 1e-4));
  // The share of the spot's flux within rEnc of the axis, from the exact trace (a uniform beam
  // of radius `aperture`; Fresnel transmission varies by < 1% over it).
  const double rEnc = 0.03;
  double inside = 0, all = 0;
  for (int i = 0; i < 20000; ++i)
  {
    const double rho = aperture * (i + 0.5) / 20000;
    inside += photontest::SharpSphereRadiusAt(rho, radius, index, D) < rEnc ? rho : 0.0;
    all += rho;
  }
  const double tracedShare = inside / all;
  const auto coarseSpot = SpotRms(set, coarse, 2, 1, rEnc);
  const auto fineSpot = SpotRms(set, fine, 2, 4, rEnc);
  EXPECT_NEAR(fineSpot[1], coarseSpot[1], 1e-5 * coarseSpot[1]);
  const double traced = photontest::SharpSphereRms(aperture, radius, index, D);
  std::cout << "caustic atlas: screen flux " << coarseSpot[1] << ", RMS spot radius coarse "
            << coarseSpot[0] << ", fine " << fineSpot[0] << ", traced " << traced
            << "; flux share within " << rEnc << ": coarse " << coarseSpot[2] << ", fine "
            << fineSpot[2] << ", traced " << tracedShare << "; worst coarse - sum(fine) " << worst
            << " of peak " << screen << "\n";
  EXPECT_NEAR(fineSpot[0], traced, 0.02 * traced);
  EXPECT_NEAR(fineSpot[2], tracedShare, 0.03);

  // Without glass: no caustic photons, no caustic array.
  vtkNew<vtkRefractaSurfaceSet> plain;
  plain->AddSurface(
    photontest::Rectangle({ -0.5, -0.5, -D }, { 0.5, -0.5, -D }, { -0.5, 0.5, -D }), Black());
  tracer->SetSurfaces(plain);
  tracer->Update();
  EXPECT_EQ(tracer->GetOutput()->GetFieldData()->GetArray(
              vtkRefractaLightingVolume::SurfaceCausticIrradianceName()),
    nullptr);
  // The fine texels' budget lowers c for the run: 9.5 per atlas texel allows c = 3.
  tracer->SetSurfaces(set);
  tracer->SetMaximumNumberOfCausticTexels(texels * 19 / 2);
  tracer->Update();
  EXPECT_EQ(tracer->GetLastCausticSubdivision(), 3);
  EXPECT_EQ(tracer->GetOutput()
              ->GetFieldData()
              ->GetArray(vtkRefractaLightingVolume::SurfaceCausticIrradianceName())
              ->GetNumberOfTuples(),
    9 * texels);
  tracer->SetMaximumNumberOfCausticTexels(vtkIdType(1) << 24);
  // c = 1 turns the caustic atlas off.
  tracer->SetSurfaces(set);
  tracer->SetCausticSubdivision(1);
  tracer->Update();
  EXPECT_EQ(tracer->GetOutput()->GetFieldData()->GetArray(
              vtkRefractaLightingVolume::SurfaceCausticIrradianceName()),
    nullptr);
}
