/**
 * @class   vtkRefractaVolumeRepresentation
 * @brief   ParaView's image volume representation drawn by vtkRefractiveVolumeMapper: a medium
 *          (or a scalar volume through its colour map and opacity) with Refracta's light in the
 *          ordinary render view.
 *
 * vtkImageVolumeRepresentation (ParaView's "Volume" representation of image data) delivers the
 * data to the render view and draws it with a volume mapper; this subclass replaces the mapper
 * by vtkRefractiveVolumeMapper, so the render view's camera and lights (ParaView's light kit
 * and any added lights) drive the photon pass, multiple scattering and the view pass, and the
 * result is composited with the view's opaque geometry by the mapper's rule. A Refracta medium
 * (any vtkRefractaMedium array present) is drawn as it is; a scalar volume is mapped through the
 * representation's colour map (albedo) and opacity function (extinction), exactly as the mapper
 * maps a vtkVolumeProperty (vtkTransferFunctionMedium).
 *
 * Knobs forwarded to the mapper (defaults are the mapper's): RefractaQuality
 * (vtkEffectPlan::Quality, default INTERACTIVE), RefractaExposure (default 1),
 * RefractaAutomaticExposure (default off), RefractaMultipleScattering (default on),
 * RefractaNumberOfPhotons (default 2^18), RefractaVolumeCausticSubdivision (the photon tracer's
 * VolumeCausticSubdivision, default 4) and RefractaGlassSupersampling (the view pass's
 * DielectricSupersampling, default 3). The mapper reports bad input (no medium arrays and no
 * selected scalars) once, in the output window.
 */
#ifndef vtkRefractaVolumeRepresentation_h
#define vtkRefractaVolumeRepresentation_h

#include "RefractaParaViewAdaptersModule.h" // for export macro
#include "vtkImageVolumeRepresentation.h"

class vtkRefractiveVolumeMapper;

class REFRACTAPARAVIEWADAPTERS_EXPORT vtkRefractaVolumeRepresentation
  : public vtkImageVolumeRepresentation
{
public:
  static vtkRefractaVolumeRepresentation* New();
  vtkTypeMacro(vtkRefractaVolumeRepresentation, vtkImageVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Forwarded to vtkRefractiveVolumeMapper.
   */
  void SetRefractaQuality(int quality);
  void SetRefractaExposure(double exposure);
  void SetRefractaAutomaticExposure(bool on);
  void SetRefractaMultipleScattering(bool on);
  void SetRefractaNumberOfPhotons(int photons);
  void SetRefractaVolumeCausticSubdivision(int subdivision);
  void SetRefractaGlassSupersampling(int samples);
  ///@}

  /**
   * The mapper this representation draws with.
   */
  vtkRefractiveVolumeMapper* GetRefractiveMapper();

protected:
  vtkRefractaVolumeRepresentation();
  ~vtkRefractaVolumeRepresentation() override;

  /**
   * The superclass's array selection, then the volume is shown even without a colour array:
   * a medium needs none.
   */
  void UpdateMapperParameters() override;

private:
  vtkRefractaVolumeRepresentation(const vtkRefractaVolumeRepresentation&) = delete;
  void operator=(const vtkRefractaVolumeRepresentation&) = delete;
};

#endif
