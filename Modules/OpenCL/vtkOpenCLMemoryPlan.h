/**
 * @class   vtkOpenCLMemoryPlan
 * @brief   A pass's device and host memory, estimated before anything is allocated.
 *
 * Each pass lists what it is about to allocate (AddDeviceBuffer, AddHostMemory: what, how many
 * bytes, and the setting that sizes it), then asks Fits() whether that fits the context's limits:
 * every buffer within the largest allocation the device allows (CL_DEVICE_MAX_MEM_ALLOC_SIZE), all
 * of them within its global memory (CL_DEVICE_GLOBAL_MEM_SIZE), and the host part within the
 * machine's physical memory. What does not fit gets one message that names what needs how much,
 * the limit, and the setting to lower, e.g. "image 16384 x 16384 needs 4.0 GiB for the HDR buffer;
 * device 'X' allows 1.0 GiB per allocation (CL_DEVICE_MAX_MEM_ALLOC_SIZE): lower the image size".
 * The plan's totals are what reports print as the planned memory.
 */
#ifndef vtkOpenCLMemoryPlan_h
#define vtkOpenCLMemoryPlan_h

#include "RefractaOpenCLModule.h" // for export macro
#include "vtkObject.h"

#include <string> // for std::string
#include <vector> // for std::vector

class vtkOpenCLContext;

class REFRACTAOPENCL_EXPORT vtkOpenCLMemoryPlan : public vtkObject
{
public:
  static vtkOpenCLMemoryPlan* New();
  vtkTypeMacro(vtkOpenCLMemoryPlan, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Forget every entry; `pass` names the pass in messages (e.g. "photon pass").
   */
  void Reset(const std::string& pass);

  /**
   * A device buffer of `bytes` bytes: `subject` says what it serves (e.g. "image 640 x 480",
   * "grid 128 x 128 x 128", "2^20 photons"), `what` the buffer ("HDR buffer"), `setting` what
   * to lower to make it smaller ("the image size", "NumberOfPhotons").
   */
  void AddDeviceBuffer(
    const std::string& subject, const std::string& what, double bytes, const std::string& setting);

  /**
   * Device memory already allocated (e.g. arrays uploaded earlier) that stays in use: it counts
   * towards the global memory, not against the per-allocation limit.
   */
  void AddResidentDeviceBuffer(
    const std::string& subject, const std::string& what, double bytes, const std::string& setting);

  /**
   * Host memory of `bytes` bytes, described as for AddDeviceBuffer.
   */
  void AddHostMemory(
    const std::string& subject, const std::string& what, double bytes, const std::string& setting);

  /**
   * Whether the plan fits the limits of `context` (initialised); when not, GetMessage() says why.
   */
  bool Fits(vtkOpenCLContext* context);

  /**
   * Why the last Fits() failed (empty if it did not).
   */
  const std::string& GetMessage() const { return this->Message; }

  ///@{
  /**
   * Totals of the plan in bytes, and its largest device buffer.
   */
  double GetDeviceBytes() const;
  double GetHostBytes() const;
  double GetLargestDeviceBufferBytes() const;
  ///@}

  /**
   * One line: "device 195.0 MiB (largest: photon positions 16.0 MiB), host 80.0 MiB".
   */
  std::string GetSummary() const;

  /**
   * Bytes in binary units with one decimal, e.g. "4.0 GiB", "512.0 KiB", "12 bytes".
   */
  static std::string FormatBytes(double bytes);

protected:
  vtkOpenCLMemoryPlan() = default;
  ~vtkOpenCLMemoryPlan() override = default;

  struct Entry
  {
    std::string Subject;
    std::string What;
    double Bytes;
    std::string Setting;
    bool Resident;
  };
  std::string Pass;
  std::vector<Entry> Device;
  std::vector<Entry> Host;
  std::string Message;

private:
  vtkOpenCLMemoryPlan(const vtkOpenCLMemoryPlan&) = delete;
  void operator=(const vtkOpenCLMemoryPlan&) = delete;
};

#endif
