// Private to vtkRefractiveVolumeMapper (not installed): what the mapper holds between renders,
// shared by its main file and the forwarding of its settings (vtkRefractiveVolumeMapperSettings).
#ifndef vtkRefractiveVolumeMapperInternals_h
#define vtkRefractiveVolumeMapperInternals_h

#include "vtkRefractiveVolumeMapper.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRefractaActorSurfaces.h"
#include "vtkRefractaErrorCapture.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaRendererBackground.h"
#include "vtkRefractiveVolumeMapperCompositing.h"
#include "vtkSmartPointer.h"
#include "vtkTimeStamp.h"
#include "vtkTransferFunctionMedium.h"

#include <cstdint>
#include <string>
#include <vector>

class vtkRefractaSurfaceSet;

struct vtkRefractiveVolumeMapper::Internals
{
  vtkSmartPointer<vtkRefractaRenderPipeline> Pipeline =
    vtkSmartPointer<vtkRefractaRenderPipeline>::New();
  vtkSmartPointer<vtkTransferFunctionMedium> Mapping =
    vtkSmartPointer<vtkTransferFunctionMedium>::New();
  vtkSmartPointer<vtkPiecewiseFunction> IndexFunction;
  vtkSmartPointer<vtkImageData> LightingData;
  // An unnamed selected array (chosen by index) cannot be named to the mapping filter: a shallow
  // copy of the input with that array as the active scalars is mapped instead, rebuilt when the
  // input or the array changes.
  vtkNew<vtkImageData> Unnamed;
  vtkImageData* UnnamedFrom = nullptr;
  vtkDataArray* UnnamedArray = nullptr;
  vtkTimeStamp UnnamedTime;
  vtkSmartPointer<vtkImageData> Medium; // the input or its transfer-function mapping, cut
  vtkImageData* Uncut = nullptr;        // what Medium was cut from
  vtkTimeStamp CutTime;
  std::vector<double> CutCropping; // the cropping settings it was cut with
  vtkNew<vtkRefractaRendererBackground> Background;
  vtkNew<vtkRefractaActorSurfaces> Actors;
  vtkRefractaSurfaceSet* ClassifiedWith = nullptr; // the surfaces the pixel kinds were made for
  bool ClassifiedEverywhere = false; // ShadeActorsEverywhere at the last classification
  std::vector<double> ClassifiedView; // the view (ray frame, projection) it was made for
  vtkTimeStamp ClassifiedTime;
  // The medium's active box (see vtkRefractiveVolumeMapperCompositing.h) and what it was
  // computed from.
  vtkRefractiveVolumeMapperDetail::LocalBox ActiveBox;
  vtkImageData* ActiveBoxMedium = nullptr;
  vtkMTimeType ActiveBoxTime = 0;
  std::vector<std::uint8_t> Kinds; // per pixel, vtkRefractiveVolumeMapperDetail::PixelKind

  // The view stage's depth input: the raw depth buffer and the path-length limits it gave.
  std::vector<float> Depth;
  std::vector<float> Limits;
  std::string LastMessage; // said once, not on every Render
  // The transfer-function mapping's error text, so that the mapper says it (once, in its own
  // event) instead of the filter and its executive on every Render.
  vtkNew<vtkRefractaErrorCapture> MappingError;

  double MeteredExposure = 1.0;
  int MeteredAt = -1; // plan + light-pass runs when the exposure was metered
  bool BlendModeWarned = false;
  bool OtherVolumesWarned = false; // another visible volume shares the renderer
  bool TranslucentPropsWarned = false; // translucent geometry shares the renderer
};

#endif
