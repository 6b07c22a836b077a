/**
 * @class   vtkRefractaRenderWindowCheck
 * @brief   Whether this process can open a VTK render window, asked before one is made.
 *
 * An X11 build of VTK (Debian's, and ParaView 5.11's) aborts the process when a render window is
 * initialised and no X server answers ("bad X server connection"); a program cannot catch that.
 * CanOpen() asks first, without touching VTK's window: it creates (but does not initialise) the
 * vtkRenderWindow that the object factory gives, and when that is an X window it opens and closes
 * a connection to the display named by DISPLAY. Builds whose default window is offscreen (EGL or
 * OSMesa: VTK_DEFAULT_RENDER_WINDOW_OFFSCREEN) and non-X platforms need no display: the answer is
 * yes. The result is computed once per process.
 *
 * Refracta's filters, the render pipeline and `refracta-render` never need a window; the mapper
 * (vtkRefractiveVolumeMapper) draws into one. Tests and benchmarks that need a window call this
 * and skip with GetReason() instead of aborting. To run the mapper on a machine without a
 * display, use a VTK built with VTK_OPENGL_HAS_EGL or VTK_OPENGL_HAS_OSMESA and
 * VTK_DEFAULT_RENDER_WINDOW_OFFSCREEN (Documentation/Reference.md, "Headless"), or an X server
 * such as `xvfb-run -a`.
 */
#ifndef vtkRefractaRenderWindowCheck_h
#define vtkRefractaRenderWindowCheck_h

#include "RefractaRenderingOpenGLModule.h" // for export macro
#include "vtkObject.h"

#include <string> // for std::string

class REFRACTARENDERINGOPENGL_EXPORT vtkRefractaRenderWindowCheck : public vtkObject
{
public:
  static vtkRefractaRenderWindowCheck* New();
  vtkTypeMacro(vtkRefractaRenderWindowCheck, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * True when a vtkRenderWindow can be initialised in this process (computed once).
   */
  static bool CanOpen();

  /**
   * Why CanOpen() is false (what was tried and what would help); empty when it is true.
   */
  static std::string GetReason();

protected:
  vtkRefractaRenderWindowCheck() = default;
  ~vtkRefractaRenderWindowCheck() override = default;

private:
  vtkRefractaRenderWindowCheck(const vtkRefractaRenderWindowCheck&) = delete;
  void operator=(const vtkRefractaRenderWindowCheck&) = delete;
};

#endif
