// What the mapper's render-window tests share: one offscreen window per test process (every X
// connection is a chance for a loaded virtual X server to refuse one) and a capture of its
// back buffer as an RGB vtkImageData.
#ifndef MapperTestUtilities_h
#define MapperTestUtilities_h

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"

namespace refracta_test
{
inline vtkRenderWindow* SharedWindow(int size)
{
  static vtkSmartPointer<vtkRenderWindow> window;
  if (!window)
  {
    window = vtkSmartPointer<vtkRenderWindow>::New();
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);
  }
  window->SetSize(size, size);
  return window;
}

inline vtkSmartPointer<vtkImageData> Capture(vtkRenderWindow* window)
{
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}
}

#endif
