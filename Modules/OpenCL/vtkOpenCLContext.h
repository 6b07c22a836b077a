/**
 * @class   vtkOpenCLContext
 * @brief   The OpenCL device, context, queue and program cache shared by Refracta's passes.
 *
 * Device choice, in order:
 * 1. SetDeviceSelection(), if called with a non-empty string;
 * 2. else the environment variable REFRACTA_OPENCL_DEVICE;
 * 3. else the first GPU of any platform, else the first CPU device (PoCL on Debian), else the
 *    first device of any kind.
 * A selection string is "gpu", "cpu", "P:D" (platform index P, device index D, as listed by
 * ListDevices()), or any other text, matched case-insensitively against
 * "<platform name> <device name> <vendor>".
 *
 * Programs are built from the embedded files of vtkOpenCLKernelLibrary with -D options and
 * cached twice: in memory (one cl_program per source + options), and as device binaries on disk
 * in a user cache directory (vtkOpenCLBinaryCache), so that a second process start loads the
 * binary instead of compiling. The directory is the one set by SetBinaryCacheDirectory(), else
 * REFRACTA_KERNEL_CACHE_DIR if set, else none when the driver keeps a disk cache of its own
 * (GetDriverCachesPrograms()), else $XDG_CACHE_HOME/refracta/kernels, else
 * $HOME/.cache/refracta/kernels. A cache entry's key is a
 * hash of the source, the options, the Refracta version and the platform, device and driver
 * versions, so a driver update never loads a stale binary. Entries carry a checksum: a truncated,
 * corrupt or foreign entry (or one the driver refuses) is deleted and rebuilt; entries are written
 * to a temporary file and renamed into place, so concurrent processes are safe; a folder that
 * cannot be written gives one warning and the disk cache is off from then on.
 *
 * Device capabilities are checked where they are needed, with messages that name the device and
 * the limit: a program's `#pragma OPENCL EXTENSION <name> : enable` lines before it is built (e.g.
 * cl_khr_int64_base_atomics for the transport passes, cl_khr_fp64 for a program using double);
 * a launch's work-group size against the kernel's maximum on the device and the kernel's local
 * memory against the device's. Memory limits (GetMaximumAllocationBytes(),
 * GetGlobalMemoryBytes(), GetHostMemoryBytes()) feed each pass's vtkOpenCLMemoryPlan.
 *
 * Profiling: with ProfileKernels on (or REFRACTA_PROFILE_KERNELS=1 in the environment), every
 * launch's device time is summed per kernel in GetKernelProfile() (vtkOpenCLKernelProfile).
 *
 * Test hooks (all off by default): SetSimulated*() pretend the device or the host is smaller than
 * it is (allocation size, global, local and host memory, work-group size, missing extensions),
 * and SetFailingEnqueue(n) makes the n-th enqueue from then on fail as a driver error would, so
 * that the passes' error paths can be exercised on any machine.
 *
 * Every OpenCL failure becomes a vtkErrorMacro message naming the call, the error code's name
 * and number, and the device; a failed program build adds the build log and which lines of the
 * concatenated source came from which file. No OpenCL platform at all gives one message that says
 * what to install; Initialize() then returns false and every pass that needs the device fails
 * cleanly.
 *
 * Accumulation: Refracta's passes add float deposits with 64-bit fixed point (see
 * Kernels/refracta_atomics.cl and ChooseFixedPointScale()): exact, order-independent and so
 * deterministic per seed on every device, and it needs only cl_khr_int64_base_atomics.
 */
#ifndef vtkOpenCLContext_h
#define vtkOpenCLContext_h

#include "RefractaOpenCLModule.h" // for export macro
#include "vtkObject.h"

#include <functional> // for Enqueue
#include <map>        // for the program cache
#include <mutex>      // for the program cache
#include <string>     // for std::string
#include <vector>     // for std::vector

#ifndef __VTK_WRAP__
#include "vtkOpenCLBinaryCache.h"   // for the disk cache
#include "vtkOpenCLDeviceArrays.h"  // for the device copies
#include "vtkOpenCLHandle.h"        // for vtkOpenCLKernel, vtkOpenCLBuffer
#include "vtkOpenCLKernelProfile.h" // for the kernel profile
#include "vtkSmartPointer.h"        // for the disk cache
#endif

class vtkOpenCLDeviceArrays;
class vtkOpenCLKernelProfile;

class REFRACTAOPENCL_EXPORT vtkOpenCLContext : public vtkObject
{
public:
  static vtkOpenCLContext* New();
  vtkTypeMacro(vtkOpenCLContext, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The process-wide context the passes use unless they are given another one. Created on
   * first use; Initialize() it (cheap once done) before use.
   */
  static vtkOpenCLContext* GetDefault();

  ///@{
  /**
   * Device selection string (see the class description); overrides REFRACTA_OPENCL_DEVICE.
   * Changing it after Initialize() has no effect. Default: empty.
   */
  vtkSetStringMacro(DeviceSelection);
  vtkGetStringMacro(DeviceSelection);
  ///@}

  /**
   * Select the device and create the context and queue. Returns true on success. Idempotent:
   * later calls return the first call's result without retrying a failure.
   */
  bool Initialize();

  /**
   * True after a successful Initialize().
   */
  bool IsReady() const { return this->Ready; }

  /**
   * Message of the last error this context reported (empty if none).
   */
  const char* GetLastErrorMessage() const { return this->LastErrorMessage.c_str(); }

  ///@{
  /**
   * Facts about the selected device (valid after Initialize()).
   */
  const char* GetPlatformName() const { return this->PlatformName.c_str(); }
  const char* GetDeviceName() const { return this->DeviceName.c_str(); }
  const char* GetDeviceVendor() const { return this->DeviceVendor.c_str(); }
  const char* GetDeviceVersion() const { return this->DeviceVersion.c_str(); }
  const char* GetDriverVersion() const { return this->DriverVersion.c_str(); }
  bool GetIsGPU() const { return this->IsGPU; }
  int GetNumberOfComputeUnits() const { return this->ComputeUnits; }
  double GetGlobalMemoryMiB() const { return this->GetGlobalMemoryBytes() / 1048576.0; }
  double GetMaximumAllocationMiB() const { return this->GetMaximumAllocationBytes() / 1048576.0; }
  bool HasExtension(const char* name) const;
  ///@}

  ///@{
  /**
   * Limits the passes plan with, in bytes (valid after Initialize()): the largest single buffer
   * (CL_DEVICE_MAX_MEM_ALLOC_SIZE), the device's global memory (CL_DEVICE_GLOBAL_MEM_SIZE), its
   * local memory per work-group (CL_DEVICE_LOCAL_MEM_SIZE), the host's physical memory, and the
   * largest work-group (CL_DEVICE_MAX_WORK_GROUP_SIZE); each the smaller of the real value and
   * its SetSimulated*() value when one is set.
   */
  double GetMaximumAllocationBytes() const;
  double GetGlobalMemoryBytes() const;
  double GetLocalMemoryBytes() const;
  double GetHostMemoryBytes() const;
  size_t GetMaximumWorkGroupSize() const;
  ///@}

  /**
   * The largest work-group `kernel` may run in on this device: the smaller of
   * CL_KERNEL_WORK_GROUP_SIZE and GetMaximumWorkGroupSize().
   */
  size_t GetKernelWorkGroupSize(cl_kernel kernel) const;

  /**
   * Whether the device's local memory is its own on-chip memory (CL_DEVICE_LOCAL_MEM_TYPE
   * CL_LOCAL: GPUs) rather than ordinary memory (CL_GLOBAL: CPU devices such as PoCL's), where
   * kernels that stage data in local memory gain nothing. False before Initialize().
   */
  bool HasDedicatedLocalMemory() const { return this->DedicatedLocalMemory; }

  ///@{
  /**
   * Test hooks: pretend a smaller device or host (bytes; work-items), or a device without the
   * listed extensions (space-separated names). 0 or empty (default): the real value.
   */
  vtkSetMacro(SimulatedMaximumAllocationBytes, double);
  vtkGetMacro(SimulatedMaximumAllocationBytes, double);
  vtkSetMacro(SimulatedGlobalMemoryBytes, double);
  vtkGetMacro(SimulatedGlobalMemoryBytes, double);
  vtkSetMacro(SimulatedLocalMemoryBytes, double);
  vtkGetMacro(SimulatedLocalMemoryBytes, double);
  vtkSetMacro(SimulatedHostMemoryBytes, double);
  vtkGetMacro(SimulatedHostMemoryBytes, double);
  vtkSetMacro(SimulatedMaximumWorkGroupSize, int);
  vtkGetMacro(SimulatedMaximumWorkGroupSize, int);
  vtkSetStringMacro(SimulatedMissingExtensions);
  vtkGetStringMacro(SimulatedMissingExtensions);
  ///@}

  ///@{
  /**
   * Test hook: the n-th enqueue from this call on (kernel launch, buffer write, read or fill;
   * 1 = the next one) fails with CL_OUT_OF_RESOURCES as a driver error would, once; 0 (default)
   * disarms it. GetNumberOfEnqueues() counts the enqueues since the context was created.
   */
  void SetFailingEnqueue(int n);
  vtkGetMacro(NumberOfEnqueues, int);
  ///@}

  /**
   * One line per OpenCL device on this machine: "P:D  platform  /  device  (type)".
   * Returns a message instead when there is no platform.
   */
  static std::string ListDevices();

  /**
   * Name of an OpenCL error code, e.g. "CL_INVALID_VALUE" for -30.
   */
  static const char* GetErrorName(int code);

  /**
   * Power-of-two scale for 64-bit fixed-point accumulation such that a sum of magnitude up to
   * `largestSum` stays below 2^62: the resolution of one deposit is then 1/scale. Returns 2^32
   * for a non-positive or non-finite argument.
   */
  static double ChooseFixedPointScale(double largestSum);

  /**
   * A float literal for a -D build option ("1.25000000e+00f") that the OpenCL compiler reads back
   * as the same float as static_cast<float>(value).
   */
  static std::string FloatLiteral(double value);

  ///@{
  /**
   * On-disk binary cache. The directory defaults as described above; UseBinaryCache (default
   * on) turns the disk cache off entirely (the memory cache always works).
   */
  vtkSetStringMacro(BinaryCacheDirectory);
  vtkGetStringMacro(BinaryCacheDirectory);
  vtkSetMacro(UseBinaryCache, bool);
  vtkGetMacro(UseBinaryCache, bool);
  vtkBooleanMacro(UseBinaryCache, bool);
  ///@}

  /**
   * True when the device's driver keeps compiled programs on disk itself, so that the binary
   * cache is off unless a directory was named (SetBinaryCacheDirectory() or
   * REFRACTA_KERNEL_CACHE_DIR): PoCL with its kernel cache on (POCL_KERNEL_CACHE unset or
   * starting with 1, as PoCL reads it) and a
   * folder to keep it in (POCL_CACHE_DIR, XDG_CACHE_HOME or HOME set). Both caches would only
   * cost time there: asking PoCL for a program's binary makes it generate machine code for every
   * kernel of the program, used or not, and the launches then generate it again for their
   * work-group size. A cold start of the view pass tests took 48 s with both caches and 29 s
   * with PoCL's alone; the warm start is 1.8 s against 1.0 s.
   */
  bool GetDriverCachesPrograms() const;

  ///@{
  /**
   * How programs were obtained since this context was created: compiled from source, loaded
   * from a disk binary, or found in the memory cache; and how many disk entries were rejected
   * (truncated, corrupt, foreign or refused by the driver: deleted and rebuilt).
   */
  vtkGetMacro(NumberOfSourceBuilds, int);
  vtkGetMacro(NumberOfBinaryLoads, int);
  vtkGetMacro(NumberOfMemoryCacheHits, int);
  vtkGetMacro(NumberOfRejectedBinaries, int);
  ///@}

  ///@{
  /**
   * Kernel profiling (default off, or on when the environment variable REFRACTA_PROFILE_KERNELS
   * is 1 when the context is created): every RunKernel() launch keeps its event and
   * GetKernelProfile() sums the device time per launch label. GetKernelProfile() waits for the
   * queue and collects first, so its totals are complete.
   */
  vtkSetMacro(ProfileKernels, bool);
  vtkGetMacro(ProfileKernels, bool);
  vtkBooleanMacro(ProfileKernels, bool);
  vtkOpenCLKernelProfile* GetKernelProfile();
  ///@}

  ///@{
  /**
   * Stagger buffers on CPU devices (default on; the environment variable
   * REFRACTA_STAGGER_BUFFERS=0 turns it off for a process, e.g. for the A/B of a benchmark): every
   * buffer of 64 KiB or more that CreateBuffer() makes on a CPU device starts at its own offset
   * within a 4 KiB page (a region of a slightly larger allocation, at most 4 KiB more), so that
   * the buffers a kernel streams at once do not share cache sets and 4 KiB aliases, as
   * page-aligned host allocations otherwise all do. The lattice step ran 1.3-1.4x faster on the
   * 2-core PoCL device (Benchmarks.md). No effect on GPUs, whose memory is their own, nor on the
   * results.
   */
  vtkSetMacro(StaggerBuffers, bool);
  vtkGetMacro(StaggerBuffers, bool);
  vtkBooleanMacro(StaggerBuffers, bool);
  ///@}

  /**
   * The device copies of host arrays that the passes in this context hand on to each other
   * (the lighting volume, photon pass -> lattice -> view pass) instead of uploading them again.
   */
  vtkOpenCLDeviceArrays* GetDeviceArrays();

  /**
   * The path of the disk-cache entry of a program (as GetProgram() would build it), or empty
   * when the disk cache is off. For tests and diagnostics.
   */
  std::string GetBinaryCachePath(
    const std::vector<std::string>& kernelFiles, const std::string& options);

  /**
   * Compile a program from embedded kernel files (comma-separated names, in order) and options,
   * and report whether it built. For scripts and diagnostics; C++ passes use GetProgram().
   */
  bool BuildProgram(const char* kernelFiles, const char* options);

#ifndef __VTK_WRAP__
  cl_context GetContext() const
  {
    return this->Context;
  }
  cl_device_id GetDevice() const
  {
    return this->Device;
  }
  cl_command_queue GetQueue() const
  {
    return this->Queue;
  }

  /**
   * The program made of the named embedded files (concatenated in order) built with `options`
   * (e.g. "-DSTEPS=8"). Owned by the context: do not release it. Returns nullptr after
   * reporting an error (on `reporter` if given, else on this context).
   */
  cl_program GetProgram(const std::vector<std::string>& kernelFiles, const std::string& options,
    vtkObject* reporter = nullptr);

  /**
   * The same for a source given as text; `label` names it in messages.
   */
  cl_program GetProgramFromSource(const std::string& source, const std::string& options,
    const std::string& label, vtkObject* reporter = nullptr);

  /**
   * A kernel of a program, or an empty handle after reporting an error.
   */
  vtkOpenCLKernel CreateKernel(cl_program program, const char* name, vtkObject* reporter = nullptr);

  /**
   * A buffer of `bytes` bytes (copied from `hostData` when given), or an empty handle after
   * reporting an error; `what` names the buffer in messages.
   */
  vtkOpenCLBuffer CreateBuffer(cl_mem_flags flags, size_t bytes, const void* hostData,
    const char* what, vtkObject* reporter = nullptr);

  /**
   * CreateBuffer() with the buffer's start placed `pageOffset` bytes into a 4 KiB page (rounded
   * down to the device's base-address alignment) where StaggerBuffers applies, instead of the next
   * offset of the context's sequence: for a pass whose buffers are streamed together, so that
   * their relative placement does not depend on what was allocated before.
   */
  vtkOpenCLBuffer CreateBufferAt(cl_mem_flags flags, size_t bytes, const void* hostData,
    const char* what, vtkObject* reporter, size_t pageOffset);

  ///@{
  /**
   * Blocking transfers (a write or read at `offset` bytes into the buffer), a zero fill and a
   * device-side copy of the first `bytes` of `source` to `destination` from `destinationOffset`
   * bytes on (enqueued like a kernel), reporting errors; return true on success.
   */
  bool WriteBuffer(cl_mem buffer, size_t bytes, const void* data, vtkObject* reporter = nullptr,
    size_t offset = 0);
  bool ReadBuffer(
    cl_mem buffer, size_t bytes, void* data, vtkObject* reporter = nullptr, size_t offset = 0);
  bool ZeroBuffer(cl_mem buffer, size_t bytes, vtkObject* reporter = nullptr);
  bool CopyBuffer(cl_mem source, cl_mem destination, size_t bytes, vtkObject* reporter = nullptr,
    size_t destinationOffset = 0);
  ///@}

  /**
   * Enqueue a kernel over `dimensions` global sizes (each rounded up to a multiple of the local
   * size when one is given; kernels guard their range), optionally from a global offset. The
   * work-group size and the kernel's local memory are checked against the device first. Returns
   * true on success.
   */
  bool RunKernel(cl_kernel kernel, cl_uint dimensions, const size_t* globalSize,
    const size_t* localSize, const char* label, vtkObject* reporter = nullptr,
    const size_t* globalOffset = nullptr);

  /**
   * clFinish on the queue, reporting errors.
   */
  bool Finish(vtkObject* reporter = nullptr);

  /**
   * Report `status` as an error naming `call` when it is not CL_SUCCESS; returns true when it
   * is CL_SUCCESS.
   */
  bool Check(cl_int status, const char* call, vtkObject* reporter = nullptr);
#endif

protected:
  vtkOpenCLContext();
  ~vtkOpenCLContext() override;

  void ReportError(const std::string& message, vtkObject* reporter);
  bool SelectDevice();
  std::string ResolveCacheDirectory() const;
  std::string CacheKey(const std::string& source, const std::string& options) const;
  std::string ConcatenateKernelFiles(
    const std::vector<std::string>& kernelFiles, std::string& label, vtkObject* reporter);
  bool CheckRequiredExtensions(
    const std::string& source, const std::string& label, vtkObject* reporter);
  bool InjectedFault(const char* call, vtkObject* reporter);
  void UpdateBinaryCacheDirectory();

  char* DeviceSelection = nullptr;
  char* BinaryCacheDirectory = nullptr;
  bool UseBinaryCache = true;
  bool ProfileKernels = false;
  bool StaggerBuffers = true;
  size_t BaseAddressAlignment = 0; // bytes, queried with the first staggered buffer
  size_t NumberOfStaggeredBuffers = 0;
  bool Initialized = false;
  bool Ready = false;
  int NumberOfSourceBuilds = 0;
  int NumberOfBinaryLoads = 0;
  int NumberOfMemoryCacheHits = 0;
  int NumberOfRejectedBinaries = 0;
  int NumberOfEnqueues = 0;
  int FailingEnqueue = 0; // absolute enqueue number that fails, 0: none
  double SimulatedMaximumAllocationBytes = 0;
  double SimulatedGlobalMemoryBytes = 0;
  double SimulatedLocalMemoryBytes = 0;
  double SimulatedHostMemoryBytes = 0;
  int SimulatedMaximumWorkGroupSize = 0;
  char* SimulatedMissingExtensions = nullptr;

  std::string PlatformName;
  std::string PlatformVersion;
  std::string DeviceName;
  std::string DeviceVendor;
  std::string DeviceVersion;
  std::string DriverVersion;
  std::string Extensions;
  bool IsGPU = false;
  int ComputeUnits = 0;
  double GlobalMemoryBytes = 0;
  double MaxAllocationBytes = 0;
  double LocalMemoryBytes = 0;
  bool DedicatedLocalMemory = false;
  size_t MaxWorkGroupSize = 0;
  std::string LastErrorMessage;

#ifndef __VTK_WRAP__
  cl_platform_id Platform = nullptr;
  cl_device_id Device = nullptr;
  cl_context Context = nullptr;
  cl_command_queue Queue = nullptr;
  cl_program BuildFromSource(const std::string& source, const std::string& options,
    const std::string& label, vtkObject* reporter);
  cl_program LoadBinary(const std::string& key, const std::string& options);
  void SaveBinary(cl_program program, const std::string& key);
  bool CheckLaunch(cl_kernel kernel, const size_t* localSize, cl_uint dimensions, const char* label,
    vtkObject* reporter);
  // With ProfileKernels on, hands the call's event (or none) and the host's wall time since
  // `hostStart` (HostClock()) to the profile; always returns true so it chains after Check().
  bool RecordLaunch(const char* label, cl_event event, double hostStart, size_t bytes = 0);
  // One transfer or fill of `bytes`: the fault hook, the call (given the event to fill, or null
  // when not profiling), its check, and its record under `label` followed by the reporter's class
  // (who moved the data: the profile's per-pass transfer volumes).
  bool Enqueue(const char* call, const char* label, size_t bytes, vtkObject* reporter,
    const std::function<cl_int(cl_event*)>& enqueue);
  static double HostClock();
  // The offset of a buffer of `bytes` within its allocation (StaggerBuffers): `wanted` rounded down
  // to the base-address alignment, or the next of the context's sequence when `wanted` is
  // SIZE_MAX; 0 for none.
  size_t Stagger(size_t bytes, size_t wanted);
  vtkOpenCLBuffer CreateStaggeredBuffer(cl_mem_flags flags, size_t bytes, const void* hostData,
    const char* what, vtkObject* reporter, size_t wanted);
  vtkSmartPointer<vtkOpenCLBinaryCache> DiskCache;
  vtkSmartPointer<vtkOpenCLKernelProfile> KernelProfile;
  vtkSmartPointer<vtkOpenCLDeviceArrays> DeviceArrays;
  bool WarnedAboutDiskCache = false;
  std::map<std::string, cl_program> Programs;
  std::mutex ProgramsMutex;
#endif

private:
  vtkOpenCLContext(const vtkOpenCLContext&) = delete;
  void operator=(const vtkOpenCLContext&) = delete;
};

#endif
