/**
 * @file    RefractaPipeline.h
 * @brief   vtkRefractaRenderPipeline on a procedural scene, with every quality knob of every
 *          pass in one struct (the knobs the accuracy/time benchmark sweeps).
 */
#ifndef RefractaPipeline_h
#define RefractaPipeline_h

#include "RefractaScenes.h"

#include <string>
#include <vector>

class vtkEffectPlan;

namespace refracta
{
namespace bench
{
/** The quality knobs of the passes; defaults are the classes' defaults. */
struct PipelineKnobs
{
  int Photons = 1 << 16;            ///< vtkPhotonTracer::NumberOfPhotons
  double PhotonMinimumStep = 1.0;   ///< vtkPhotonTracer::MinimumStep (voxels)
  double PrimaryTolerance = 0.005;  ///< vtkPhotonTracer octree eps
  double SecondaryTolerance = 0.02; ///< vtkPhotonTracer octree eps'
  double LatticeTolerance = 1e-4;   ///< vtkLatticeBoltzmannLighting::Tolerance
  int BlockSize = 4;                ///< vtkLatticeBoltzmannLighting::BlockSize (0 = unblocked)
  double ViewStep = 1.0;            ///< vtkRefractaImageRenderer::StepSize (voxels)
  /// Multiple scattering: the orders the photons carry (vtkPhotonTracer::ScatteringOrders): 0 the
  /// lattice alone, k > 0 the first-collision split, -1 every order; -2 (default) the plan's
  /// automatic choice. Lattice: its directions, 6 (default: the lattice the tables of
  /// Benchmarks.md were measured with) or 18; 0 the plan's choice.
  int ScatteringOrders = -2;
  int Lattice = 6;
  int ImageWidth = 64;
  int ImageHeight = 64;
};

/**
 * Render `scene` through vtkRefractaRenderPipeline (the shipping wiring), with `plan`'s tolerance
 * and per-effect modes, and return the HDR image as RGB triples, row by row from the bottom.
 */
std::vector<double> RenderPipeline(
  const scenes::Scene& scene, vtkEffectPlan* plan, const PipelineKnobs& knobs);

/** Analyse `scene` and decide `plan` (its modes and tolerance as set); false on failure. */
bool PlanScene(const scenes::Scene& scene, vtkEffectPlan* plan);
}
}

#endif
