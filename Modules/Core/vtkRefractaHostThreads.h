/**
 * @class   vtkRefractaHostThreads
 * @brief   Puts Refracta's host loops on every core when VTK would run them on one.
 *
 * Refracta's host work (reading and validating medium arrays, the scene analysis, the solver's
 * source and coefficient set-up, the voxelizer, the reference renderer) runs through vtkSMPTools.
 * VTK picks its SMP backend when it is built, and the VTK of Debian's ParaView (the one Refracta
 * builds against) picks Sequential: every such loop then runs on one core, which on a GPU machine
 * costs more than the device's work for a light move.
 *
 * UseThreadedBackend() switches vtkSMPTools to its STDThread backend when (a) the backend in use
 * is Sequential, (b) the user has not chosen one (the environment variable
 * VTK_SMP_BACKEND_IN_USE, which VTK reads, is unset) and (c) VTK was built with STDThread. The
 * backend is process-wide, so this also parallelises the user's other VTK filters; setting
 * VTK_SMP_BACKEND_IN_USE=Sequential keeps everything on one core. The classes with host work
 * per render call it when they are created (vtkRefractaRenderPipeline, vtkPhotonTracer,
 * vtkLatticeBoltzmannSolver, vtkRefractaViewPass), so every front end (the mapper, the ParaView
 * plugin, refracta-render) and every pipeline of the bare filters gets it.
 *
 * Results do not depend on the backend: Refracta's parallel loops write disjoint outputs, and its
 * reductions combine integers, minima, maxima or flags, never float sums in thread order.
 */
#ifndef vtkRefractaHostThreads_h
#define vtkRefractaHostThreads_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"

#include <string> // for std::string

class REFRACTACORE_EXPORT vtkRefractaHostThreads : public vtkObject
{
public:
  static vtkRefractaHostThreads* New();
  vtkTypeMacro(vtkRefractaHostThreads, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Switches vtkSMPTools from Sequential to STDThread where the user has not chosen a backend
   * (see the class description). Returns true when the backend in use afterwards runs on more
   * than one thread. Cheap after the first call.
   */
  static bool UseThreadedBackend();

  /**
   * The vtkSMPTools backend in use and its thread count, e.g. "STDThread, 16 threads".
   */
  static std::string GetBackendDescription();

protected:
  vtkRefractaHostThreads() = default;
  ~vtkRefractaHostThreads() override = default;

private:
  vtkRefractaHostThreads(const vtkRefractaHostThreads&) = delete;
  void operator=(const vtkRefractaHostThreads&) = delete;
};

#endif
