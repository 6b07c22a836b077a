/**
 * @file    RefractaPipeline.h
 * @brief   The whole Refracta pipeline on a procedural scene, as a benchmark runs it: scene
 *          analysis and effect plan, photon tracer, Lattice-Boltzmann lighting, view pass, with
 *          every quality knob of every pass in one struct.
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
  int ImageWidth = 64;
  int ImageHeight = 64;
};

/**
 * Render `scene` with the pipeline as `plan` decides (a plan that has already Decide()d on the
 * scene's analysis) and return the HDR image as RGB triples, row by row from the bottom. The
 * photon pass runs only when single scattering is on and there are lights, the lattice only when
 * multiple scattering is on too.
 */
std::vector<double> RenderPipeline(
  const scenes::Scene& scene, vtkEffectPlan* plan, const PipelineKnobs& knobs);

/** Analyse `scene` and decide `plan` (its modes and tolerance as set); false on failure. */
bool PlanScene(const scenes::Scene& scene, vtkEffectPlan* plan);
}
}

#endif
