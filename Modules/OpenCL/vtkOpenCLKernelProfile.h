/**
 * @class   vtkOpenCLKernelProfile
 * @brief   Device time per kernel, from OpenCL's profiling events: where a pass spends its time.
 *
 * vtkOpenCLContext keeps one (GetKernelProfile()). While the context's ProfileKernels is on (off
 * by default; the environment variable REFRACTA_PROFILE_KERNELS=1 turns it on for a whole
 * process, e.g. `refracta-render` or a benchmark), every launch through
 * vtkOpenCLContext::RunKernel() hands its event here, and the profile sums, per launch label, the
 * launches and the device time from CL_PROFILING_COMMAND_START to CL_PROFILING_COMMAND_END
 * (seconds). Events of finished launches are folded in as they accumulate, so a long run holds at
 * most a few hundred events. The context's transfers are recorded the same way under bracketed
 * labels ("[write]", "[read]", "[fill]", followed by the class of the object that asked for the
 * transfer where the caller named one, e.g. "[read] vtkPhotonTracer"), with the bytes they moved,
 * and calls with no device work under theirs ("[create buffer]", "[finish]"). Every entry also sums the host's wall time inside the OpenCL
 * call (the enqueue, or the whole wait of a blocking transfer or clFinish): a frame's wall time
 * less GetTotalHostSeconds() is the host's own work, and GetTotalDeviceSeconds() is what the
 * device did of it.
 *
 * Collect() waits for the pending launches and folds them in; the getters report what was
 * collected. The cost is one event per launch (microseconds); off, nothing is recorded.
 */
#ifndef vtkOpenCLKernelProfile_h
#define vtkOpenCLKernelProfile_h

#include "RefractaOpenCLModule.h" // for export macro
#include "vtkObject.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string
#include <vector> // for std::vector

#ifndef __VTK_WRAP__
#include "vtkOpenCLHandle.h" // for vtkOpenCLEvent
#endif

class REFRACTAOPENCL_EXPORT vtkOpenCLKernelProfile : public vtkObject
{
public:
  static vtkOpenCLKernelProfile* New();
  vtkTypeMacro(vtkOpenCLKernelProfile, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Waits for every recorded launch and adds its device time to its label's total.
   */
  void Collect();

  /**
   * Forgets every total and pending launch.
   */
  void Reset();

  ///@{
  /**
   * The collected totals: one entry per label, in the order of their first launch.
   */
  int GetNumberOfKernels() const;
  const char* GetKernelLabel(int i) const;
  int GetNumberOfLaunches(int i) const;
  double GetDeviceSeconds(int i) const;
  double GetTotalDeviceSeconds() const;
  /** Host wall time inside the OpenCL calls of entry i (seconds). */
  double GetHostSeconds(int i) const;
  double GetTotalHostSeconds() const;
  /**
   * Bytes of entry i: copied between host and device by a transfer, or set on the device by a
   * fill (0 for kernels and waits).
   */
  double GetBytes(int i) const;
  double GetTotalBytes() const;
  ///@}

  /**
   * The totals as a Markdown table, longest first: label, launches, device seconds, share, host
   * seconds in the calls, MiB moved.
   */
  std::string GetTable() const;

#ifndef __VTK_WRAP__
  /**
   * Keeps `event` (a finished or pending launch of `label`) until Collect() or until it has
   * finished and enough events are pending to fold the finished ones in, and adds `hostSeconds`
   * (the host's wall time inside the call) to the label's host total. A null event counts the
   * call and its host time only. `bytes`: what a transfer or fill moved (0 for a kernel).
   */
  void Record(
    const char* label, vtkOpenCLEvent event, double hostSeconds = 0.0, double bytes = 0.0);
#endif

protected:
  vtkOpenCLKernelProfile();
  ~vtkOpenCLKernelProfile() override;

private:
  vtkOpenCLKernelProfile(const vtkOpenCLKernelProfile&) = delete;
  void operator=(const vtkOpenCLKernelProfile&) = delete;

  struct Total
  {
    std::string Label;
    int Launches = 0;
    double Seconds = 0.0;
    double HostSeconds = 0.0;
    double Bytes = 0.0;
  };
  struct Pending;
  Total& TotalOf(const std::string& label);
#ifndef __VTK_WRAP__ // (the wrappers' parser reads no pointers to members)
  double EntryValue(int i, double Total::*field) const; // 0 for an index out of range
  double SumOf(double Total::*field) const;
#endif
  void Fold(bool wait);
  std::vector<Total> Totals;
  std::unique_ptr<std::vector<Pending>> PendingLaunches;
};

#endif
