// Isotropy of the grid multiple-scattering methods (issue 14): a point light at the centre of a
// homogeneous, isotropically scattering fog (albedo 0.95, sigma_t 2 per unit, grid 41^3 of
// spacing 0.1: optical radius 4). Physically MultipleScattering depends on the distance from
// the light alone; the test measures, at distance 1 (10 voxels), the mean over the 6 axis
// directions against the mean over the 8 body diagonals (trilinear interpolation) for the lattice
// alone (D3Q6, D3Q18), the first-collision split (vtkPhotonTracer::ScatteringOrders) and the
// photons carrying every order, prints the ratios and checks the target (within 3%) for
// the last two (Documentation/Physics.md, "Ray effects of the grid multiple scattering").
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannLighting.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
const int Size = 41;
const double Spacing = 0.1;

vtkSmartPointer<vtkImageData> Fog()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(Size, Size, Size);
  image->SetSpacing(Spacing, Spacing, Spacing);
  const vtkIdType n = static_cast<vtkIdType>(Size) * Size * Size;
  vtkNew<vtkFloatArray> e, a;
  e->SetName(vtkRefractaMedium::ExtinctionName());
  a->SetName(vtkRefractaMedium::AlbedoName());
  e->SetNumberOfComponents(3);
  a->SetNumberOfComponents(3);
  e->SetNumberOfTuples(n);
  a->SetNumberOfTuples(n);
  e->Fill(2.0);
  a->Fill(0.95);
  image->GetPointData()->AddArray(e);
  image->GetPointData()->AddArray(a);
  return image;
}

// Trilinear value of channel 0 at index coordinates (x, y, z).
double Sample(vtkDataArray* a, double x, double y, double z)
{
  const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y)),
            k = static_cast<int>(std::floor(z));
  const double fx = x - i, fy = y - j, fz = z - k;
  double sum = 0;
  for (int c = 0; c < 8; ++c)
  {
    const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    const double w = (di ? fx : 1 - fx) * (dj ? fy : 1 - fy) * (dk ? fz : 1 - fz);
    sum += w * a->GetComponent((i + di) + Size * ((j + dj) + Size * (k + dk)), 0);
  }
  return sum;
}

double AxisOverDiagonal(vtkImageData* lighting, double voxels)
{
  vtkDataArray* ms =
    lighting->GetPointData()->GetArray(vtkRefractaLightingVolume::MultipleScatteringName());
  const double c = (Size - 1) / 2.0;
  double axis = 0, diagonal = 0;
  for (int s = -1; s <= 1; s += 2)
  {
    axis += Sample(ms, c + s * voxels, c, c) + Sample(ms, c, c + s * voxels, c) +
      Sample(ms, c, c, c + s * voxels);
  }
  const double d = voxels / std::sqrt(3.0);
  for (int corner = 0; corner < 8; ++corner)
  {
    diagonal += Sample(
      ms, c + ((corner & 1) ? d : -d), c + ((corner & 2) ? d : -d), c + ((corner & 4) ? d : -d));
  }
  return (axis / 6) / (diagonal / 8);
}

struct Result
{
  double Ratio = 0;      // axis / diagonal at distance 1
  double AtDistance = 0; // MultipleScattering along +x at distance 1
  double Seconds = 0;
  vtkSmartPointer<vtkImageData> Photons; // the photon pass's output
};

// The fog lit by a point light at its centre: photons carrying `orders` scattering orders
// (vtkPhotonTracer::ScatteringOrders), then the lattice `lattice` unless they carried every order.
Result Render(vtkImageData* fog, int orders, int lattice)
{
  const auto start = std::chrono::steady_clock::now();
  vtkNew<vtkLight> light;
  light->SetPositional(true);
  light->SetConeAngle(180);
  const double centre = (Size - 1) / 2.0 * Spacing;
  light->SetPosition(centre, centre, centre);
  light->SetFocalPoint(centre, centre, centre + 1);
  light->SetIntensity(1.0);
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(fog);
  tracer->AddLight(light);
  tracer->SetNumberOfPhotons(1 << 18);
  tracer->SetScatteringOrders(orders);
  Result r;
  vtkImageData* out = nullptr;
  vtkNew<vtkLatticeBoltzmannLighting> lbl;
  if (orders == vtkPhotonTracer::EVERY_ORDER)
  {
    tracer->Update();
    out = tracer->GetOutput();
  }
  else
  {
    lbl->SetInputData(fog);
    lbl->SetLightingConnection(tracer->GetOutputPort());
    lbl->SetLattice(lattice);
    lbl->Update();
    out = lbl->GetOutput();
  }
  r.Photons = tracer->GetOutput();
  r.Ratio = AxisOverDiagonal(out, 10.0);
  const double c = (Size - 1) / 2.0;
  r.AtDistance =
    Sample(out->GetPointData()->GetArray(vtkRefractaLightingVolume::MultipleScatteringName()),
      c + 10, c, c);
  r.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

double Energy(vtkImageData* image, const char* name)
{
  vtkDataArray* a = image->GetFieldData()->GetArray(name);
  return a ? a->GetComponent(0, 0) : -1;
}
}

// The lattice alone draws the "+" (D3Q6) or a weaker one (D3Q18); with the photons carrying the
// first orders (the first-collision split) or every order, the field depends on the distance alone
// within the 3%, and the methods without ray effects agree on its value, which the lattice
// alone misses by a factor of 1.2-2.6.
TEST(MultipleScatteringIsotropy, PointLightInFog)
{
  vtkSmartPointer<vtkImageData> fog = Fog();
  struct Case
  {
    const char* Name;
    int Orders;
    int Lattice;
  };
  const Case cases[] = { { "lattice D3Q6", 0, 6 }, { "lattice D3Q18", 0, 18 },
    { "split k = 3, D3Q18", 3, 18 }, { "split k = 6, D3Q6", 6, 6 },
    { "photons, every order", vtkPhotonTracer::EVERY_ORDER, 6 } };
  std::vector<Result> results;
  for (const Case& c : cases)
  {
    results.push_back(Render(fog, c.Orders, c.Lattice));
    std::printf("%-22s axis / diagonal at distance 1: %.4f, MultipleScattering there %.4f "
                "(%.1f s)\n",
      c.Name, results.back().Ratio, results.back().AtDistance, results.back().Seconds);
  }
  EXPECT_GT(results[0].Ratio, 3.0) << "D3Q6 alone: the '+' of issue 14";
  EXPECT_LT(std::fabs(results[1].Ratio - 1.0), std::fabs(results[0].Ratio - 1.0));
  const double truth = results[4].AtDistance;
  for (int i = 2; i < 5; ++i)
  {
    EXPECT_LT(std::fabs(results[i].Ratio - 1.0), 0.03) << cases[i].Name;
    EXPECT_NEAR(results[i].AtDistance / truth, 1.0, 0.03) << cases[i].Name;
  }
  EXPECT_GT(results[1].AtDistance / truth, 1.15) << "the lattice alone overestimates it";

  // The split's books: what the photons handed on is booked as scattered, and they close.
  vtkImageData* split = results[2].Photons;
  const double emitted = Energy(split, "EnergyEmitted");
  const double handed = Energy(split, "EnergyScattered");
  EXPECT_GT(handed, 0.1 * emitted);
  EXPECT_NEAR(Energy(split, "EnergyAbsorbed") + Energy(split, "EnergyEscaped") + handed +
      Energy(split, "EnergyRemaining"),
    emitted, 1e-4 * emitted);
  EXPECT_NEAR(Energy(results[4].Photons, "EnergyScattered"), 0.0, 1e-9 * emitted);
}
