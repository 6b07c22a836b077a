/**
 * @class   vtkOpenCLDeviceArrays
 * @brief   Device buffers known to hold a host array's current values: the lighting volume's
 *          hand-off from one pass to the next without a host round trip.
 *
 * A pass that reads a result from the device into a host array (the photon pass's `Radiance`,
 * the lattice's `MultipleScattering`) can Remember() the buffer it read from; a later pass in the
 * same vtkOpenCLContext (vtkOpenCLContext::GetDeviceArrays()) that needs that array on the device
 * asks Share() or Find() first and uploads only when neither has it. A light move then moves the
 * lighting volume photon pass -> lattice -> view pass on the device; the host arrays still exist
 * (the passes' outputs are ordinary vtkImageData), they are just not sent back.
 *
 * A remembered buffer is the array's copy only while the array lives and its MTime is the one it
 * had when remembered: an array modified on the host (and Modified(), as VTK requires) or deleted
 * is forgotten at the next call, and its buffer released. The layout is the array's own: its
 * tuples one after the other, each of its components, as 32-bit floats (only vtkFloatArray
 * instances are remembered). A pass must not write into a buffer it remembered.
 *
 * The buffers stay allocated as long as their arrays live: producers remember only when asked to
 * (vtkPhotonTracer::KeepDeviceCopies, vtkLatticeBoltzmannSolver::KeepDeviceCopies; the render
 * pipeline turns them on), and GetBytes() says how much device memory the copies hold.
 */
#ifndef vtkOpenCLDeviceArrays_h
#define vtkOpenCLDeviceArrays_h

#include "RefractaOpenCLModule.h" // for export macro
#include "vtkObject.h"

#include <memory> // for std::unique_ptr

#ifndef __VTK_WRAP__
#include "vtkOpenCLHandle.h" // for vtkOpenCLBuffer
#endif

class vtkDataArray;
class vtkFloatArray;

class REFRACTAOPENCL_EXPORT vtkOpenCLDeviceArrays : public vtkObject
{
public:
  static vtkOpenCLDeviceArrays* New();
  vtkTypeMacro(vtkOpenCLDeviceArrays, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /**
   * Records that `buffer` now holds `array`'s values (its tuples x components floats, in order),
   * as of the array's current MTime, and retains the buffer. Replaces an earlier copy of the same
   * array. Ignored (and an earlier copy forgotten) when `array` or `buffer` is null or the buffer
   * is smaller than the array's values. `owner` (the producing pass) lets it ForgetOwner() the
   * copies of its last run when it runs again, before it allocates the next ones.
   */
  void Remember(vtkFloatArray* array, cl_mem buffer, const void* owner = nullptr);

  /**
   * The device copy of `array`, or null when there is none (never remembered, modified since,
   * or forgotten). Borrowed: valid until the next call on this object; for a kernel argument of
   * a launch made right away.
   */
  cl_mem Find(vtkDataArray* array);

  /**
   * Like Find(), as an owned reference (the buffer retained): for a pass that keeps the buffer
   * beyond the call, e.g. the view pass's lighting volume. Counts a hit.
   */
  vtkOpenCLBuffer Share(vtkDataArray* array);
#endif

  /**
   * Forgets `array`'s copy (releases the buffer).
   */
  void Forget(vtkDataArray* array);

  /**
   * Forgets the copies remembered with this `owner`.
   */
  void ForgetOwner(const void* owner);

  /**
   * Forgets every copy.
   */
  void Clear();

  /**
   * The copies held now (after dropping those of deleted or modified arrays), and the device
   * memory they hold (bytes).
   */
  int GetNumberOfArrays();
  double GetBytes();

  /**
   * How many times Find() or Share() returned a copy: how many uploads the hand-off saved.
   */
  vtkGetMacro(NumberOfHits, long long);

protected:
  vtkOpenCLDeviceArrays();
  ~vtkOpenCLDeviceArrays() override;

private:
  vtkOpenCLDeviceArrays(const vtkOpenCLDeviceArrays&) = delete;
  void operator=(const vtkOpenCLDeviceArrays&) = delete;

  struct Entries;
  std::unique_ptr<Entries> Held;
  long long NumberOfHits = 0;
};

#endif
