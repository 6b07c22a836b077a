// Private to the ParaView adapters: the quality knobs the Refracta Lighting and Refracta Render
// Image filters share (a preset of the render pipeline and, over it, a photon count), applied to
// their pipeline in the one order the preset rule needs.
#ifndef vtkRefractaPluginQuality_h
#define vtkRefractaPluginQuality_h

#include "vtkEffectPlan.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaRenderPipeline.h"

#include <algorithm>

namespace refracta_plugin
{
struct PipelineQuality
{
  int Quality = vtkEffectPlan::INTERACTIVE; // vtkEffectPlan::Quality, DRAFT to PRODUCTION
  int NumberOfPhotons = 0;                  // 0: the preset's count

  /**
   * The preset, then the photon count over it.
   */
  void ApplyTo(vtkRefractaRenderPipeline* pipeline) const
  {
    pipeline->SetQuality(this->Quality);
    if (this->NumberOfPhotons > 0)
    {
      pipeline->GetPhotonTracer()->SetNumberOfPhotons(this->NumberOfPhotons);
    }
  }

  /**
   * Clamps `quality` to DRAFT..PRODUCTION; when that changes the preset, applies it to
   * `pipeline` and returns true.
   */
  bool SetQuality(int quality, vtkRefractaRenderPipeline* pipeline)
  {
    quality = std::min(std::max(quality, static_cast<int>(vtkEffectPlan::DRAFT)),
      static_cast<int>(vtkEffectPlan::PRODUCTION));
    if (quality == this->Quality)
    {
      return false;
    }
    this->Quality = quality;
    this->ApplyTo(pipeline);
    return true;
  }

  /**
   * Clamps `photons` to >= 0; when that changes the count, applies it to `pipeline` and returns
   * true.
   */
  bool SetNumberOfPhotons(int photons, vtkRefractaRenderPipeline* pipeline)
  {
    photons = std::max(photons, 0);
    if (photons == this->NumberOfPhotons)
    {
      return false;
    }
    this->NumberOfPhotons = photons;
    this->ApplyTo(pipeline);
    return true;
  }
};
}

#endif
