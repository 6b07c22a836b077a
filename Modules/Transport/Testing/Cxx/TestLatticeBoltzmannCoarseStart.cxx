// Tests of the Lattice-Boltzmann solver's coarse start (vtkLatticeBoltzmannSolver::CoarseStart):
// - from a zero state it reaches the cold start's fixed point (S_ms within a bound set by the
//   tolerance) in fewer steps on the grid, on odd, anisotropic grids with a heterogeneous medium,
//   in every schedule and lattice and at both boundaries;
// - it runs only where it should: not below 2 * MinimumCoarseDimension voxels per axis, not from
//   a state that Iterate() or a warm start left, not when switched off;
// - several levels nest (each level's steps counted, its cost weighted by its voxels);
// - progress stays monotone through the coarse stage and an abort there stops the whole solve;
// - albedo 1 with mirror faces (no steady state) stops cleanly at MaximumIterations, finite;
// - a non-finite source fails the coarse stage with an error, and the solver recovers;
// - a warm start's coarse correction (CoarseWarmStart) reaches the new source's fixed point in
//   fewer steps than the plain warm start, never negative, and only from the last Solve()'s state.
#include "vtkCommand.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkNew.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace
{
// A ball of dense, forward-scattering medium in a thin, tinted one, lit by a beam along +x
// (S1 = sigma_s exp(-tau(x)), its direction +x): the smooth and the sharp parts a coarse grid
// sees differently.
struct Problem
{
  int Dims[3];
  double Spacing[3];
  std::vector<float> Extinction, Albedo, G, Source, Direction;
  size_t N() const { return size_t(Dims[0]) * Dims[1] * Dims[2]; }
};

// Anisotropic voxels (1, 1.25, 0.8) by default: three step-length classes.
Problem MakeProblem(int nx, int ny, int nz, double albedo, bool cubicVoxels = false)
{
  Problem p{ { nx, ny, nz }, { 1.0, 1.25, 0.8 } };
  if (cubicVoxels)
  {
    p.Spacing[1] = p.Spacing[2] = 1.0;
  }
  const size_t n = p.N();
  p.Extinction.resize(3 * n);
  p.Albedo.resize(3 * n);
  p.G.resize(n);
  p.Source.resize(3 * n);
  p.Direction.assign(3 * n, 0.0f);
  for (int z = 0; z < nz; ++z)
  {
    for (int y = 0; y < ny; ++y)
    {
      double tau[3] = { 0, 0, 0 };
      for (int x = 0; x < nx; ++x)
      {
        const size_t v = x + size_t(nx) * (y + size_t(ny) * z);
        const double dx = (x - 0.55 * nx) * p.Spacing[0], dy = (y - 0.5 * ny) * p.Spacing[1],
                     dz = (z - 0.45 * nz) * p.Spacing[2];
        const bool ball = dx * dx + dy * dy + dz * dz < 0.09 * nx * nx;
        for (int c = 0; c < 3; ++c)
        {
          const double st = ball ? 1.5 + 0.2 * c : 0.15 + 0.05 * c;
          const double a = albedo * (ball ? 1.0 : 0.97);
          p.Extinction[3 * v + c] = float(st);
          p.Albedo[3 * v + c] = float(a);
          p.Source[3 * v + c] = float(a * st * std::exp(-tau[c]));
          tau[c] += st * p.Spacing[0];
        }
        p.G[v] = ball ? 0.6f : 0.1f;
        p.Direction[3 * v] = 1.0f;
      }
    }
  }
  return p;
}

struct SolveResult
{
  int Steps = 0;
  int CoarseSteps = 0;
  double CoarseCost = 0;
  bool Converged = false;
  std::vector<float> Scattered; // S_ms
};

SolveResult Solve(const Problem& p, bool coarseStart, int lattice, int block, int boundary,
  double tolerance, int minimumCoarse = 16)
{
  vtkNew<vtkLatticeBoltzmannSolver> solver;
  solver->SetCoarseStart(coarseStart);
  solver->SetMinimumCoarseDimension(minimumCoarse);
  solver->SetLattice(lattice);
  solver->SetBlockSize(block);
  solver->SetBlockPolicy(vtkLatticeBoltzmannSolver::ALWAYS_BLOCKS); // also on a CPU device
  solver->SetBoundary(boundary);
  solver->SetTolerance(tolerance);
  SolveResult run;
  EXPECT_TRUE(
    solver->Initialize(p.Dims, p.Spacing, p.Extinction.data(), p.Albedo.data(), p.G.data()));
  EXPECT_TRUE(solver->SetSource(p.Source.data(), p.Direction.data()));
  EXPECT_TRUE(solver->Solve());
  run.Steps = solver->GetIterations();
  run.CoarseSteps = solver->GetCoarseStartSteps();
  run.CoarseCost = solver->GetCoarseStartCost();
  run.Converged = solver->GetConverged();
  run.Scattered.resize(3 * p.N());
  EXPECT_TRUE(solver->ComputeMultipleScattering(run.Scattered.data()));
  return run;
}

double MaxDifferenceOverPeak(const std::vector<float>& a, const std::vector<float>& b)
{
  double diff = 0, peak = 0;
  for (size_t k = 0; k < a.size(); ++k)
  {
    EXPECT_TRUE(std::isfinite(a[k]));
    diff = std::max(diff, std::abs(double(a[k]) - double(b[k])));
    peak = std::max(peak, std::abs(double(b[k])));
  }
  return peak > 0 ? diff / peak : diff;
}
}

// The fixed point does not depend on the start: with the coarse start the grid's own steps fall
// (with the coarse levels' cost, below 0.9 of the cold steps; measured 0.64-0.86) and S_ms stays
// within the tolerance's reach of the cold start's.
TEST(LatticeBoltzmannCoarseStart, SameFixedPointInFewerSteps)
{
  // Odd sizes: the last coarse voxels have 1-4 children. Anisotropic voxels for the D3Q6 global
  // cases (the kernels of the other cases here), cubic ones for the others (those of the other
  // lattice tests): fewer kernel compilations.
  const Problem anisotropic = MakeProblem(35, 34, 33, 0.95);
  const Problem cubic = MakeProblem(35, 34, 33, 0.95, true);
  struct Case
  {
    const char* Name;
    int Lattice, Block, Boundary;
    const Problem& P;
  };
  for (const Case& c :
    { Case{ "global D3Q6 vacuum", 6, 0, vtkLatticeBoltzmannSolver::VACUUM, anisotropic },
      Case{ "global D3Q6 mirror", 6, 0, vtkLatticeBoltzmannSolver::REFLECTIVE, anisotropic },
      Case{ "blocks D3Q6 vacuum", 6, 4, vtkLatticeBoltzmannSolver::VACUUM, cubic },
      Case{ "global D3Q18 vacuum", 18, 0, vtkLatticeBoltzmannSolver::VACUUM, cubic } })
  {
    SCOPED_TRACE(c.Name);
    const Problem& p = c.P;
    const double tolerance = 1e-5;
    const SolveResult cold = Solve(p, false, c.Lattice, c.Block, c.Boundary, tolerance);
    const SolveResult warm = Solve(p, true, c.Lattice, c.Block, c.Boundary, tolerance);
    ASSERT_TRUE(cold.Converged);
    ASSERT_TRUE(warm.Converged);
    EXPECT_EQ(cold.CoarseSteps, 0);
    EXPECT_GT(warm.CoarseSteps, 0); // 35 x 34 x 33 -> 18 x 17 x 17: one coarse level
    EXPECT_NEAR(warm.CoarseCost, warm.CoarseSteps * (18.0 * 17 * 17) / (35.0 * 34 * 33), 1e-9);
    EXPECT_LT(warm.Steps + warm.CoarseCost, 0.9 * cold.Steps);
    const double difference = MaxDifferenceOverPeak(warm.Scattered, cold.Scattered);
    std::printf("%s: cold %d steps, coarse start %d + %d coarse (%.1f), S_ms difference %.2e of "
                "the peak\n",
      c.Name, cold.Steps, warm.Steps, warm.CoarseSteps, warm.CoarseCost, difference);
    // Either solve stops about tolerance / (1 - rho) from the fixed point (rho the iteration's
    // slowest decay per step, 1 / (1 - rho) below the cold step count), from different sides.
    EXPECT_LT(difference, 0.1 * tolerance * cold.Steps);
  }
}

// Where the coarse start must not run, every step is on the grid: the same steps and the same
// bits as with it switched off.
TEST(LatticeBoltzmannCoarseStart, RunsOnlyWhereItApplies)
{
  // 31 voxels on one axis < 2 x 16: no coarse grid.
  const Problem small = MakeProblem(40, 40, 31, 0.9);
  const SolveResult on = Solve(small, true, 6, 0, vtkLatticeBoltzmannSolver::VACUUM, 1e-4);
  const SolveResult off = Solve(small, false, 6, 0, vtkLatticeBoltzmannSolver::VACUUM, 1e-4);
  EXPECT_EQ(on.CoarseSteps, 0);
  EXPECT_EQ(on.Steps, off.Steps);
  EXPECT_EQ(on.Scattered, off.Scattered);

  // A state that Iterate() advanced, and a warm start (ClearSource()), continue as they are.
  const Problem p = MakeProblem(40, 40, 40, 0.9);
  vtkNew<vtkLatticeBoltzmannSolver> solver;
  ASSERT_TRUE(
    solver->Initialize(p.Dims, p.Spacing, p.Extinction.data(), p.Albedo.data(), p.G.data()));
  ASSERT_TRUE(solver->SetSource(p.Source.data(), p.Direction.data()));
  ASSERT_TRUE(solver->Iterate(8));
  ASSERT_TRUE(solver->Solve());
  EXPECT_EQ(solver->GetCoarseStartSteps(), 0);
  ASSERT_TRUE(solver->ClearSource());
  ASSERT_TRUE(solver->SetSource(p.Source.data(), p.Direction.data()));
  ASSERT_TRUE(solver->Solve());
  EXPECT_EQ(solver->GetCoarseStartSteps(), 0);
  // Restart() zeroes the state: the coarse start runs again.
  ASSERT_TRUE(solver->Restart());
  ASSERT_TRUE(solver->SetSource(p.Source.data(), p.Direction.data()));
  ASSERT_TRUE(solver->Solve());
  EXPECT_GT(solver->GetCoarseStartSteps(), 0);
  // A zero source gives a zero field at once, with or without a coarse grid.
  ASSERT_TRUE(solver->Restart());
  ASSERT_TRUE(solver->Solve());
  EXPECT_EQ(solver->GetCoarseStartSteps(), 0);
}

// 50^3 with MinimumCoarseDimension 6 nests three coarse levels (25, 13, 7), with 13 one (25^3);
// each level's steps count once and its cost by its voxels, and the answer is the cold one's.
TEST(LatticeBoltzmannCoarseStart, LevelsNest)
{
  const Problem p = MakeProblem(50, 50, 50, 0.95);
  const SolveResult cold = Solve(p, false, 6, 0, vtkLatticeBoltzmannSolver::VACUUM, 1e-5, 6);
  const SolveResult one = Solve(p, true, 6, 0, vtkLatticeBoltzmannSolver::VACUUM, 1e-5, 13);
  const SolveResult three = Solve(p, true, 6, 0, vtkLatticeBoltzmannSolver::VACUUM, 1e-5, 6);
  std::printf("50^3, albedo 0.95: cold %d steps; one level %d + %d (%.1f); three levels %d + %d "
              "(%.1f)\n",
    cold.Steps, one.Steps, one.CoarseSteps, one.CoarseCost, three.Steps, three.CoarseSteps,
    three.CoarseCost);
  EXPECT_NEAR(one.CoarseCost, one.CoarseSteps / 8.0, 1e-9); // 25^3 / 50^3
  EXPECT_GT(three.CoarseSteps * 0.125, three.CoarseCost);   // deeper levels cost less a step
  EXPECT_LT(three.CoarseCost, one.CoarseCost);
  EXPECT_LT(three.Steps + three.CoarseCost, 0.75 * cold.Steps);
  EXPECT_LT(MaxDifferenceOverPeak(three.Scattered, cold.Scattered), 1e-3);
  EXPECT_LT(MaxDifferenceOverPeak(one.Scattered, cold.Scattered), 1e-3);
}

// Progress through the coarse stage: never backwards, ends at 1; an abort requested while the
// coarse grid iterates stops the whole Solve() before any step on the grid.
TEST(LatticeBoltzmannCoarseStart, ProgressAndAbort)
{
  const Problem p = MakeProblem(48, 48, 48, 0.95);
  struct Recorder : vtkCommand
  {
    static Recorder* New() { return new Recorder; }
    std::vector<double> Values;
    size_t AbortAfter = 0; // 0: never
    void Execute(vtkObject* caller, unsigned long, void* data) override
    {
      this->Values.push_back(*static_cast<double*>(data));
      if (this->AbortAfter && this->Values.size() >= this->AbortAfter)
      {
        static_cast<vtkLatticeBoltzmannSolver*>(caller)->SetAbortSolve(true);
      }
    }
  };
  for (size_t abortAfter : { size_t(0), size_t(2) })
  {
    vtkNew<vtkLatticeBoltzmannSolver> solver;
    vtkNew<Recorder> recorder;
    recorder->AbortAfter = abortAfter;
    solver->AddObserver(vtkCommand::ProgressEvent, recorder);
    ASSERT_TRUE(
      solver->Initialize(p.Dims, p.Spacing, p.Extinction.data(), p.Albedo.data(), p.G.data()));
    ASSERT_TRUE(solver->SetSource(p.Source.data(), p.Direction.data()));
    ASSERT_TRUE(solver->Solve());
    ASSERT_FALSE(recorder->Values.empty());
    EXPECT_TRUE(std::is_sorted(recorder->Values.begin(), recorder->Values.end()));
    if (abortAfter)
    {
      EXPECT_TRUE(solver->GetAborted());
      EXPECT_FALSE(solver->GetConverged());
      EXPECT_EQ(solver->GetIterations(), 0); // stopped in the coarse stage
      EXPECT_EQ(recorder->Values.size(), abortAfter);
      EXPECT_LT(recorder->Values.back(), 0.2);
    }
    else
    {
      EXPECT_TRUE(solver->GetConverged());
      EXPECT_GT(solver->GetCoarseStartSteps(), 0);
      EXPECT_EQ(recorder->Values.back(), 1.0);
    }
  }
}

// Albedo 1 with mirror faces has no steady state (nothing leaves): both levels stop at
// MaximumIterations with finite values, the coarse start does not hang or overflow.
TEST(LatticeBoltzmannCoarseStart, NoSteadyStateStopsCleanly)
{
  Problem p = MakeProblem(36, 36, 36, 1.0);
  std::fill(p.Albedo.begin(), p.Albedo.end(), 1.0f);
  vtkNew<vtkLatticeBoltzmannSolver> solver;
  solver->SetBoundary(vtkLatticeBoltzmannSolver::REFLECTIVE);
  solver->SetMaximumIterations(200);
  ASSERT_TRUE(
    solver->Initialize(p.Dims, p.Spacing, p.Extinction.data(), p.Albedo.data(), p.G.data()));
  ASSERT_TRUE(solver->SetSource(p.Source.data(), p.Direction.data()));
  ASSERT_TRUE(solver->Solve());
  EXPECT_FALSE(solver->GetConverged());
  EXPECT_EQ(solver->GetCoarseStartSteps(), 200);
  EXPECT_EQ(solver->GetIterations(), 200);
  std::vector<float> out(3 * p.N());
  ASSERT_TRUE(solver->ComputeMultipleScattering(out.data()));
  for (float v : out)
  {
    ASSERT_TRUE(std::isfinite(v));
  }
}

// A source with a NaN (which the filters refuse upstream) reaches the coarse grid through the
// restriction: the coarse solve stops at its first check with an error the solver that asked
// reports, Solve() fails without a fine step, and the same solver solves a valid source after.
TEST(LatticeBoltzmannCoarseStart, NonFiniteSourceIsAnErrorNotAHang)
{
  Problem p = MakeProblem(36, 36, 36, 0.9);
  vtkNew<vtkLatticeBoltzmannSolver> solver;
  vtkNew<vtkTest::ErrorObserver> errors;
  solver->AddObserver(vtkCommand::ErrorEvent, errors);
  ASSERT_TRUE(
    solver->Initialize(p.Dims, p.Spacing, p.Extinction.data(), p.Albedo.data(), p.G.data()));
  std::vector<float> bad = p.Source;
  bad[3 * (p.N() / 2) + 1] = std::nanf("");
  ASSERT_TRUE(solver->SetSource(bad.data(), p.Direction.data()));
  EXPECT_FALSE(solver->Solve());
  const std::string msg = errors->GetErrorMessage();
  EXPECT_NE(msg.find("coarse start"), std::string::npos) << msg;
  EXPECT_EQ(solver->GetIterations(), 0) << "no fine step after the coarse start failed";
  EXPECT_LE(solver->GetCoarseStartSteps(), 16) << "stopped at its first checks";

  errors->Clear();
  ASSERT_TRUE(solver->Restart());
  ASSERT_TRUE(solver->SetSource(p.Source.data(), p.Direction.data()));
  ASSERT_TRUE(solver->Solve()) << errors->GetErrorMessage();
  EXPECT_TRUE(solver->GetConverged());
  std::vector<float> out(3 * p.N());
  ASSERT_TRUE(solver->ComputeMultipleScattering(out.data()));
  for (float v : out)
  {
    ASSERT_TRUE(std::isfinite(v));
  }
}

// A warm start: the field of one source, then a new source (the beam 1.6 times brighter in its
// upper half: a change with a smooth part). With the coarse correction the grid reaches the new
// fixed point (the cold start's S_ms for the new source, within the tolerance's reach) in fewer
// full-grid steps than the plain warm start, in both schedules; no density goes negative.
// Iterate() from outside a Solve() leaves a state the coarse grid does not know: no correction.
TEST(LatticeBoltzmannCoarseStart, WarmStartCorrection)
{
  const Problem before = MakeProblem(34, 34, 34, 0.9, true);
  Problem after = before;
  for (size_t v = 0; v < after.N(); ++v)
  {
    if ((v / 34) % 34 >= 17)
    {
      for (int c = 0; c < 3; ++c)
      {
        after.Source[3 * v + c] *= 1.6f;
      }
    }
  }
  const double tolerance = 1e-4;
  for (int block : { 0, 4 })
  {
    SCOPED_TRACE(block ? "blocks" : "global");
    const SolveResult cold =
      Solve(after, false, 6, block, vtkLatticeBoltzmannSolver::VACUUM, tolerance);
    double fullGridSteps[2] = { 0, 0 }; // plain, corrected
    for (bool correct : { false, true })
    {
      vtkNew<vtkLatticeBoltzmannSolver> solver;
      solver->SetCoarseWarmStart(correct);
      solver->SetBlockSize(block);
      solver->SetBlockPolicy(vtkLatticeBoltzmannSolver::ALWAYS_BLOCKS);
      solver->SetTolerance(tolerance);
      ASSERT_TRUE(solver->Initialize(before.Dims, before.Spacing, before.Extinction.data(),
        before.Albedo.data(), before.G.data()));
      ASSERT_TRUE(solver->SetSource(before.Source.data(), before.Direction.data()));
      ASSERT_TRUE(solver->Solve());
      EXPECT_FALSE(solver->GetLastSolveCorrected()) << "the first solve starts from zero";
      ASSERT_TRUE(solver->ClearSource());
      ASSERT_TRUE(solver->SetSource(after.Source.data(), after.Direction.data()));
      ASSERT_TRUE(solver->Solve());
      ASSERT_TRUE(solver->GetConverged());
      EXPECT_EQ(solver->GetLastSolveCorrected(), correct);
      EXPECT_EQ(solver->GetCoarseStartSteps() > 0, correct);
      std::vector<float> scattered(3 * after.N());
      ASSERT_TRUE(solver->ComputeMultipleScattering(scattered.data()));
      EXPECT_GE(*std::min_element(scattered.begin(), scattered.end()), 0.0f);
      const double difference = MaxDifferenceOverPeak(scattered, cold.Scattered);
      EXPECT_LT(difference, 0.1 * tolerance * cold.Steps);
      fullGridSteps[correct] = solver->GetIterations() + solver->GetCoarseStartCost();
      std::printf("%s warm start%s: %d steps + %d coarse (%.1f); cold start %d; S_ms difference "
                  "%.2e of the peak\n",
        block ? "blocks" : "global", correct ? " with the coarse correction" : "",
        solver->GetIterations(), solver->GetCoarseStartSteps(), solver->GetCoarseStartCost(),
        cold.Steps, difference);
    }
    EXPECT_LT(fullGridSteps[1], 0.9 * fullGridSteps[0]);
  }

  vtkNew<vtkLatticeBoltzmannSolver> solver;
  ASSERT_TRUE(solver->Initialize(
    before.Dims, before.Spacing, before.Extinction.data(), before.Albedo.data(), before.G.data()));
  ASSERT_TRUE(solver->SetSource(before.Source.data(), before.Direction.data()));
  ASSERT_TRUE(solver->Solve());
  ASSERT_TRUE(solver->Iterate(4));
  ASSERT_TRUE(solver->ClearSource());
  ASSERT_TRUE(solver->SetSource(after.Source.data(), after.Direction.data()));
  ASSERT_TRUE(solver->Solve());
  EXPECT_FALSE(solver->GetLastSolveCorrected());
  EXPECT_EQ(solver->GetCoarseStartSteps(), 0);
}
