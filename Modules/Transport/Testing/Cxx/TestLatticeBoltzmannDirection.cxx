// The direction of the lattice's multiple scattering (vtkLatticeBoltzmannSolver::
// ComputeMultipleScatteringDirection, lbl_scattered_flux): the flux of the light it scatters over
// its scattered power, F / S, in the grid's frame.
// - light that travels along one lattice direction (a source spread by a phase function of
//   g = 0.99 about it) has F / S of length ~1 along that direction's unit vector in the grid's
//   frame, which with a non-cubic spacing is not c_i / |c_i| (D3Q18's (1, 1, 0) with spacing
//   (1, 2, 1) is (1, 2, 0) / sqrt 5), and no flux across it (D3Q6 along x: F_y = F_z = 0);
// - a uniform isotropic field (an isotropic source everywhere, mirror faces) has no flux;
// - with the first-collision split the direction is the lattice's and the photons' weighted by
//   their scattered power: all the photons' where they hold all of it, the lattice's where they
//   hold none, the mean where they hold half;
// - the filters put it into their output (`MultipleScatteringDirection`); bad arguments are
//   errors.
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannLighting.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
struct Grid
{
  int Dims[3];
  double Spacing[3];
  size_t N() const { return size_t(Dims[0]) * Dims[1] * Dims[2]; }
};

// A solver on a uniform medium (sigma_t, albedo, g), its source S1 = 1 everywhere along
// `direction` (null: isotropic source), solved to convergence.
vtkSmartPointer<vtkLatticeBoltzmannSolver> Solve(const Grid& grid, int lattice, double sigmaT,
  double albedo, double g, const double* direction, int boundary)
{
  auto solver = vtkSmartPointer<vtkLatticeBoltzmannSolver>::New();
  solver->SetLattice(lattice);
  solver->SetBoundary(boundary);
  solver->SetSourceDistribution(direction ? vtkLatticeBoltzmannSolver::PHASE_FUNCTION_SOURCE
                                          : vtkLatticeBoltzmannSolver::ISOTROPIC_SOURCE);
  solver->SetTolerance(1e-6);
  solver->SetMaximumIterations(20000);
  const size_t n = grid.N();
  const std::vector<float> extinction(3 * n, static_cast<float>(sigmaT));
  const std::vector<float> albedos(3 * n, static_cast<float>(albedo));
  const std::vector<float> gs(n, static_cast<float>(g));
  if (!solver->Initialize(grid.Dims, grid.Spacing, extinction.data(), albedos.data(), gs.data()))
  {
    return nullptr;
  }
  const std::vector<float> s1(3 * n, 1.0f);
  std::vector<float> d(3 * n, 0.0f);
  for (size_t v = 0; direction && v < n; ++v)
  {
    for (int a = 0; a < 3; ++a)
    {
      d[3 * v + a] = static_cast<float>(direction[a]);
    }
  }
  if (!solver->SetSource(s1.data(), direction ? d.data() : nullptr) || !solver->Solve())
  {
    return nullptr;
  }
  return solver;
}

// The direction at the grid's centre voxel.
void CentreDirection(vtkFloatArray* f, const Grid& grid, double out[3])
{
  const vtkIdType centre =
    grid.Dims[0] / 2 + grid.Dims[0] * (grid.Dims[1] / 2 + grid.Dims[1] * (grid.Dims[2] / 2));
  f->GetTuple(centre, out);
}
} // namespace

// D3Q18 on a spacing of (1, 2, 1): light along the lattice vector (1, 1, 0) travels along
// (1, 2, 0) / sqrt 5 in the grid's frame.
TEST(LatticeBoltzmannDirection, FollowsALatticeDirectionInTheGridsFrame)
{
  const Grid grid = { { 12, 12, 8 }, { 1, 2, 1 } };
  double along[3] = { 1, 2, 0 };
  vtkMath::Normalize(along);
  auto solver = Solve(grid, 18, 0.2, 0.5, 0.99, along, vtkLatticeBoltzmannSolver::VACUUM);
  ASSERT_NE(solver, nullptr);
  vtkNew<vtkFloatArray> f;
  ASSERT_TRUE(solver->ComputeMultipleScatteringDirection(f));
  ASSERT_EQ(f->GetNumberOfTuples(), static_cast<vtkIdType>(grid.N()));
  ASSERT_EQ(f->GetNumberOfComponents(), 3);
  double d[3];
  CentreDirection(f, grid, d);
  const double length = vtkMath::Norm(d);
  EXPECT_GT(length, 0.95) << "nearly all of it along one lattice direction";
  EXPECT_LE(length, 1.0 + 1e-5);
  // c_i / |c_i| = (1, 1, 0) / sqrt 2 would be 18.4 degrees off.
  EXPECT_GT(vtkMath::Dot(d, along) / length, std::cos(vtkMath::RadiansFromDegrees(1.0)));
}

// D3Q6 along x: by symmetry no flux along y or z, and F / S of length ~1 along x; an isotropic
// source scatters into no net flux there only where the grid is symmetric about the voxel.
TEST(LatticeBoltzmannDirection, NoFluxAcrossTheLight)
{
  const Grid grid = { { 12, 9, 9 }, { 0.5, 0.5, 0.5 } };
  const double x[3] = { 1, 0, 0 };
  auto solver = Solve(grid, 6, 0.4, 0.5, 0.99, x, vtkLatticeBoltzmannSolver::VACUUM);
  ASSERT_NE(solver, nullptr);
  vtkNew<vtkFloatArray> f;
  ASSERT_TRUE(solver->ComputeMultipleScatteringDirection(f));
  double d[3];
  CentreDirection(f, grid, d);
  EXPECT_GT(d[0], 0.95);
  EXPECT_NEAR(d[1], 0.0, 1e-6);
  EXPECT_NEAR(d[2], 0.0, 1e-6);
}

// A uniform isotropic field: no flux anywhere, while S_ms is positive.
TEST(LatticeBoltzmannDirection, IsotropicFieldHasNoFlux)
{
  const Grid grid = { { 8, 8, 8 }, { 1, 1, 1 } };
  for (int lattice : { 6, 18 })
  {
    auto solver =
      Solve(grid, lattice, 0.5, 0.5, 0.6, nullptr, vtkLatticeBoltzmannSolver::REFLECTIVE);
    ASSERT_NE(solver, nullptr);
    vtkNew<vtkFloatArray> f, ms;
    ASSERT_TRUE(solver->ComputeMultipleScattering(ms, nullptr));
    ASSERT_TRUE(solver->ComputeMultipleScatteringDirection(f));
    double largest = 0;
    for (vtkIdType i = 0; i < f->GetNumberOfValues(); ++i)
    {
      largest = std::max(largest, std::abs(double(f->GetValue(i))));
      ASSERT_GT(ms->GetValue(i), 0.0f);
    }
    EXPECT_LT(largest, 1e-5) << "D3Q" << lattice;
  }
}

// Light too weak for 1 / S (a source of 1e-38, below FLT_MIN where it scatters): finite, at most
// unit length, everywhere.
TEST(LatticeBoltzmannDirection, DeepShadowStaysFinite)
{
  const Grid grid = { { 8, 8, 8 }, { 1, 1, 1 } };
  const double x[3] = { 1, 0, 0 };
  auto solver = vtkSmartPointer<vtkLatticeBoltzmannSolver>::New();
  const size_t n = grid.N();
  const std::vector<float> extinction(3 * n, 0.5f), albedo(3 * n, 0.5f), g(n, 0.9f);
  ASSERT_TRUE(
    solver->Initialize(grid.Dims, grid.Spacing, extinction.data(), albedo.data(), g.data()));
  std::vector<float> s1(3 * n, 1e-38f), d(3 * n, 0.0f);
  for (size_t v = 0; v < n; ++v)
  {
    d[3 * v] = static_cast<float>(x[0]);
  }
  ASSERT_TRUE(solver->SetSource(s1.data(), d.data()));
  solver->SetMaximumIterations(64);
  solver->Solve();
  vtkNew<vtkFloatArray> f;
  ASSERT_TRUE(solver->ComputeMultipleScatteringDirection(f));
  for (vtkIdType v = 0; v < f->GetNumberOfTuples(); ++v)
  {
    double t[3];
    f->GetTuple(v, t);
    ASSERT_TRUE(std::isfinite(t[0]) && std::isfinite(t[1]) && std::isfinite(t[2])) << v;
    ASSERT_LE(vtkMath::Norm(t), 1.0 + 1e-5) << v;
  }
}

// The photon orders of a split on the solver's grid: their S_ms and, unless null, its direction.
vtkSmartPointer<vtkImageData> PhotonOrders(vtkDataArray* ms, vtkDataArray* direction)
{
  auto orders = vtkSmartPointer<vtkImageData>::New();
  ms->SetName(vtkRefractaLightingVolume::MultipleScatteringName());
  orders->GetPointData()->AddArray(ms);
  if (direction)
  {
    direction->SetName(vtkRefractaLightingVolume::MultipleScatteringDirectionName());
    orders->GetPointData()->AddArray(direction);
  }
  return orders;
}

// The split: the lattice's and the photons' directions weighted by their parts of the total.
TEST(LatticeBoltzmannDirection, SplitWeighsThePartsByTheirPower)
{
  const Grid grid = { { 10, 8, 8 }, { 1, 1, 1 } };
  const double x[3] = { 1, 0, 0 };
  auto solver = Solve(grid, 6, 0.4, 0.5, 0.99, x, vtkLatticeBoltzmannSolver::VACUUM);
  ASSERT_NE(solver, nullptr);
  vtkNew<vtkFloatArray> lattice, ms;
  ASSERT_TRUE(solver->ComputeMultipleScatteringDirection(lattice));
  ASSERT_TRUE(solver->ComputeMultipleScattering(ms, nullptr));
  const vtkIdType n = ms->GetNumberOfTuples();
  // The photons' part: along +y (f = 0.5), with power `share` times the lattice's (so the total
  // holds the lattice's and the photons').
  for (const double share : { 0.0, 1.0 })
  {
    vtkNew<vtkFloatArray> photons, photonDirection, total, merged;
    for (vtkFloatArray* a :
      { photons.GetPointer(), photonDirection.GetPointer(), total.GetPointer() })
    {
      a->SetNumberOfComponents(3);
      a->SetNumberOfTuples(n);
    }
    for (vtkIdType v = 0; v < n; ++v)
    {
      for (int c = 0; c < 3; ++c)
      {
        photons->SetComponent(v, c, share * ms->GetComponent(v, c));
        total->SetComponent(v, c, (1 + share) * ms->GetComponent(v, c));
        photonDirection->SetComponent(v, c, c == 1 ? 0.5 : 0.0);
      }
    }
    ASSERT_TRUE(solver->ComputeMultipleScatteringDirection(
      merged, total, PhotonOrders(photons, photonDirection)));
    for (vtkIdType v = 0; v < n; v += 37)
    {
      const double w = share / (1 + share); // the photons' weight
      EXPECT_NEAR(merged->GetComponent(v, 0), (1 - w) * lattice->GetComponent(v, 0), 1e-5);
      EXPECT_NEAR(
        merged->GetComponent(v, 1), (1 - w) * lattice->GetComponent(v, 1) + w * 0.5, 1e-5);
    }
  }
  // Without the photons' direction their part counts as isotropic.
  vtkNew<vtkFloatArray> merged, total, photons;
  total->DeepCopy(ms);
  photons->DeepCopy(ms);
  for (vtkIdType i = 0; i < total->GetNumberOfValues(); ++i)
  {
    total->SetValue(i, 2 * ms->GetValue(i));
  }
  ASSERT_TRUE(
    solver->ComputeMultipleScatteringDirection(merged, total, PhotonOrders(photons, nullptr)));
  EXPECT_NEAR(merged->GetComponent(n / 2, 0), 0.5 * lattice->GetComponent(n / 2, 0), 1e-5);
}

TEST(LatticeBoltzmannDirection, BadArgumentsAreErrors)
{
  const Grid grid = { { 6, 6, 6 }, { 1, 1, 1 } };
  auto solver = Solve(grid, 6, 0.5, 0.9, 0.0, nullptr, vtkLatticeBoltzmannSolver::VACUUM);
  ASSERT_NE(solver, nullptr);
  vtkNew<vtkTest::ErrorObserver> errors;
  solver->AddObserver(vtkCommand::ErrorEvent, errors);
  EXPECT_FALSE(solver->ComputeMultipleScatteringDirection(nullptr));
  EXPECT_TRUE(errors->GetError());
  errors->Clear();
  vtkNew<vtkFloatArray> out, shortArray, full;
  shortArray->SetNumberOfComponents(3);
  shortArray->SetNumberOfTuples(5);
  full->SetNumberOfComponents(3);
  full->SetNumberOfTuples(static_cast<vtkIdType>(grid.N()));
  full->FillValue(1.0f);
  // Photons of the wrong shape; photons without a total; a total without S_ms in the photons.
  EXPECT_FALSE(
    solver->ComputeMultipleScatteringDirection(out, full, PhotonOrders(shortArray, nullptr)));
  EXPECT_TRUE(errors->GetError());
  errors->Clear();
  EXPECT_FALSE(
    solver->ComputeMultipleScatteringDirection(out, nullptr, PhotonOrders(full, nullptr)));
  EXPECT_TRUE(errors->GetError());
  errors->Clear();
  vtkNew<vtkImageData> empty;
  EXPECT_FALSE(solver->ComputeMultipleScatteringDirection(out, full, empty));
  EXPECT_TRUE(errors->GetError());
}

TEST(LatticeBoltzmannDirection, FilterOutputsIt)
{
  vtkNew<vtkImageData> medium;
  medium->SetDimensions(9, 9, 9);
  const vtkIdType n = medium->GetNumberOfPoints();
  auto array = [&](const char* name, int comps, float value)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(comps);
    a->SetNumberOfTuples(n);
    a->FillValue(value);
    return a;
  };
  medium->GetPointData()->AddArray(array("Extinction", 3, 0.5f));
  medium->GetPointData()->AddArray(array("Albedo", 3, 0.9f));
  medium->GetPointData()->AddArray(array("Anisotropy", 1, 0.7f));
  vtkNew<vtkImageData> lighting;
  lighting->CopyStructure(medium);
  lighting->GetPointData()->AddArray(array(vtkRefractaLightingVolume::RadianceName(), 3, 1.0f));
  auto direction = array(vtkRefractaLightingVolume::RadianceDirectionName(), 3, 0.0f);
  for (vtkIdType v = 0; v < n; ++v)
  {
    direction->SetComponent(v, 2, 1.0);
  }
  lighting->GetPointData()->AddArray(direction);
  vtkNew<vtkLatticeBoltzmannLighting> filter;
  filter->SetInputData(medium);
  filter->SetLightingData(lighting);
  filter->Update();
  vtkDataArray* f = filter->GetOutput()->GetPointData()->GetArray(
    vtkRefractaLightingVolume::MultipleScatteringDirectionName());
  ASSERT_NE(f, nullptr);
  double d[3];
  f->GetTuple(4 + 9 * (4 + 9 * 4), d); // the centre: symmetric in x and y
  EXPECT_GT(d[2], 0.1) << "the light scattered forwards from a source along +z flows along +z";
  EXPECT_NEAR(d[0], 0.0, 1e-5);
  EXPECT_NEAR(d[1], 0.0, 1e-5);
}
