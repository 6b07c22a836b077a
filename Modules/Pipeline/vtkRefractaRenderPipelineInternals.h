// Private state of vtkRefractaRenderPipeline, shared by its two source files
// (vtkRefractaRenderPipeline.cxx: inputs, staleness and the stage runner;
// vtkRefractaRenderPipelineStages.cxx: what each stage does).
#ifndef vtkRefractaRenderPipelineInternals_h
#define vtkRefractaRenderPipelineInternals_h

#include "vtkRefractaRenderPipeline.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkEffectPlan.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannLighting.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkPhotonDiffusionSchedule.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRefractaViewPass.h"
#include "vtkSceneAnalysis.h"
#include "vtkSmartPointer.h"
#include "vtkTimeStamp.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

struct vtkRefractaRenderPipeline::Internals
{
  vtkSmartPointer<vtkImageData> Medium;
  vtkSmartPointer<vtkImageData> LightingData;
  vtkSmartPointer<vtkLightCollection> Lights = vtkSmartPointer<vtkLightCollection>::New();
  vtkSmartPointer<vtkCamera> Camera;
  vtkSmartPointer<vtkMatrix4x4> PropMatrix;
  vtkSmartPointer<vtkOpenCLContext> Context;

  vtkNew<vtkSceneAnalysis> Analysis;
  vtkNew<vtkEffectPlan> Plan;
  vtkNew<vtkPhotonDiffusionSchedule> Schedule;
  vtkNew<vtkLightRaySingleScattering> LightRays;       // straight light (vtkEffectPlan's choice)
  vtkNew<vtkLatticeBoltzmannLighting> LightRayLattice; // multiple scattering from its output
  vtkNew<vtkRefractaViewPass> ViewPass;

  vtkSmartPointer<vtkRefractaSurfaceSet> Surfaces; // the caller's (SetSurfaces)
  int PlannedSurfaces = 0;                         // surfaces with triangles when the plan last ran

  // The surfaces every pass sees (UpdateSceneSurfaces): the caller's set itself, or, when the
  // medium carries exact dielectric interfaces, ComposedSurfaces = the caller's surfaces plus
  // the interfaces placed by PropMatrix.
  vtkRefractaSurfaceSet* SceneSurfaces = nullptr;
  vtkNew<vtkRefractaSurfaceSet> ComposedSurfaces;
  vtkImageData* ComposedMedium = nullptr;
  vtkRefractaSurfaceSet* ComposedFrom = nullptr;
  vtkMatrix4x4* ComposedMatrix = nullptr;
  vtkTimeStamp ComposeTime;

  // Products of the stages.
  vtkSmartPointer<vtkImageData> Planned;
  vtkSmartPointer<vtkLightCollection> DataLights; // the lights in the medium's data frame
  vtkSmartPointer<vtkImageData> Lighting;
  std::vector<float> Image;
  std::vector<float> Transmittance;
  std::vector<float> BackgroundPart; // of Image, for an exposure to leave alone

  // What each stage saw when it last completed.
  vtkTimeStamp PlanTime;
  vtkTimeStamp LightTime;
  vtkTimeStamp ViewTime;
  vtkImageData* PlannedFrom = nullptr;
  std::vector<vtkLight*> LightList;
  std::array<bool, vtkEffectPlan::NUMBER_OF_EFFECTS> Decisions{};
  // The rays of the last view (camera, prop matrix and grid): a camera whose MTime moved without
  // moving a ray (a clipping range reset, vtkWindowToImageFilter's re-render) keeps the image.
  vtkRefractaViewPass::RayFrame ViewFrame = {};
  int ViewSize[2] = { 0, 0 };
  std::vector<float> ViewDepth;
  bool PlanDone = false;
  bool LightDone = false;
  bool ViewDone = false;

  // The render in progress.
  bool Ran[NUMBER_OF_STAGES] = { false, false, false };
  double Seconds[NUMBER_OF_STAGES] = { 0, 0, 0 };
  double LastSeconds[NUMBER_OF_STAGES] = { -1, -1, -1 };
  double StageStart[NUMBER_OF_STAGES] = { 0, 0, 0 }; // progress at which each stage starts
  double StageWeight[NUMBER_OF_STAGES] = { 0, 0, 0 };
  double Progress = 0;
  bool Abort = false;
  vtkAlgorithm* Running = nullptr;
  std::string LastError;
  vtkSmartPointer<vtkCallbackCommand> EventForwarder;

  // A light pass's progress as a fraction of the lighting stage: the light rays and the lattice
  // on their output share it half and half when both run; every other pass has it whole.
  double LightingFraction(vtkObject* caller, double fraction) const
  {
    if (this->Running == this->LightRayLattice.GetPointer())
    {
      if (caller == this->LightRays.GetPointer())
      {
        return 0.5 * fraction;
      }
      if (caller == this->LightRayLattice.GetPointer())
      {
        return 0.5 + 0.5 * fraction;
      }
    }
    return fraction;
  }

  // Points SceneSurfaces at the set the passes are to use (see above); false (with an error)
  // when the medium's interface arrays are inconsistent. `withInterfaces` false (refraction
  // forced off) leaves the interfaces out.
  bool UpdateSceneSurfaces(bool withInterfaces);

  // Surfaces with something to hit (the plan depends on their presence only).
  // Whether `matrix` (nullptr: identity) is a rotation and translation (1e-6 relative).
  static bool IsRigid(vtkMatrix4x4* matrix)
  {
    for (int r = 0; matrix && r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        double dot = 0;
        for (int k = 0; k < 3; ++k)
        {
          dot += matrix->GetElement(k, r) * matrix->GetElement(k, c);
        }
        if (std::abs(dot - (r == c ? 1.0 : 0.0)) > 1e-6)
        {
          return false;
        }
      }
    }
    return true;
  }

  static int CountSurfaces(vtkRefractaSurfaceSet* set)
  {
    return set ? set->GetNumberOfNonEmptySurfaces() : 0;
  }

  vtkOpenCLContext* GetContext()
  {
    return this->Context ? this->Context.Get() : vtkOpenCLContext::GetDefault();
  }

  std::vector<vtkLight*> CurrentLightList()
  {
    std::vector<vtkLight*> list;
    vtkCollectionSimpleIterator it;
    this->Lights->InitTraversal(it);
    while (vtkLight* light = this->Lights->GetNextLight(it))
    {
      list.push_back(light);
    }
    return list;
  }
};

#endif
