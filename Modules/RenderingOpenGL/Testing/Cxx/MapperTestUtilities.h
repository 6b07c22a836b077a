// What the mapper's render-window tests share: every test of a program that includes this header
// is skipped, with the reason, where no render window can be opened (an X11 VTK would abort the
// process instead); one offscreen window per test process (every X connection is a chance for a
// loaded virtual X server to refuse one); a capture of its back buffer as an RGB vtkImageData.
#ifndef MapperTestUtilities_h
#define MapperTestUtilities_h

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRefractaRenderWindowCheck.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"

#include <gtest/gtest.h>

namespace refracta_test
{
// Skips every test before the first window is made (ctest reports the program as skipped: see
// refracta_add_gtest's NEEDS_RENDER_WINDOW).
class RenderWindowEnvironment : public ::testing::Environment
{
public:
  void SetUp() override
  {
    if (!vtkRefractaRenderWindowCheck::CanOpen())
    {
      GTEST_SKIP() << "no render window: " << vtkRefractaRenderWindowCheck::GetReason();
    }
  }
};
inline ::testing::Environment* const RenderWindowEnvironmentInstance =
  ::testing::AddGlobalTestEnvironment(new RenderWindowEnvironment);

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
