// Analog scattering of the photon pass with surfaces (vtkPhotonTracer::AnalogScattering, issue
// #13): in a closed white box the books close with nothing handed to a lattice (EnergyScattered
// 0), all power ends absorbed in the medium, and the scattered power in the output arrays,
// sum (S1 + S_ms) dV, is a / (1 - a) times the absorbed power, as it must be for a grey albedo a;
// chunked and unchunked runs agree exactly; the single-scattering source S1 keeps its expected
// value (it equals the deterministic pass's within the photon noise); the light the fog scatters
// reaches a floor; a rotated and moved medium (direction matrix, origin) with its floor and light
// moved alike gives the floor the same irradiance; and the mode switches itself off without
// surfaces or without a scattering medium.
#include "PhotonTestUtilities.h"

#include "vtkCubeSource.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"

#include "vtkPhotonTracer.h"
#include "vtkPlaneSource.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>

namespace
{
constexpr double SPACING = 0.25;
constexpr int N = 12;

// A grey medium (sigma_t, albedo) with a uniform Henyey-Greenstein g.
vtkSmartPointer<vtkImageData> Fog(double sigmaT, double albedo, double g)
{
  auto medium = photontest::MakeMedium(N, N, N, SPACING,
    [&](double, double, double)
    {
      photontest::Voxel v;
      v.Extinction = { sigmaT, sigmaT, sigmaT };
      v.Albedo = { albedo, albedo, albedo };
      return v;
    });
  vtkNew<vtkFloatArray> anisotropy;
  anisotropy->SetName(vtkRefractaMedium::AnisotropyName());
  anisotropy->SetNumberOfTuples(medium->GetNumberOfPoints());
  anisotropy->Fill(g);
  medium->GetPointData()->AddArray(anisotropy);
  return medium;
}

// Sum over the voxels of a 3-component point array (first channel) times the voxel volume.
double Integral(vtkImageData* image, const char* name)
{
  vtkDataArray* a = image->GetPointData()->GetArray(name);
  if (!a)
  {
    return -1;
  }
  double sum = 0;
  for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
  {
    sum += a->GetComponent(t, 0);
  }
  return sum * SPACING * SPACING * SPACING;
}

// Power deposited on the surfaces (first channel, both sides): sum of irradiance x texel area.
double SurfaceFlux(vtkRefractaSurfaceSet* set, vtkImageData* image)
{
  vtkDataArray* e =
    image->GetFieldData()->GetArray(vtkRefractaLightingVolume::SurfaceIrradianceName());
  if (!e)
  {
    return -1;
  }
  double sum = 0;
  for (vtkIdType t = 0; t < e->GetNumberOfTuples(); ++t)
  {
    sum += photontest::TexelIrradiance(e, t) * set->GetTexelAreas()[t];
  }
  return sum;
}

// A grey floor y = 0.3 across the fog (and beyond it) of the given albedo.
vtkSmartPointer<vtkRefractaSurfaceSet> Floor(double albedo)
{
  auto set = vtkSmartPointer<vtkRefractaSurfaceSet>::New();
  vtkNew<vtkRefractaSurfaceMaterial> material;
  material->SetAlbedo(albedo, albedo, albedo);
  set->AddSurface(photontest::Rectangle({ -1, 0.3, -1 }, { 4, 0.3, -1 }, { -1, 0.3, 4 }), material);
  return set;
}

vtkSmartPointer<vtkRefractaSurfaceSet> WhiteBox()
{
  auto set = vtkSmartPointer<vtkRefractaSurfaceSet>::New();
  vtkNew<vtkRefractaSurfaceMaterial> white;
  white->SetAlbedo(1, 1, 1);
  vtkNew<vtkCubeSource> box;
  box->SetBounds(-0.4, 3.15, -0.4, 3.15, -0.4, 3.15);
  box->Update();
  set->AddSurface(box->GetOutput(), white);
  return set;
}
}

TEST(PhotonAnalogScattering, WhiteBoxConservesPower)
{
  const double a = 0.8;
  auto medium = Fog(1.0, a, 0.5);
  auto set = WhiteBox();
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(medium);
  tracer->SetSurfaces(set);
  tracer->AnalogScatteringOn();
  tracer->AddLight(photontest::Positional({ 1.4, 1.3, 1.5 }, { 0, 0, 0 }, 180, 0, 1.0));
  tracer->SetNumberOfPhotons(1 << 13);
  tracer->SetRouletteThreshold(0.01); // fewer bounces: roulette is unbiased, the books hold
  tracer->Update();
  ASSERT_TRUE(tracer->GetUsedAnalogScattering());
  vtkNew<vtkImageData> whole;
  whole->DeepCopy(tracer->GetOutput());
  const auto emitted = photontest::Energy(whole, "EnergyEmitted");
  const auto absorbed = photontest::Energy(whole, "EnergyAbsorbed");
  const auto surface = photontest::Energy(whole, "EnergySurface");
  const auto escaped = photontest::Energy(whole, "EnergyEscaped");
  const auto scattered = photontest::Energy(whole, "EnergyScattered");
  const auto remaining = photontest::Energy(whole, "EnergyRemaining");
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_EQ(scattered[c], 0.0) << "nothing is handed to a lattice";
    EXPECT_NEAR(absorbed[c] + surface[c] + escaped[c] + remaining[c], emitted[c], 1e-4 * emitted[c])
      << "channel " << c;
    EXPECT_LT(surface[c], 1e-6 * emitted[c]) << "white walls absorb nothing";
    EXPECT_LT(escaped[c], 1e-3 * emitted[c]) << "the box is closed";
  }
  // Every collision scatters a and absorbs 1 - a of the power it takes.
  const double s1 = Integral(whole, vtkRefractaLightingVolume::RadianceName());
  const double sms = Integral(whole, vtkRefractaLightingVolume::MultipleScatteringName());
  std::cout << "emitted " << emitted[0] << ", absorbed " << absorbed[0] << ", remaining "
            << remaining[0] << "; sum S1 dV " << s1 << ", sum S_ms dV " << sms
            << ", (S1 + S_ms) / (a / (1 - a) absorbed) = "
            << (s1 + sms) / (a / (1 - a) * absorbed[0]) << std::endl;
  EXPECT_NEAR(s1 + sms, a / (1 - a) * absorbed[0], 1e-3 * a / (1 - a) * absorbed[0]);
  EXPECT_GT(sms, s1) << "between white walls most scattered light has scattered before";
  EXPECT_NEAR(absorbed[0], emitted[0], 0.01 * emitted[0]) << "the medium takes all in the end";

  // The chunked kernel keeps each photon's order between launches: the same deposits.
  tracer->SetStepsPerChunk(64);
  tracer->Update();
  vtkImageData* chunked = tracer->GetOutput();
  EXPECT_EQ(
    photontest::Energy(chunked, "EnergyAbsorbed"), photontest::Energy(whole, "EnergyAbsorbed"));
  EXPECT_EQ(Integral(chunked, vtkRefractaLightingVolume::MultipleScatteringName()), sms);
  EXPECT_EQ(Integral(chunked, vtkRefractaLightingVolume::RadianceName()), s1);
}

TEST(PhotonAnalogScattering, SingleScatteringStaysUnbiasedAndScatteredLightReachesTheFloor)
{
  // Fog over a black floor inside it under a spot light: the floor absorbs all it receives.
  auto medium = Fog(1.5, 0.8, 0.3);
  auto set = Floor(0.0);
  auto run =
    [&](vtkRefractaSurfaceSet* surfaces, bool analog, double& s1, double& floorFlux, double& sms)
  {
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetInputData(medium);
    tracer->SetSurfaces(surfaces);
    tracer->SetAnalogScattering(analog);
    tracer->AddLight(
      photontest::Positional({ 1.375, 6.0, 1.375 }, { 1.375, 0, 1.375 }, 20, 1, 3.0));
    tracer->SetNumberOfPhotons(1 << 17);
    tracer->Update();
    vtkImageData* out = tracer->GetOutput();
    EXPECT_EQ(tracer->GetUsedAnalogScattering(), analog);
    s1 = Integral(out, vtkRefractaLightingVolume::RadianceName());
    sms = Integral(out, vtkRefractaLightingVolume::MultipleScatteringName());
    floorFlux = SurfaceFlux(surfaces, out);
    // A black floor absorbs what it receives: the atlas and the books must agree.
    const double absorbed = photontest::Energy(out, "EnergySurface")[0];
    EXPECT_NEAR(floorFlux, absorbed, 1e-4 * absorbed);
  };
  double s1Det, fluxDet, smsDet, s1Ana, fluxAna, smsAna;
  run(set, false, s1Det, fluxDet, smsDet);
  run(set, true, s1Ana, fluxAna, smsAna);
  std::cout << "sum S1 dV: deterministic " << s1Det << ", analog " << s1Ana << " (ratio "
            << s1Ana / s1Det << "); flux on the floor: deterministic " << fluxDet << ", analog "
            << fluxAna << " (ratio " << fluxAna / fluxDet << ")" << std::endl;
  EXPECT_NEAR(s1Ana / s1Det, 1.0, 0.01) << "S1 is the same expected value either way";
  EXPECT_EQ(smsDet, -1) << "no S_ms array without analog scattering";
  EXPECT_GT(smsAna, 0);
  EXPECT_GT(fluxAna, 1.5 * fluxDet) << "scattered light must reach the floor";
}

// With every order by photons, MultipleScatteringDirection is the multiply scattered light's flux
// over its fluence F / phi_ms: never longer than 1; in the fog just above a black floor, where
// nothing comes back up, it points down (measured: mean y -0.51); above a white floor, whose
// reflected light counts with S_ms (diffuse light, no beam from a light), the floor's light going
// up balances the fog's coming down (-0.03). S1 then holds only the beams from the light: the
// same values over either floor.
TEST(PhotonAnalogScattering, MultipleScatteringDirectionFollowsTheNetFlux)
{
  auto medium = Fog(1.5, 0.8, 0.3);
  // Mean y component of F / phi over the voxels (i, 2, k), i, k in 3..8 (centres 0.2 above the
  // floor y = 0.3 of albedo `albedo`), under a spot light aimed down; S1 into `s1`.
  auto meanY = [&](double albedo, std::vector<double>& s1)
  {
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetInputData(medium);
    tracer->SetSurfaces(Floor(albedo));
    tracer->AnalogScatteringOn();
    tracer->AddLight(
      photontest::Positional({ 1.375, 6.0, 1.375 }, { 1.375, 0, 1.375 }, 20, 1, 3.0));
    tracer->SetNumberOfPhotons(1 << 16);
    tracer->Update();
    vtkPointData* pd = tracer->GetOutput()->GetPointData();
    vtkDataArray* radiance = pd->GetArray(vtkRefractaLightingVolume::RadianceName());
    s1.assign(radiance ? 3 * radiance->GetNumberOfTuples() : 0, 0.0);
    for (size_t i = 0; i < s1.size(); ++i)
    {
      s1[i] = radiance->GetComponent(static_cast<vtkIdType>(i / 3), static_cast<int>(i % 3));
    }
    vtkDataArray* f = pd->GetArray(vtkRefractaLightingVolume::MultipleScatteringDirectionName());
    EXPECT_NE(f, nullptr);
    if (!f)
    {
      return 0.0;
    }
    double longest = 0;
    for (vtkIdType t = 0; t < f->GetNumberOfTuples(); ++t)
    {
      double v[3];
      f->GetTuple(t, v);
      EXPECT_TRUE(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]));
      longest = std::max(longest, vtkMath::Norm(v));
    }
    EXPECT_LE(longest, 1.0 + 1e-6);
    double mean = 0;
    for (int k = 3; k <= 8; ++k)
    {
      for (int i = 3; i <= 8; ++i)
      {
        mean += f->GetComponent(i + N * (2 + N * k), 1) / 36;
      }
    }
    return mean;
  };
  std::vector<double> s1Black, s1White;
  const double black = meanY(0.0, s1Black), white = meanY(1.0, s1White);
  std::cout << "F / phi 0.2 above the floor, mean y: black floor " << black << ", white floor "
            << white << std::endl;
  EXPECT_LT(black, -0.3) << "the light above a black floor travels down";
  EXPECT_GT(white, black + 0.3) << "a white floor sends its reflection back up";
  ASSERT_FALSE(s1Black.empty());
  EXPECT_EQ(s1White, s1Black) << "S1 holds the light's own beams, whatever the floor reflects";
}

TEST(PhotonAnalogScattering, OffWithoutSurfacesOrScattering)
{
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(Fog(1.0, 0.8, 0.0));
  tracer->AnalogScatteringOn();
  tracer->AddLight(photontest::Positional({ 1.4, 6, 1.5 }, { 1.4, 0, 1.5 }, 20, 0, 1.0));
  tracer->SetNumberOfPhotons(1 << 12);
  tracer->Update();
  EXPECT_FALSE(tracer->GetUsedAnalogScattering()) << "no surfaces: the lattice's job";
  EXPECT_GT(photontest::Energy(tracer->GetOutput(), "EnergyScattered")[0], 0.0);
  tracer->SetInputData(Fog(1.0, 0.0, 0.0));
  tracer->SetSurfaces(WhiteBox());
  tracer->Update();
  EXPECT_FALSE(tracer->GetUsedAnalogScattering()) << "nothing scatters";
  EXPECT_EQ(tracer->GetOutput()->GetPointData()->GetArray(
              vtkRefractaLightingVolume::MultipleScatteringName()),
    nullptr);
}

TEST(PhotonAnalogScattering, RotatedAndMovedMediumLightsTheFloorTheSame)
{
  // The same scene twice: fog over a floor inside it under a spot light, once with the grid at the
  // origin and axis-aligned, once with the grid rotated (a direction matrix) and moved (an origin)
  // and the floor and the light moved with it. The floor's texels correspond one to one (same
  // mesh up to the rigid map, fixed texel size); its irradiance must agree within photon noise.
  const double angle = vtkMath::RadiansFromDegrees(40.0);
  double axis[3] = { 1, 2, 3 };
  vtkMath::Normalize(axis);
  vtkNew<vtkTransform> rigid;
  rigid->Translate(10, -5, 3);
  rigid->RotateWXYZ(vtkMath::DegreesFromRadians(angle), axis);
  auto place = [&](bool moved, vtkSmartPointer<vtkImageData>& medium, vtkRefractaSurfaceSet* set,
                 std::array<double, 3>& light, std::array<double, 3>& aim)
  {
    medium = Fog(0.8, 0.8, 0.3);
    vtkNew<vtkPlaneSource> floor;
    floor->SetOrigin(-1, 0.6, -1);
    floor->SetPoint1(4, 0.6, -1);
    floor->SetPoint2(-1, 0.6, 4);
    floor->SetResolution(4, 4);
    floor->Update();
    light = { 1.375, 5.0, 1.375 };
    aim = { 1.375, 0.0, 1.375 };
    vtkNew<vtkTransformPolyDataFilter> moveFloor;
    moveFloor->SetInputConnection(floor->GetOutputPort());
    moveFloor->SetTransform(rigid);
    moveFloor->Update();
    if (moved)
    {
      double direction[9];
      vtkNew<vtkMatrix4x4> m;
      rigid->GetMatrix(m);
      for (int r = 0; r < 3; ++r)
      {
        for (int c = 0; c < 3; ++c)
        {
          direction[3 * r + c] = m->GetElement(r, c);
        }
      }
      medium->SetDirectionMatrix(direction);
      medium->SetOrigin(m->GetElement(0, 3), m->GetElement(1, 3), m->GetElement(2, 3));
      rigid->TransformPoint(light.data(), light.data());
      rigid->TransformPoint(aim.data(), aim.data());
    }
    vtkNew<vtkRefractaSurfaceMaterial> grey;
    grey->SetAlbedo(0.5, 0.5, 0.5);
    set->AddSurface(moved ? moveFloor->GetOutput() : floor->GetOutput(), grey);
    set->SetTexelSize(0.1);
  };
  // Flux per cell of a 10 x 10 grid over the floor's own (x, z) in the axis-aligned frame: the
  // texels of each run, their centres mapped back by the inverse of the rigid map when moved.
  const int cells = 10;
  std::vector<double> flux[2];
  double total[2] = { 0, 0 };
  vtkNew<vtkTransform> back;
  back->DeepCopy(rigid);
  back->Inverse();
  for (int moved = 0; moved < 2; ++moved)
  {
    vtkSmartPointer<vtkImageData> medium;
    vtkNew<vtkRefractaSurfaceSet> set;
    std::array<double, 3> light, aim;
    place(moved == 1, medium, set, light, aim);
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetInputData(medium);
    tracer->SetSurfaces(set);
    tracer->AnalogScatteringOn();
    tracer->AddLight(photontest::Positional(light, aim, 25, 1, 3.0));
    tracer->SetNumberOfPhotons(1 << 16);
    tracer->Update();
    vtkDataArray* irradiance = tracer->GetOutput()->GetFieldData()->GetArray(
      vtkRefractaLightingVolume::SurfaceIrradianceName());
    ASSERT_NE(irradiance, nullptr);
    flux[moved].assign(cells * cells, 0.0);
    vtkRefractaBVH* bvh = set->GetBVH();
    const auto& info = set->GetTriangleInfo();
    for (vtkIdType k = 0; k < set->GetNumberOfTriangles(); ++k)
    {
      const double* v = &bvh->GetTriangles()[9 * k];
      const int first = info[4 * k], n = info[4 * k + 1];
      for (int i = 0; i < n * n; ++i)
      {
        double c[6];
        vtkRefractaSurfaceSet::GetTexelCorners(i, n, c);
        const double u = (c[0] + c[2] + c[4]) / 3, w = (c[1] + c[3] + c[5]) / 3;
        double centre[3];
        for (int a = 0; a < 3; ++a)
        {
          centre[a] = (1 - u - w) * v[a] + u * v[3 + a] + w * v[6 + a] + bvh->GetFrameOrigin()[a];
        }
        if (moved)
        {
          back->TransformPoint(centre, centre);
        }
        const int cx = std::min(cells - 1, std::max(0, static_cast<int>((centre[0] + 1) / 0.5)));
        const int cz = std::min(cells - 1, std::max(0, static_cast<int>((centre[2] + 1) / 0.5)));
        const double f =
          photontest::TexelIrradiance(irradiance, first + i) * set->GetTexelAreas()[first + i];
        flux[moved][cx + cells * cz] += f;
        total[moved] += f;
      }
    }
  }
  double worst = 0, brightest = 0;
  for (int c = 0; c < cells * cells; ++c)
  {
    worst = std::max(worst, std::abs(flux[1][c] - flux[0][c]));
    brightest = std::max(brightest, flux[0][c]);
  }
  std::cout << "floor flux: axis-aligned " << total[0] << ", rotated and moved " << total[1]
            << " (ratio " << total[1] / total[0] << "); largest difference of a 0.5 x 0.5 cell "
            << 100 * worst / brightest << "% of the brightest cell" << std::endl;
  EXPECT_NEAR(total[1] / total[0], 1.0, 0.01);
  EXPECT_LT(worst, 0.01 * brightest);
}

// Analog scattering without surfaces (the first-collision split and EVERY_ORDER, issue 14) in a
// refracting fog: curved photons leave the medium's box and are not taken for inside again (a
// photon on the box's face once stepped nowhere until the step cap), so no photon ends at the
// step cap or invalid, and the books close with the power handed to the lattice (split) or none
// (every order).
TEST(PhotonAnalogScattering, OrdersWithoutSurfacesInARefractingFog)
{
  auto fog = photontest::MakeMedium(N, N, N, SPACING,
    [&](double x, double, double)
    {
      photontest::Voxel v;
      v.N = 1.0 + 0.2 * x; // a gradient: curved rays
      v.Extinction = { 1.0, 1.0, 1.0 };
      v.Albedo = { 0.9, 0.9, 0.9 };
      return v;
    });
  for (int orders : { 2, static_cast<int>(vtkPhotonTracer::EVERY_ORDER) })
  {
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetInputData(fog);
    tracer->AddLight(photontest::Positional({ 1.4, 6, 1.5 }, { 1.4, 0, 1.5 }, 20, 0, 1.0));
    tracer->SetNumberOfPhotons(1 << 12);
    tracer->SetScatteringOrders(orders);
    tracer->Update();
    vtkImageData* out = tracer->GetOutput();
    ASSERT_TRUE(tracer->GetUsedCurvedRays());
    EXPECT_EQ(tracer->GetUsedScatteringOrders(), orders);
    EXPECT_EQ(out->GetFieldData()->GetArray("TerminatedStepCap")->GetTuple1(0), 0.0);
    EXPECT_EQ(out->GetFieldData()->GetArray("TerminatedInvalid")->GetTuple1(0), 0.0);
    const double emitted = photontest::Energy(out, "EnergyEmitted")[0];
    const double handed = photontest::Energy(out, "EnergyScattered")[0];
    const double books = photontest::Energy(out, "EnergyAbsorbed")[0] +
      photontest::Energy(out, "EnergyEscaped")[0] + handed +
      photontest::Energy(out, "EnergyRemaining")[0];
    EXPECT_NEAR(books, emitted, 1e-4 * emitted);
    if (orders > 0)
    {
      EXPECT_GT(handed, 0.0);
      EXPECT_NE(
        out->GetPointData()->GetArray(vtkRefractaLightingVolume::MultipleScatteringSourceName()),
        nullptr);
    }
    else
    {
      EXPECT_EQ(handed, 0.0);
    }
  }
}
