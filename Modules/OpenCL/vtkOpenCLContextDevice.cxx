// The device side of vtkOpenCLContext: finding and selecting the device, its capabilities and
// limits (extensions a program needs, work-group size, local memory, memory limits and their test
// hooks), error names, and the live-handle counts of vtkOpenCLHandle.h.
#include "vtkOpenCLContext.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <sstream>
#include <unistd.h>

namespace
{
struct DeviceEntry
{
  cl_platform_id Platform;
  cl_device_id Device;
  int PlatformIndex;
  int DeviceIndex;
  std::string PlatformName;
  std::string DeviceName;
  std::string Vendor;
  cl_device_type Type;
};

std::string PlatformString(cl_platform_id platform, cl_platform_info what)
{
  size_t size = 0;
  if (clGetPlatformInfo(platform, what, 0, nullptr, &size) != CL_SUCCESS || size == 0)
  {
    return std::string();
  }
  std::string value(size, '\0');
  clGetPlatformInfo(platform, what, size, &value[0], nullptr);
  value.resize(std::strlen(value.c_str()));
  return value;
}

std::string DeviceString(cl_device_id device, cl_device_info what)
{
  size_t size = 0;
  if (clGetDeviceInfo(device, what, 0, nullptr, &size) != CL_SUCCESS || size == 0)
  {
    return std::string();
  }
  std::string value(size, '\0');
  clGetDeviceInfo(device, what, size, &value[0], nullptr);
  value.resize(std::strlen(value.c_str()));
  return value;
}

template <typename T>
T DeviceValue(cl_device_id device, cl_device_info what)
{
  T value{};
  clGetDeviceInfo(device, what, sizeof(T), &value, nullptr);
  return value;
}

std::string Lowercase(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

const char* TypeName(cl_device_type type)
{
  if (type & CL_DEVICE_TYPE_GPU)
  {
    return "GPU";
  }
  if (type & CL_DEVICE_TYPE_CPU)
  {
    return "CPU";
  }
  if (type & CL_DEVICE_TYPE_ACCELERATOR)
  {
    return "accelerator";
  }
  return "other";
}

// All devices of all platforms, or the error of clGetPlatformIDs.
cl_int EnumerateDevices(std::vector<DeviceEntry>& entries)
{
  cl_uint numberOfPlatforms = 0;
  cl_int status = clGetPlatformIDs(0, nullptr, &numberOfPlatforms);
  if (status != CL_SUCCESS)
  {
    return status;
  }
  std::vector<cl_platform_id> platforms(numberOfPlatforms);
  if (numberOfPlatforms > 0)
  {
    clGetPlatformIDs(numberOfPlatforms, platforms.data(), nullptr);
  }
  for (cl_uint p = 0; p < numberOfPlatforms; ++p)
  {
    cl_uint numberOfDevices = 0;
    if (clGetDeviceIDs(platforms[p], CL_DEVICE_TYPE_ALL, 0, nullptr, &numberOfDevices) !=
      CL_SUCCESS)
    {
      continue;
    }
    std::vector<cl_device_id> devices(numberOfDevices);
    clGetDeviceIDs(platforms[p], CL_DEVICE_TYPE_ALL, numberOfDevices, devices.data(), nullptr);
    for (cl_uint d = 0; d < numberOfDevices; ++d)
    {
      entries.push_back({ platforms[p], devices[d], static_cast<int>(p), static_cast<int>(d),
        PlatformString(platforms[p], CL_PLATFORM_NAME), DeviceString(devices[d], CL_DEVICE_NAME),
        DeviceString(devices[d], CL_DEVICE_VENDOR),
        DeviceValue<cl_device_type>(devices[d], CL_DEVICE_TYPE) });
    }
  }
  return CL_SUCCESS;
}

// Index into `entries` of the device that `selection` names, or -1.
int FindSelectedDevice(const std::vector<DeviceEntry>& entries, const std::string& selection)
{
  const std::string wanted = Lowercase(selection);
  auto firstOfType = [&](cl_device_type type)
  {
    for (size_t i = 0; i < entries.size(); ++i)
    {
      if (entries[i].Type & type)
      {
        return static_cast<int>(i);
      }
    }
    return -1;
  };
  if (wanted.empty())
  {
    int found = firstOfType(CL_DEVICE_TYPE_GPU);
    found = found >= 0 ? found : firstOfType(CL_DEVICE_TYPE_CPU);
    return found >= 0 ? found : (entries.empty() ? -1 : 0);
  }
  if (wanted == "gpu")
  {
    return firstOfType(CL_DEVICE_TYPE_GPU);
  }
  if (wanted == "cpu")
  {
    return firstOfType(CL_DEVICE_TYPE_CPU);
  }
  int p = -1;
  int d = -1;
  char tail = 0;
  if (std::sscanf(wanted.c_str(), "%d:%d%c", &p, &d, &tail) == 2)
  {
    for (size_t i = 0; i < entries.size(); ++i)
    {
      if (entries[i].PlatformIndex == p && entries[i].DeviceIndex == d)
      {
        return static_cast<int>(i);
      }
    }
    return -1;
  }
  for (size_t i = 0; i < entries.size(); ++i)
  {
    const std::string text =
      Lowercase(entries[i].PlatformName + " " + entries[i].DeviceName + " " + entries[i].Vendor);
    if (text.find(wanted) != std::string::npos)
    {
      return static_cast<int>(i);
    }
  }
  return -1;
}
}

//------------------------------------------------------------------------------
const char* vtkOpenCLContext::GetErrorName(int code)
{
  switch (code)
  {
#define REFRACTA_CL_ERROR(name)                                                                    \
  case name:                                                                                       \
    return #name
    REFRACTA_CL_ERROR(CL_SUCCESS);
    REFRACTA_CL_ERROR(CL_DEVICE_NOT_FOUND);
    REFRACTA_CL_ERROR(CL_DEVICE_NOT_AVAILABLE);
    REFRACTA_CL_ERROR(CL_COMPILER_NOT_AVAILABLE);
    REFRACTA_CL_ERROR(CL_MEM_OBJECT_ALLOCATION_FAILURE);
    REFRACTA_CL_ERROR(CL_OUT_OF_RESOURCES);
    REFRACTA_CL_ERROR(CL_OUT_OF_HOST_MEMORY);
    REFRACTA_CL_ERROR(CL_PROFILING_INFO_NOT_AVAILABLE);
    REFRACTA_CL_ERROR(CL_MEM_COPY_OVERLAP);
    REFRACTA_CL_ERROR(CL_IMAGE_FORMAT_MISMATCH);
    REFRACTA_CL_ERROR(CL_IMAGE_FORMAT_NOT_SUPPORTED);
    REFRACTA_CL_ERROR(CL_BUILD_PROGRAM_FAILURE);
    REFRACTA_CL_ERROR(CL_MAP_FAILURE);
    REFRACTA_CL_ERROR(CL_MISALIGNED_SUB_BUFFER_OFFSET);
    REFRACTA_CL_ERROR(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST);
    REFRACTA_CL_ERROR(CL_COMPILE_PROGRAM_FAILURE);
    REFRACTA_CL_ERROR(CL_LINKER_NOT_AVAILABLE);
    REFRACTA_CL_ERROR(CL_LINK_PROGRAM_FAILURE);
    REFRACTA_CL_ERROR(CL_DEVICE_PARTITION_FAILED);
    REFRACTA_CL_ERROR(CL_KERNEL_ARG_INFO_NOT_AVAILABLE);
    REFRACTA_CL_ERROR(CL_INVALID_VALUE);
    REFRACTA_CL_ERROR(CL_INVALID_DEVICE_TYPE);
    REFRACTA_CL_ERROR(CL_INVALID_PLATFORM);
    REFRACTA_CL_ERROR(CL_INVALID_DEVICE);
    REFRACTA_CL_ERROR(CL_INVALID_CONTEXT);
    REFRACTA_CL_ERROR(CL_INVALID_QUEUE_PROPERTIES);
    REFRACTA_CL_ERROR(CL_INVALID_COMMAND_QUEUE);
    REFRACTA_CL_ERROR(CL_INVALID_HOST_PTR);
    REFRACTA_CL_ERROR(CL_INVALID_MEM_OBJECT);
    REFRACTA_CL_ERROR(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR);
    REFRACTA_CL_ERROR(CL_INVALID_IMAGE_SIZE);
    REFRACTA_CL_ERROR(CL_INVALID_SAMPLER);
    REFRACTA_CL_ERROR(CL_INVALID_BINARY);
    REFRACTA_CL_ERROR(CL_INVALID_BUILD_OPTIONS);
    REFRACTA_CL_ERROR(CL_INVALID_PROGRAM);
    REFRACTA_CL_ERROR(CL_INVALID_PROGRAM_EXECUTABLE);
    REFRACTA_CL_ERROR(CL_INVALID_KERNEL_NAME);
    REFRACTA_CL_ERROR(CL_INVALID_KERNEL_DEFINITION);
    REFRACTA_CL_ERROR(CL_INVALID_KERNEL);
    REFRACTA_CL_ERROR(CL_INVALID_ARG_INDEX);
    REFRACTA_CL_ERROR(CL_INVALID_ARG_VALUE);
    REFRACTA_CL_ERROR(CL_INVALID_ARG_SIZE);
    REFRACTA_CL_ERROR(CL_INVALID_KERNEL_ARGS);
    REFRACTA_CL_ERROR(CL_INVALID_WORK_DIMENSION);
    REFRACTA_CL_ERROR(CL_INVALID_WORK_GROUP_SIZE);
    REFRACTA_CL_ERROR(CL_INVALID_WORK_ITEM_SIZE);
    REFRACTA_CL_ERROR(CL_INVALID_GLOBAL_OFFSET);
    REFRACTA_CL_ERROR(CL_INVALID_EVENT_WAIT_LIST);
    REFRACTA_CL_ERROR(CL_INVALID_EVENT);
    REFRACTA_CL_ERROR(CL_INVALID_OPERATION);
    REFRACTA_CL_ERROR(CL_INVALID_GL_OBJECT);
    REFRACTA_CL_ERROR(CL_INVALID_BUFFER_SIZE);
    REFRACTA_CL_ERROR(CL_INVALID_MIP_LEVEL);
    REFRACTA_CL_ERROR(CL_INVALID_GLOBAL_WORK_SIZE);
    REFRACTA_CL_ERROR(CL_INVALID_PROPERTY);
    REFRACTA_CL_ERROR(CL_INVALID_IMAGE_DESCRIPTOR);
    REFRACTA_CL_ERROR(CL_INVALID_COMPILER_OPTIONS);
    REFRACTA_CL_ERROR(CL_INVALID_LINKER_OPTIONS);
    REFRACTA_CL_ERROR(CL_INVALID_DEVICE_PARTITION_COUNT);
#undef REFRACTA_CL_ERROR
    case -1001:
      return "CL_PLATFORM_NOT_FOUND_KHR";
    default:
      return "unknown OpenCL error";
  }
}

//------------------------------------------------------------------------------
std::string vtkOpenCLContext::ListDevices()
{
  std::vector<DeviceEntry> entries;
  const cl_int status = EnumerateDevices(entries);
  std::ostringstream out;
  if (status != CL_SUCCESS || entries.empty())
  {
    out << "no OpenCL device (clGetPlatformIDs: " << GetErrorName(status) << ")\n";
    return out.str();
  }
  for (const auto& e : entries)
  {
    out << e.PlatformIndex << ":" << e.DeviceIndex << "  " << e.PlatformName << "  /  "
        << e.DeviceName << "  (" << TypeName(e.Type) << ")\n";
  }
  return out.str();
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::SelectDevice()
{
  std::vector<DeviceEntry> entries;
  const cl_int status = EnumerateDevices(entries);
  if (status != CL_SUCCESS || entries.empty())
  {
    std::ostringstream msg;
    msg << "No OpenCL platform or device found (clGetPlatformIDs: " << GetErrorName(status)
        << "). Refracta needs an OpenCL driver: on Debian install pocl-opencl-icd (CPU) or your "
           "GPU vendor's OpenCL ICD, and check /etc/OpenCL/vendors (or OCL_ICD_VENDORS).";
    this->ReportError(msg.str(), nullptr);
    return false;
  }

  std::string selection;
  const char* origin = "default";
  if (this->DeviceSelection && *this->DeviceSelection)
  {
    selection = this->DeviceSelection;
    origin = "SetDeviceSelection";
  }
  else if (const char* env = std::getenv("REFRACTA_OPENCL_DEVICE"))
  {
    selection = env;
    origin = "REFRACTA_OPENCL_DEVICE";
  }
  const int chosen = FindSelectedDevice(entries, selection);
  if (chosen < 0)
  {
    std::ostringstream msg;
    msg << "No OpenCL device matches the selection '" << selection << "' (from " << origin
        << "). Use 'gpu', 'cpu', 'P:D' or part of a name; the devices are:\n"
        << ListDevices();
    this->ReportError(msg.str(), nullptr);
    return false;
  }

  const DeviceEntry& entry = entries[chosen];
  this->Platform = entry.Platform;
  this->Device = entry.Device;
  this->PlatformName = entry.PlatformName;
  this->PlatformVersion = PlatformString(entry.Platform, CL_PLATFORM_VERSION);
  this->DeviceName = entry.DeviceName;
  this->DeviceVendor = entry.Vendor;
  this->DeviceVersion = DeviceString(entry.Device, CL_DEVICE_VERSION);
  this->DriverVersion = DeviceString(entry.Device, CL_DRIVER_VERSION);
  this->Extensions = DeviceString(entry.Device, CL_DEVICE_EXTENSIONS);
  this->IsGPU = (entry.Type & CL_DEVICE_TYPE_GPU) != 0;
  this->ComputeUnits =
    static_cast<int>(DeviceValue<cl_uint>(entry.Device, CL_DEVICE_MAX_COMPUTE_UNITS));
  this->GlobalMemoryBytes =
    static_cast<double>(DeviceValue<cl_ulong>(entry.Device, CL_DEVICE_GLOBAL_MEM_SIZE));
  this->MaxAllocationBytes =
    static_cast<double>(DeviceValue<cl_ulong>(entry.Device, CL_DEVICE_MAX_MEM_ALLOC_SIZE));
  this->LocalMemoryBytes =
    static_cast<double>(DeviceValue<cl_ulong>(entry.Device, CL_DEVICE_LOCAL_MEM_SIZE));
  this->MaxWorkGroupSize = DeviceValue<size_t>(entry.Device, CL_DEVICE_MAX_WORK_GROUP_SIZE);
  this->DedicatedLocalMemory =
    DeviceValue<cl_device_local_mem_type>(entry.Device, CL_DEVICE_LOCAL_MEM_TYPE) == CL_LOCAL;

  cl_int error = CL_SUCCESS;
  const cl_context_properties properties[] = { CL_CONTEXT_PLATFORM,
    reinterpret_cast<cl_context_properties>(this->Platform), 0 };
  this->Context = clCreateContext(properties, 1, &this->Device, nullptr, nullptr, &error);
  if (!this->Check(error, "clCreateContext"))
  {
    return false;
  }
  this->Queue =
    clCreateCommandQueue(this->Context, this->Device, CL_QUEUE_PROFILING_ENABLE, &error);
  if (!this->Check(error, "clCreateCommandQueue"))
  {
    return false;
  }
  vtkDebugMacro("Selected OpenCL device " << this->DeviceName << " on " << this->PlatformName);
  return true;
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::HasExtension(const char* name) const
{
  if (!name || !*name)
  {
    return false;
  }
  if (this->SimulatedMissingExtensions)
  {
    std::istringstream missing(this->SimulatedMissingExtensions);
    if (std::find(std::istream_iterator<std::string>(missing), std::istream_iterator<std::string>(),
          std::string(name)) != std::istream_iterator<std::string>())
    {
      return false;
    }
  }
  std::istringstream words(this->Extensions);
  return std::find(std::istream_iterator<std::string>(words), std::istream_iterator<std::string>(),
           std::string(name)) != std::istream_iterator<std::string>();
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::CheckRequiredExtensions(
  const std::string& source, const std::string& label, vtkObject* reporter)
{
  // OpenCL C enables an optional feature with "#pragma OPENCL EXTENSION <name> : enable" (double
  // needs cl_khr_fp64 so): those lines are the program's requirements.
  std::istringstream lines(source);
  std::string line;
  while (std::getline(lines, line))
  {
    std::istringstream words(line);
    std::string hash, pragma, opencl, extension, name;
    words >> hash;
    if (hash == "#")
    {
      words >> pragma;
    }
    else if (hash == "#pragma")
    {
      pragma = "pragma";
    }
    if (pragma != "pragma" || !(words >> opencl >> extension >> name) || opencl != "OPENCL" ||
      extension != "EXTENSION" || name == "all" || this->HasExtension(name.c_str()))
    {
      continue;
    }
    std::ostringstream msg;
    msg << "Cannot build OpenCL program [" << label << "]: it needs the extension " << name
        << ", which device '" << this->DeviceName << "' (" << this->PlatformName
        << ") does not offer";
    if (name == "cl_khr_fp64")
    {
      msg << " (double precision)";
    }
    else if (name == "cl_khr_int64_base_atomics")
    {
      msg << " (64-bit atomics: the transport passes accumulate in 64-bit fixed point)";
    }
    msg << ". Choose another device with REFRACTA_OPENCL_DEVICE; the devices are:\n"
        << ListDevices();
    this->ReportError(msg.str(), reporter);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::CheckLaunch(cl_kernel kernel, const size_t* localSize, cl_uint dimensions,
  const char* label, vtkObject* reporter)
{
  cl_ulong kernelLocal = 0;
  clGetKernelWorkGroupInfo(
    kernel, this->Device, CL_KERNEL_LOCAL_MEM_SIZE, sizeof(kernelLocal), &kernelLocal, nullptr);
  size_t group = 1;
  for (cl_uint d = 0; localSize && d < dimensions; ++d)
  {
    group *= std::max<size_t>(localSize[d], 1);
  }
  const size_t allowed = this->GetKernelWorkGroupSize(kernel);
  std::ostringstream msg;
  if (localSize && group > allowed)
  {
    msg << "Kernel " << label << " runs in work-groups of " << group << " work-items, but device '"
        << this->DeviceName << "' allows at most " << allowed
        << " for it (CL_KERNEL_WORK_GROUP_SIZE / CL_DEVICE_MAX_WORK_GROUP_SIZE). Choose another "
           "device with REFRACTA_OPENCL_DEVICE.";
  }
  else if (static_cast<double>(kernelLocal) > this->GetLocalMemoryBytes())
  {
    msg << "Kernel " << label << " needs " << kernelLocal
        << " bytes of local memory per work-group, but device '" << this->DeviceName << "' has "
        << this->GetLocalMemoryBytes()
        << " (CL_DEVICE_LOCAL_MEM_SIZE). Choose another device with REFRACTA_OPENCL_DEVICE.";
  }
  else
  {
    return true;
  }
  this->ReportError(msg.str(), reporter);
  return false;
}

//------------------------------------------------------------------------------
double vtkOpenCLContext::GetMaximumAllocationBytes() const
{
  return this->SimulatedMaximumAllocationBytes > 0
    ? std::min(this->SimulatedMaximumAllocationBytes, this->MaxAllocationBytes)
    : this->MaxAllocationBytes;
}

double vtkOpenCLContext::GetGlobalMemoryBytes() const
{
  return this->SimulatedGlobalMemoryBytes > 0
    ? std::min(this->SimulatedGlobalMemoryBytes, this->GlobalMemoryBytes)
    : this->GlobalMemoryBytes;
}

double vtkOpenCLContext::GetLocalMemoryBytes() const
{
  return this->SimulatedLocalMemoryBytes > 0
    ? std::min(this->SimulatedLocalMemoryBytes, this->LocalMemoryBytes)
    : this->LocalMemoryBytes;
}

double vtkOpenCLContext::GetHostMemoryBytes() const
{
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long pageSize = sysconf(_SC_PAGE_SIZE);
  const double physical = pages > 0 && pageSize > 0 ? double(pages) * double(pageSize) : 0.0;
  if (this->SimulatedHostMemoryBytes > 0)
  {
    return physical > 0 ? std::min(physical, this->SimulatedHostMemoryBytes)
                        : this->SimulatedHostMemoryBytes;
  }
  return physical;
}

size_t vtkOpenCLContext::GetKernelWorkGroupSize(cl_kernel kernel) const
{
  size_t kernelMaximum = 0;
  clGetKernelWorkGroupInfo(kernel, this->Device, CL_KERNEL_WORK_GROUP_SIZE, sizeof(kernelMaximum),
    &kernelMaximum, nullptr);
  const size_t device = this->GetMaximumWorkGroupSize();
  return kernelMaximum > 0 ? std::min(device, kernelMaximum) : device;
}

size_t vtkOpenCLContext::GetMaximumWorkGroupSize() const
{
  const size_t device = this->MaxWorkGroupSize > 0 ? this->MaxWorkGroupSize : 1;
  return this->SimulatedMaximumWorkGroupSize > 0
    ? std::min(device, static_cast<size_t>(this->SimulatedMaximumWorkGroupSize))
    : device;
}

//------------------------------------------------------------------------------
namespace
{
std::atomic<long long> LiveHandles[3];
}

long long vtkOpenCLLiveHandles(int kind)
{
  return kind >= 0 && kind < 3 ? LiveHandles[kind].load() : 0;
}

void vtkOpenCLCountHandle(int kind, int change)
{
  if (kind >= 0 && kind < 3)
  {
    LiveHandles[kind] += change;
  }
}
