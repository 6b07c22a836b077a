// Isotropy of the grid multiple-scattering methods (issue 14): a point light at the centre of a
// homogeneous, isotropically scattering fog (albedo 0.95, sigma_t 2 per unit, grid 41^3 of
// spacing 0.1: optical radius 4). Physically MultipleScattering depends on the distance from
// the light alone; the test measures, at distance 1 (10 voxels), the mean over the 6 axis
// directions against the mean over the 8 body diagonals (trilinear interpolation) for each
// lattice, prints the ratios and checks that D3Q18 is closer to isotropic than D3Q6. The issue's
// target (ratio within 3%) is printed; no method here reaches it yet (see
// Documentation/Physics.md).
#include "vtkDataArray.h"
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

#include <cmath>
#include <cstdio>

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
}

TEST(MultipleScatteringIsotropy, PointLightInFog)
{
  vtkSmartPointer<vtkImageData> fog = Fog();
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
  tracer->SetNumberOfPhotons(1 << 19);
  tracer->Update();
  double ratio[2] = { 0, 0 };
  const int lattices[2] = { vtkLatticeBoltzmannSolver::D3Q6, vtkLatticeBoltzmannSolver::D3Q18 };
  for (int l = 0; l < 2; ++l)
  {
    vtkNew<vtkLatticeBoltzmannLighting> lbl;
    lbl->SetInputData(fog);
    lbl->SetLightingConnection(tracer->GetOutputPort());
    lbl->SetLattice(lattices[l]);
    lbl->Update();
    ratio[l] = AxisOverDiagonal(lbl->GetOutput(), 10.0);
  }
  std::printf("MultipleScattering axis / diagonal at distance 1 (10 voxels): D3Q6 %.3f, D3Q18 "
              "%.3f (target: within 3%% of 1)\n",
    ratio[0], ratio[1]);
  EXPECT_LT(std::fabs(ratio[1] - 1.0), std::fabs(ratio[0] - 1.0));
}
