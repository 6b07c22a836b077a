// The volume caustic of vtkPhotonTracer (VolumeCausticSubdivision; Documentation/Physics.md
// "Volume caustics"): a sharp glass ball lens (n = 1.5, R = 1) under a beam through a hole of
// radius 0.3 focuses its light in a thin fog (sigma_t 0.1, albedo 1) on a 0.125 grid.
// - The bricks change where S1 is stored, nothing else: every book and counter equals a run
//   without them (same seed; a budget too small for any brick, so the same pilot and kernels),
//   and each voxel's Radiance without bricks equals its Radiance plus the mean of its brick with
//   them (smoothing off), to fixed-point rounding; the lattice's source
//   (vtkRefractaLightingVolume::ReadLatticeSource) takes the bricks' light back into its voxels.
// - The bricks resolve the focus: the RMS radius of S1 about the axis in the fine layer of each
//   plane follows an independent Snell trace of the beam (SharpSphereTrace.h) within 15% down to
//   the fine voxels' own floor, where the voxels stay at theirs (4x wider).
// - Off where it must be: no interfaces, a chunked march, a budget too small for any brick.
#include "PhotonTestUtilities.h"
#include "SharpSphereTrace.h"

#include "vtkDiskSource.h"
#include "vtkFieldData.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

namespace
{
const double Radius = 1.0, Index = 1.5, Aperture = 0.3, H = 0.125;
const int N = 24; // grid points per axis
const double Window = 0.2; // the shaft's voxels: 4 x 4 about the axis

// The fog: 24^3 points of spacing 0.125 around the ball and its focus (z from -2.44 to 0.44).
vtkSmartPointer<vtkImageData> Fog()
{
  auto medium = photontest::MakeMedium(N, N, N, H,
    [](double, double, double)
    {
      photontest::Voxel v;
      v.Extinction = { 0.1, 0.1, 0.1 };
      v.Albedo = { 1, 1, 1 };
      return v;
    });
  medium->SetOrigin(-0.5 * (N - 1) * H, -0.5 * (N - 1) * H, -2.4375);
  return medium;
}

// The glass ball at the origin under a black disk at z = 1.3 with a hole of radius Aperture.
vtkSmartPointer<vtkRefractaSurfaceSet> BallLens()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(Radius);
  sphere->SetThetaResolution(256);
  sphere->SetPhiResolution(128);
  sphere->Update();
  vtkNew<vtkDiskSource> disk;
  disk->SetInnerRadius(Aperture);
  disk->SetOuterRadius(2.5); // beyond the box's corners
  disk->SetCircumferentialResolution(96);
  disk->SetCenter(0, 0, 1.3);
  disk->Update();
  vtkNew<vtkRefractaSurfaceMaterial> glass, black;
  glass->SetKindToDielectric();
  glass->SetIndexInside(Index);
  glass->SetIndexOutside(1.0);
  black->SetAlbedo(0, 0, 0);
  auto set = vtkSmartPointer<vtkRefractaSurfaceSet>::New();
  set->SetTexelSize(0.05);
  set->AddSurface(sphere->GetOutput(), glass);
  set->AddSurface(disk->GetOutput(), black);
  return set;
}

struct TracerRun
{
  vtkSmartPointer<vtkImageData> Output;
  int Subdivision = 1;
  vtkIdType Bricks = 0;
};

TracerRun Trace(int subdivision, vtkRefractaSurfaceSet* set, int chunk = 0, vtkIdType budget = 1 << 20)
{
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(Fog());
  tracer->AddLight(photontest::Directional({ 0, 0, 10 }, { 0, 0, 0 }, 1.0));
  tracer->SetNumberOfPhotons(1 << 18);
  tracer->SetSurfaces(set);
  tracer->AnalogScatteringOn();
  tracer->SmoothingOff();
  tracer->SetStepsPerChunk(chunk);
  tracer->SetVolumeCausticSubdivision(subdivision);
  tracer->SetMaximumNumberOfVolumeCausticVoxels(budget);
  // About 3000 photons pass the hole (the directional light's footprint also covers the disk):
  // bricks where an estimated 2 pieces per fine voxel pass, the whole shaft.
  tracer->SetVolumeCausticPiecesPerFineVoxel(2.0);
  tracer->Update();
  TracerRun r;
  r.Output = tracer->GetOutput();
  r.Subdivision = tracer->GetLastVolumeCausticSubdivision();
  r.Bricks = tracer->GetLastNumberOfVolumeCausticBricks();
  return r;
}

// The ball lens traced once without bricks (a budget of 7 fine voxels: not one brick of 2^3 fits,
// so the pilot runs and places none) and once with them; shared by the tests below.
const TracerRun& Plain()
{
  static const TracerRun run = Trace(4, BallLens(), 0, 7);
  return run;
}

const TracerRun& Bricked()
{
  static const TracerRun run = Trace(4, BallLens());
  return run;
}

vtkDataArray* Field(vtkImageData* out, const char* name)
{
  return out->GetFieldData()->GetArray(name);
}

// RMS distance from the axis of S1 (red) in the layer of height z, over the voxels whose centres
// lie within Window of the axis (the shaft; light the ball reflects sideways stays out): Radiance
// at the voxel centres of the voxel layer containing z plus, where `fine`, each brick's fine
// voxels of the fine layer containing z at their centres.
double LayerRms(vtkImageData* out, double z, bool fine)
{
  vtkDataArray* s1 = out->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName());
  vtkDataArray* bricks = Field(out, vtkRefractaLightingVolume::VolumeCausticBricksName());
  vtkDataArray* values = Field(out, vtkRefractaLightingVolume::VolumeCausticRadianceName());
  const double* o = out->GetOrigin();
  const int c = fine ? vtkRefractaLightingVolume::GetVolumeCausticSubdivision(out) : 1;
  const double u = (z - o[2]) / H + 0.5; // voxel units, voxel k spans [k, k + 1)
  const int k = static_cast<int>(std::floor(u));
  const int kf = std::min(c - 1, static_cast<int>((u - k) * c));
  double m0 = 0, m2 = 0;
  for (int j = 0; j < N; ++j)
  {
    for (int i = 0; i < N; ++i)
    {
      const vtkIdType v = i + N * (j + N * static_cast<vtkIdType>(k));
      const double x = o[0] + i * H, y = o[1] + j * H;
      if (x * x + y * y > Window * Window)
      {
        continue;
      }
      const double coarse = s1->GetComponent(v, 0);
      m0 += coarse;
      m2 += coarse * (x * x + y * y);
      const int b = c > 1 ? static_cast<int>(bricks->GetComponent(v, 0)) : -1;
      for (int fj = 0; b >= 0 && fj < c; ++fj)
      {
        for (int fi = 0; fi < c; ++fi)
        {
          // A fine voxel holds 1 / c^3 of a voxel's volume; its layer is 1 / c of the voxel's.
          const double w =
            values->GetComponent(b * vtkIdType(c) * c * c + (kf * c + fj) * c + fi, 0) / (c * c);
          const double xf = x + ((fi + 0.5) / c - 0.5) * H, yf = y + ((fj + 0.5) / c - 0.5) * H;
          m0 += w;
          m2 += w * (xf * xf + yf * yf);
        }
      }
    }
  }
  return m0 > 0 ? std::sqrt(m2 / m0) : 0.0;
}
}

TEST(PhotonVolumeCaustic, BricksMoveLightWithoutChangingIt)
{
  const TracerRun& plain = Plain();
  const TracerRun& bricked = Bricked();
  EXPECT_EQ(plain.Subdivision, 1);
  EXPECT_EQ(Field(plain.Output, vtkRefractaLightingVolume::VolumeCausticBricksName()), nullptr);
  ASSERT_EQ(bricked.Subdivision, 4);
  ASSERT_GT(bricked.Bricks, 0);
  vtkDataArray* bricks = Field(bricked.Output, vtkRefractaLightingVolume::VolumeCausticBricksName());
  vtkDataArray* fine = Field(bricked.Output, vtkRefractaLightingVolume::VolumeCausticRadianceName());
  vtkDataArray* direction =
    Field(bricked.Output, vtkRefractaLightingVolume::VolumeCausticRadianceDirectionName());
  ASSERT_NE(bricks, nullptr);
  ASSERT_NE(fine, nullptr);
  ASSERT_NE(direction, nullptr);
  ASSERT_EQ(bricks->GetNumberOfTuples(), N * N * N);
  ASSERT_EQ(fine->GetNumberOfTuples(), bricked.Bricks * 64);
  ASSERT_EQ(direction->GetNumberOfTuples(), bricked.Bricks * 64);
  EXPECT_EQ(bricks->GetRange(0)[1], bricked.Bricks - 1);
  std::cout << bricked.Bricks << " bricks of 4^3\n";

  // The same books and counters: the pilot's march is cleared, the main march is unchanged.
  for (const char* book : { "EnergyEmitted", "EnergyAbsorbed", "EnergyEscaped", "EnergyScattered",
         "EnergySurface", "EnergyRemaining", "EnergyInterfaceTransmitted" })
  {
    const auto a = photontest::Energy(plain.Output, book);
    const auto b = photontest::Energy(bricked.Output, book);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(a[c], b[c], 1e-12 + 1e-9 * std::abs(a[c])) << book;
    }
  }
  for (const char* counter : { "PhotonsMarched", "TotalSteps", "TotalVoxelPieces", "SurfaceHits" })
  {
    EXPECT_EQ(Field(plain.Output, counter)->GetTuple1(0), Field(bricked.Output, counter)->GetTuple1(0))
      << counter;
  }

  // Each voxel's S1 is its Radiance plus its brick's mean.
  vtkDataArray* r1 = plain.Output->GetPointData()->GetArray("Radiance");
  vtkDataArray* r4 = bricked.Output->GetPointData()->GetArray("Radiance");
  const double peak = r1->GetRange(0)[1];
  ASSERT_GT(peak, 0);
  double moved = 0, worst = 0;
  for (vtkIdType v = 0; v < N * N * N; ++v)
  {
    const int b = static_cast<int>(bricks->GetComponent(v, 0));
    for (int c = 0; c < 3; ++c)
    {
      double mean = 0;
      for (int f = 0; b >= 0 && f < 64; ++f)
      {
        mean += fine->GetComponent(b * 64 + f, c) / 64;
      }
      moved += c == 0 ? mean : 0.0;
      worst = std::max(worst, std::abs(r4->GetComponent(v, c) + mean - r1->GetComponent(v, c)));
    }
  }
  EXPECT_LE(worst, 1e-5 * peak);
  EXPECT_GT(moved, 0.0);

  // A lattice solve takes all of S1 back: the bricked run's lattice source is the plain run's S1,
  // and its directions are unit vectors where light was deposited.
  std::vector<float> source, sourceDirection, plainSource, plainDirection;
  vtkRefractaLightingVolume::ReadLatticeSource(bricked.Output, source, sourceDirection);
  vtkRefractaLightingVolume::ReadLatticeSource(plain.Output, plainSource, plainDirection);
  ASSERT_EQ(source.size(), plainSource.size());
  double worstSource = 0, worstUnit = 0;
  for (size_t i = 0; i < source.size(); i += 3)
  {
    for (int c = 0; c < 3; ++c)
    {
      worstSource = std::max(worstSource, double(std::abs(source[i + c] - plainSource[i + c])));
    }
    if (source[i] > 1e-3 * peak)
    {
      const float* d = sourceDirection.data() + i;
      const double length =
        std::sqrt(double(d[0]) * d[0] + double(d[1]) * d[1] + double(d[2]) * d[2]);
      worstUnit = std::max(worstUnit, std::abs(length - 1.0));
    }
  }
  EXPECT_LE(worstSource, 1e-5 * peak);
  EXPECT_LE(worstUnit, 1e-5);
}

TEST(PhotonVolumeCaustic, BricksResolveTheFocus)
{
  const TracerRun& plain = Plain();
  const TracerRun& bricked = Bricked();
  ASSERT_EQ(bricked.Subdivision, 4);
  // Planes from just below the ball through the focus (traced: 1.51) and beyond. The axis runs
  // along voxel (and fine-voxel) corners, so a field sampled at centres spaced s cannot show an
  // RMS radius below sqrt(2) s / 2: 0.022 for the bricks' fine voxels, 0.088 for the voxels.
  const double fineFloor = std::sqrt(2.0) * H / 8, voxelFloor = std::sqrt(2.0) * H / 2;
  for (double D : { 1.2, 1.35, 1.5, 1.65 })
  {
    const double traced = photontest::SharpSphereRms(Aperture, Radius, Index, D);
    const double fine = LayerRms(bricked.Output, -D, true);
    const double coarse = LayerRms(plain.Output, -D, false);
    std::cout << "D = " << D << ": RMS radius traced " << traced << ", bricks " << fine
              << ", voxels " << coarse << "\n";
    const double expected = std::max(traced, fineFloor);
    EXPECT_NEAR(fine, expected, 0.15 * expected) << "D = " << D;
    EXPECT_GE(coarse, 0.99 * voxelFloor) << "D = " << D;
  }
}

TEST(PhotonVolumeCaustic, OffWhereItCannotApply)
{
  // No dielectric interface: no caustic photons, nothing allocated.
  vtkNew<vtkRefractaSurfaceSet> none;
  const TracerRun noGlass = Trace(4, none);
  EXPECT_EQ(noGlass.Subdivision, 1);
  EXPECT_EQ(Field(noGlass.Output, vtkRefractaLightingVolume::VolumeCausticBricksName()), nullptr);
  // A chunked march hands its deposits on while photons fly: no bricks.
  const TracerRun chunked = Trace(4, BallLens(), 64);
  EXPECT_EQ(chunked.Subdivision, 1);
  EXPECT_EQ(Field(chunked.Output, vtkRefractaLightingVolume::VolumeCausticBricksName()), nullptr);
  // A budget below one brick of 2^3: none placed (the plain run of the tests above).
  EXPECT_EQ(Plain().Subdivision, 1);
  EXPECT_EQ(Plain().Bricks, 0);
  EXPECT_EQ(Field(Plain().Output, vtkRefractaLightingVolume::VolumeCausticRadianceName()), nullptr);
  // A NaN threshold is refused by name (by its setter, which keeps the value).
  vtkNew<vtkPhotonTracer> tracer;
  vtkNew<vtkTest::ErrorObserver> errors;
  tracer->AddObserver(vtkCommand::ErrorEvent, errors);
  const double pieces = tracer->GetVolumeCausticPiecesPerFineVoxel();
  tracer->SetVolumeCausticPiecesPerFineVoxel(std::nan(""));
  EXPECT_EQ(tracer->GetVolumeCausticPiecesPerFineVoxel(), pieces);
  EXPECT_NE(errors->GetErrorMessage().find("VolumeCausticPiecesPerFineVoxel"), std::string::npos)
    << errors->GetErrorMessage();
}
