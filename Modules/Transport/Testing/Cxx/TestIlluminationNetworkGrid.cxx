// The illumination network against the grid path on the same particle cloud: the cloud is
// deposited on a fine grid (vtkParticleMediumDeposit, exact sphere occupancy), the photon pass
// traces single scattering through it and the Lattice-Boltzmann pass computes multiple
// scattering; the scattered powers (integrals of Radiance and MultipleScattering over the grid)
// are compared with the network's, which the deposit carries exactly.
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkIlluminationNetwork.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannLighting.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkParticleMediumDeposit.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaParticleMedium.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>

namespace
{
using Medium = vtkRefractaParticleMedium;

vtkSmartPointer<vtkPolyData> Cloud(vtkIdType n, double r, double sigma, double albedo)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  vtkNew<vtkPoints> points;
  while (points->GetNumberOfPoints() < n)
  {
    const double x = u(rng), y = u(rng), z = u(rng);
    if (x * x + y * y + z * z <= 1.0)
    {
      points->InsertNextPoint(x, y, z);
    }
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  auto add = [&](const char* name, int comps, double value)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(comps);
    a->SetNumberOfTuples(n);
    a->Fill(value);
    cloud->GetPointData()->AddArray(a);
  };
  add(Medium::RadiusName(), 1, r);
  add(Medium::ExtinctionName(), 3, sigma);
  add(Medium::AlbedoName(), 3, albedo);
  return cloud;
}

// Integral over the grid of a 3-component array (channel c), power units.
double Integral(vtkImageData* image, const char* name, int c)
{
  vtkDataArray* a = image->GetPointData()->GetArray(name);
  double sum = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    sum += a->GetComponent(i, c);
  }
  const double* s = image->GetSpacing();
  return sum * s[0] * s[1] * s[2];
}
}

TEST(IlluminationNetworkGrid, AgreesWithTheGridPathOnTheDepositedCloud)
{
  vtkSmartPointer<vtkPolyData> cloud = Cloud(1024, 0.1, 5.0, 0.9);
  vtkNew<vtkIlluminationNetwork> network;
  network->SetInputData(cloud);
  network->SetLightType(vtkIlluminationNetwork::DIRECTIONAL_LIGHT);
  network->SetLightDirection(0, 0, -1);
  network->SetLightIntensity(1, 1, 1);
  network->SetNumberOfRotations(2);
  network->SetTolerance(1e-4);

  vtkNew<vtkParticleMediumDeposit> deposit;
  deposit->SetInputConnection(network->GetOutputPort());
  deposit->SetSampleDimensions(64, 64, 64);
  deposit->Update();
  vtkImageData* medium = deposit->GetMediumOutput();
  vtkImageData* networkLight = deposit->GetLightingOutput();
  ASSERT_NE(
    networkLight->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName()), nullptr);

  vtkNew<vtkLight> sun;
  sun->SetPositional(false);
  sun->SetPosition(0, 0, 10);
  sun->SetFocalPoint(0, 0, 0);
  sun->SetIntensity(1.0);
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(medium);
  tracer->AddLight(sun);
  tracer->SetNumberOfPhotons(1 << 20);
  vtkNew<vtkLatticeBoltzmannLighting> lbl;
  lbl->SetInputData(medium);
  lbl->SetLightingConnection(tracer->GetOutputPort());
  lbl->Update();
  vtkImageData* grid = lbl->GetOutput();

  const double singleNetwork = Integral(networkLight, vtkRefractaLightingVolume::RadianceName(), 0);
  const double singleGrid = Integral(grid, vtkRefractaLightingVolume::RadianceName(), 0);
  const double multipleNetwork =
    Integral(networkLight, vtkRefractaLightingVolume::MultipleScatteringName(), 0);
  const double multipleGrid =
    Integral(grid, vtkRefractaLightingVolume::MultipleScatteringName(), 0);
  std::printf("scattered power, network vs grid path: single %.4f vs %.4f (%.2f%%), multiple "
              "%.4f vs %.4f (%.2f%%); network %d iterations\n",
    singleNetwork, singleGrid, 100 * (singleNetwork / singleGrid - 1), multipleNetwork,
    multipleGrid, 100 * (multipleNetwork / multipleGrid - 1), network->GetIterations());
  // Two models of the same cloud, neither a ground truth (Refracta.ParticlesAgainstReference
  // compares both with the path tracer): single 3.35% apart when this test was written; 5.77%
  // since the photon walk integrates the grid's trilinear sigma_t exactly at steep kinks (829d2d8,
  // node-plane cuts: the grid path's single scattering -2.3%, as the dense cube against the path
  // tracer asked for). The bounds leave room for that, not for a lost factor.
  EXPECT_NEAR(singleNetwork / singleGrid, 1.0, 0.08);
  EXPECT_NEAR(multipleNetwork / multipleGrid, 1.0, 0.25);
}
