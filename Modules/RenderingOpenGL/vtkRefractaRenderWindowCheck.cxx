#include "vtkRefractaRenderWindowCheck.h"

#include "vtkObjectFactory.h"
#include "vtkRenderWindow.h"
#include "vtkRenderingOpenGLConfigure.h"
#include "vtkSmartPointer.h"

#ifdef REFRACTA_HAVE_XLIB
#include <X11/Xlib.h>
#endif

#include <cstdlib>

vtkStandardNewMacro(vtkRefractaRenderWindowCheck);

namespace
{
struct Answer
{
  bool CanOpen = true;
  std::string Reason;
};

// An X window needs a server: open and close one connection to DISPLAY (what
// vtkXOpenGLRenderWindow does on Initialize, where a failure aborts the process).
Answer AskTheXServer()
{
  Answer answer;
#ifdef REFRACTA_HAVE_XLIB
  const char* name = std::getenv("DISPLAY");
  if (Display* display = XOpenDisplay(nullptr))
  {
    XCloseDisplay(display);
    return answer;
  }
  answer.CanOpen = false;
  answer.Reason = std::string("this VTK opens its render windows on an X server, and none answered "
                              "at DISPLAY=") +
    (name && *name ? name : "(unset)") +
    ": run under an X server (xvfb-run -a) or use a VTK built with EGL or OSMesa";
#endif
  return answer;
}

const Answer& TheAnswer()
{
  static const Answer answer = []
  {
    // The object factory's choice (created, not initialised: no connection is made yet).
    auto window = vtkSmartPointer<vtkRenderWindow>::New();
    if (window->IsA("vtkXOpenGLRenderWindow"))
    {
      return AskTheXServer();
    }
    return Answer();
  }();
  return answer;
}
}

bool vtkRefractaRenderWindowCheck::CanOpen()
{
  return TheAnswer().CanOpen;
}

std::string vtkRefractaRenderWindowCheck::GetReason()
{
  return TheAnswer().Reason;
}

void vtkRefractaRenderWindowCheck::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CanOpen: " << (CanOpen() ? "yes" : "no") << "\n";
  if (!CanOpen())
  {
    os << indent << "Reason: " << GetReason() << "\n";
  }
}
