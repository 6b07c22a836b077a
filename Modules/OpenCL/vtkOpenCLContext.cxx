#include "vtkOpenCLContext.h"

#include "vtkObjectFactory.h"
#include "vtkOpenCLKernelLibrary.h"
#include "vtkSmartPointer.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <unistd.h>

vtkStandardNewMacro(vtkOpenCLContext);

namespace
{
// Refracta's version goes into the binary-cache key: a new release never loads an old binary.
constexpr const char* RefractaCacheVersion = "refracta-0.1.0";

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

std::string BuildLog(cl_program program, cl_device_id device)
{
  size_t size = 0;
  clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
  std::string log(size, '\0');
  if (size > 0)
  {
    clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, size, &log[0], nullptr);
  }
  log.resize(std::strlen(log.c_str()));
  constexpr size_t MaximumLog = 16384;
  if (log.size() > MaximumLog)
  {
    log = log.substr(0, MaximumLog) + "\n... (build log truncated)";
  }
  return log;
}

vtkSmartPointer<vtkOpenCLContext>& DefaultContext()
{
  static vtkSmartPointer<vtkOpenCLContext> instance;
  return instance;
}
}

//------------------------------------------------------------------------------
vtkOpenCLContext::vtkOpenCLContext()
  : DiskCache(vtkSmartPointer<vtkOpenCLBinaryCache>::New())
{
}

//------------------------------------------------------------------------------
vtkOpenCLContext::~vtkOpenCLContext()
{
  for (auto& entry : this->Programs)
  {
    clReleaseProgram(entry.second);
  }
  if (this->Queue)
  {
    clReleaseCommandQueue(this->Queue);
  }
  if (this->Context)
  {
    clReleaseContext(this->Context);
  }
  this->SetDeviceSelection(nullptr);
  this->SetBinaryCacheDirectory(nullptr);
  this->SetSimulatedMissingExtensions(nullptr);
}

//------------------------------------------------------------------------------
vtkOpenCLContext* vtkOpenCLContext::GetDefault()
{
  auto& instance = DefaultContext();
  if (!instance)
  {
    instance = vtkSmartPointer<vtkOpenCLContext>::New();
  }
  return instance;
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
double vtkOpenCLContext::ChooseFixedPointScale(double largestSum)
{
  if (!(largestSum > 0.0) || !std::isfinite(largestSum))
  {
    return 4294967296.0;
  }
  // Largest power of two with largestSum * scale <= 2^62 (one bit of headroom below 2^63).
  const int exponent = 62 - static_cast<int>(std::ceil(std::log2(largestSum)));
  return std::ldexp(1.0, std::max(-1000, std::min(exponent, 1000)));
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
void vtkOpenCLContext::ReportError(const std::string& message, vtkObject* reporter)
{
  this->LastErrorMessage = message;
  vtkObject* target = reporter ? reporter : this;
  vtkErrorWithObjectMacro(target, << message);
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::Check(cl_int status, const char* call, vtkObject* reporter)
{
  if (status == CL_SUCCESS)
  {
    return true;
  }
  std::ostringstream msg;
  msg << "OpenCL call " << call << " failed with " << GetErrorName(status) << " (" << status
      << ") on device '" << this->DeviceName << "'.";
  this->ReportError(msg.str(), reporter);
  return false;
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::Initialize()
{
  if (!this->Initialized)
  {
    this->Initialized = true;
    this->Ready = this->SelectDevice();
  }
  return this->Ready;
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
std::string vtkOpenCLContext::ResolveCacheDirectory() const
{
  if (this->BinaryCacheDirectory && *this->BinaryCacheDirectory)
  {
    return this->BinaryCacheDirectory;
  }
  if (const char* dir = std::getenv("REFRACTA_KERNEL_CACHE_DIR"))
  {
    if (*dir)
    {
      return dir;
    }
  }
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"))
  {
    if (*xdg)
    {
      return std::string(xdg) + "/refracta/kernels";
    }
  }
  if (const char* home = std::getenv("HOME"))
  {
    if (*home)
    {
      return std::string(home) + "/.cache/refracta/kernels";
    }
  }
  return std::string();
}

//------------------------------------------------------------------------------
std::string vtkOpenCLContext::CacheKey(const std::string& source, const std::string& options) const
{
  std::string key = RefractaCacheVersion;
  for (const std::string* part : { &this->PlatformName, &this->PlatformVersion, &this->DeviceName,
         &this->DeviceVersion, &this->DriverVersion, &options, &source })
  {
    key += '\x1f';
    key += *part;
  }
  return key;
}

//------------------------------------------------------------------------------
cl_program vtkOpenCLContext::GetProgram(
  const std::vector<std::string>& kernelFiles, const std::string& options, vtkObject* reporter)
{
  std::string label;
  const std::string source = this->ConcatenateKernelFiles(kernelFiles, label, reporter);
  return source.empty() ? nullptr : this->GetProgramFromSource(source, options, label, reporter);
}

//------------------------------------------------------------------------------
std::string vtkOpenCLContext::ConcatenateKernelFiles(
  const std::vector<std::string>& kernelFiles, std::string& labelOut, vtkObject* reporter)
{
  std::string source;
  std::ostringstream label;
  int line = 1;
  for (const std::string& file : kernelFiles)
  {
    const char* text = vtkOpenCLKernelLibrary::GetKernelSource(file.c_str());
    if (!text)
    {
      std::ostringstream msg;
      msg << "No embedded OpenCL kernel file named '" << file << "'; the embedded files are:";
      for (int i = 0; i < vtkOpenCLKernelLibrary::GetNumberOfKernelFiles(); ++i)
      {
        msg << " " << vtkOpenCLKernelLibrary::GetKernelFileName(i);
      }
      this->ReportError(msg.str(), reporter);
      return std::string();
    }
    std::string piece(text);
    if (!piece.empty() && piece.back() != '\n')
    {
      piece += '\n';
    }
    const int lines = static_cast<int>(std::count(piece.begin(), piece.end(), '\n'));
    label << (line > 1 ? ", " : "") << file << " = lines " << line << "-" << line + lines - 1;
    line += lines;
    source += piece;
  }
  labelOut = label.str();
  return source;
}

//------------------------------------------------------------------------------
std::string vtkOpenCLContext::GetBinaryCachePath(
  const std::vector<std::string>& kernelFiles, const std::string& options)
{
  std::string label;
  const std::string source = this->ConcatenateKernelFiles(kernelFiles, label, nullptr);
  if (source.empty() || !this->Initialize() || !this->UseBinaryCache)
  {
    return std::string();
  }
  this->UpdateBinaryCacheDirectory();
  return this->DiskCache->GetEntryPath(this->CacheKey(source, options));
}

//------------------------------------------------------------------------------
void vtkOpenCLContext::UpdateBinaryCacheDirectory()
{
  const std::string directory = this->UseBinaryCache ? this->ResolveCacheDirectory() : "";
  if (directory != this->DiskCache->GetDirectory())
  {
    this->DiskCache->SetDirectory(directory);
    this->WarnedAboutDiskCache = false;
  }
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
cl_program vtkOpenCLContext::GetProgramFromSource(const std::string& source,
  const std::string& options, const std::string& label, vtkObject* reporter)
{
  if (!this->Initialize())
  {
    this->ReportError(
      "Cannot build OpenCL program (" + label + "): no OpenCL device is available.", reporter);
    return nullptr;
  }
  const std::string key = this->CacheKey(source, options);
  std::lock_guard<std::mutex> lock(this->ProgramsMutex);
  auto found = this->Programs.find(key);
  if (found != this->Programs.end())
  {
    ++this->NumberOfMemoryCacheHits;
    return found->second;
  }

  if (!this->CheckRequiredExtensions(source, label, reporter))
  {
    return nullptr;
  }
  this->UpdateBinaryCacheDirectory();
  cl_program program = this->LoadBinary(key, options);
  if (program)
  {
    ++this->NumberOfBinaryLoads;
  }
  else
  {
    program = this->BuildFromSource(source, options, label, reporter);
    if (!program)
    {
      return nullptr;
    }
    ++this->NumberOfSourceBuilds;
    this->SaveBinary(program, key);
  }
  this->Programs[key] = program;
  return program;
}

//------------------------------------------------------------------------------
cl_program vtkOpenCLContext::BuildFromSource(const std::string& source, const std::string& options,
  const std::string& label, vtkObject* reporter)
{
  const char* text = source.c_str();
  const size_t length = source.size();
  cl_int error = CL_SUCCESS;
  cl_program program = clCreateProgramWithSource(this->Context, 1, &text, &length, &error);
  if (!this->Check(error, "clCreateProgramWithSource", reporter))
  {
    return nullptr;
  }
  error = clBuildProgram(program, 1, &this->Device, options.c_str(), nullptr, nullptr);
  if (error != CL_SUCCESS)
  {
    std::ostringstream msg;
    msg << "OpenCL call clBuildProgram failed with " << GetErrorName(error) << " (" << error
        << ") on device '" << this->DeviceName << "' for program [" << label << "] with options '"
        << options << "'. Build log:\n"
        << BuildLog(program, this->Device);
    clReleaseProgram(program);
    this->ReportError(msg.str(), reporter);
    return nullptr;
  }
  return program;
}

//------------------------------------------------------------------------------
cl_program vtkOpenCLContext::LoadBinary(const std::string& key, const std::string& options)
{
  std::vector<unsigned char> binary;
  std::string why;
  const int found = this->DiskCache->Load(key, binary, &why);
  if (found == vtkOpenCLBinaryCache::REJECTED)
  {
    ++this->NumberOfRejectedBinaries;
    vtkDebugMacro("Kernel-cache entry rejected (" << why << "); rebuilding it from source.");
    return nullptr;
  }
  if (found != vtkOpenCLBinaryCache::LOADED)
  {
    return nullptr;
  }
  const unsigned char* data = binary.data();
  const size_t size = binary.size();
  cl_int binaryStatus = CL_SUCCESS;
  cl_int error = CL_SUCCESS;
  cl_program program =
    clCreateProgramWithBinary(this->Context, 1, &this->Device, &size, &data, &binaryStatus, &error);
  if (error == CL_SUCCESS && binaryStatus == CL_SUCCESS &&
    clBuildProgram(program, 1, &this->Device, options.c_str(), nullptr, nullptr) == CL_SUCCESS)
  {
    return program;
  }
  // The checksum held but the driver refuses the binary (another driver build wrote it): the
  // entry is useless, so it is deleted and rebuilt like a corrupt one.
  if (program)
  {
    clReleaseProgram(program);
  }
  ++this->NumberOfRejectedBinaries;
  this->DiskCache->Remove(key);
  return nullptr;
}

//------------------------------------------------------------------------------
void vtkOpenCLContext::SaveBinary(cl_program program, const std::string& key)
{
  if (!this->DiskCache->IsEnabled())
  {
    return;
  }
  size_t size = 0;
  if (clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof(size), &size, nullptr) !=
      CL_SUCCESS ||
    size == 0)
  {
    return;
  }
  std::vector<unsigned char> binary(size);
  unsigned char* data = binary.data();
  if (clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof(data), &data, nullptr) != CL_SUCCESS)
  {
    return;
  }
  if (!this->DiskCache->Store(key, binary) && !this->DiskCache->IsEnabled() &&
    !this->WarnedAboutDiskCache)
  {
    this->WarnedAboutDiskCache = true;
    vtkWarningMacro("OpenCL kernel cache off: "
      << this->DiskCache->GetDisabledReason()
      << ". Kernels are compiled from source in this process; set REFRACTA_KERNEL_CACHE_DIR to a "
         "writable folder to keep them between runs.");
  }
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::BuildProgram(const char* kernelFiles, const char* options)
{
  std::vector<std::string> files;
  std::istringstream list(kernelFiles ? kernelFiles : "");
  std::string file;
  while (std::getline(list, file, ','))
  {
    file.erase(0, file.find_first_not_of(" \t"));
    file.erase(file.find_last_not_of(" \t") + 1);
    if (!file.empty())
    {
      files.push_back(file);
    }
  }
  return this->GetProgram(files, options ? options : "") != nullptr;
}

//------------------------------------------------------------------------------
vtkOpenCLKernel vtkOpenCLContext::CreateKernel(
  cl_program program, const char* name, vtkObject* reporter)
{
  cl_int error = CL_SUCCESS;
  cl_kernel kernel = program ? clCreateKernel(program, name, &error) : nullptr;
  if (!program)
  {
    error = CL_INVALID_PROGRAM;
  }
  const std::string call = std::string("clCreateKernel(") + name + ")";
  if (!this->Check(error, call.c_str(), reporter))
  {
    return vtkOpenCLKernel();
  }
  return vtkOpenCLKernel(kernel);
}

//------------------------------------------------------------------------------
vtkOpenCLBuffer vtkOpenCLContext::CreateBuffer(
  cl_mem_flags flags, size_t bytes, const void* hostData, const char* what, vtkObject* reporter)
{
  if (!this->Initialize())
  {
    this->ReportError(
      std::string("Cannot create buffer ") + what + ": no OpenCL device.", reporter);
    return vtkOpenCLBuffer();
  }
  // The device allocation is rounded up to 16 bytes (OpenCL forbids empty buffers, and kernels
  // may bind one of a 1x1x1 grid as a vector); exactly `bytes` of host data are written, so a
  // caller's padding never reads past its host array.
  flags &= ~static_cast<cl_mem_flags>(CL_MEM_COPY_HOST_PTR | CL_MEM_USE_HOST_PTR);
  const size_t allocated = (std::max<size_t>(bytes, 1) + 15) / 16 * 16;
  cl_int error = CL_SUCCESS;
  cl_mem buffer = clCreateBuffer(this->Context, flags, allocated, nullptr, &error);
  std::ostringstream call;
  call << "clCreateBuffer(" << what << ", " << bytes << " bytes)";
  if (!this->Check(error, call.str().c_str(), reporter))
  {
    return vtkOpenCLBuffer();
  }
  vtkOpenCLBuffer owned(buffer);
  if (hostData && !this->WriteBuffer(buffer, bytes, hostData, reporter))
  {
    return vtkOpenCLBuffer();
  }
  return owned;
}

//------------------------------------------------------------------------------
void vtkOpenCLContext::SetFailingEnqueue(int n)
{
  this->FailingEnqueue = n > 0 ? this->NumberOfEnqueues + n : 0;
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::InjectedFault(const char* call, vtkObject* reporter)
{
  ++this->NumberOfEnqueues;
  if (this->FailingEnqueue <= 0 || this->NumberOfEnqueues != this->FailingEnqueue)
  {
    return false;
  }
  this->FailingEnqueue = 0;
  const std::string injected = std::string(call) + " [injected fault, SetFailingEnqueue]";
  return !this->Check(CL_OUT_OF_RESOURCES, injected.c_str(), reporter);
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::WriteBuffer(
  cl_mem buffer, size_t bytes, const void* data, vtkObject* reporter)
{
  return bytes == 0 ||
    (!this->InjectedFault("clEnqueueWriteBuffer", reporter) &&
      this->Check(
        clEnqueueWriteBuffer(this->Queue, buffer, CL_TRUE, 0, bytes, data, 0, nullptr, nullptr),
        "clEnqueueWriteBuffer", reporter));
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::ReadBuffer(cl_mem buffer, size_t bytes, void* data, vtkObject* reporter)
{
  return bytes == 0 ||
    (!this->InjectedFault("clEnqueueReadBuffer", reporter) &&
      this->Check(
        clEnqueueReadBuffer(this->Queue, buffer, CL_TRUE, 0, bytes, data, 0, nullptr, nullptr),
        "clEnqueueReadBuffer", reporter));
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::ZeroBuffer(cl_mem buffer, size_t bytes, vtkObject* reporter)
{
  const cl_uint zero = 0;
  return bytes == 0 ||
    (!this->InjectedFault("clEnqueueFillBuffer", reporter) &&
      this->Check(clEnqueueFillBuffer(this->Queue, buffer, &zero, sizeof(zero), 0,
                    (bytes / sizeof(zero)) * sizeof(zero), 0, nullptr, nullptr),
        "clEnqueueFillBuffer", reporter));
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::CheckLaunch(cl_kernel kernel, const size_t* localSize, cl_uint dimensions,
  const char* label, vtkObject* reporter)
{
  size_t kernelMaximum = 0;
  cl_ulong kernelLocal = 0;
  clGetKernelWorkGroupInfo(kernel, this->Device, CL_KERNEL_WORK_GROUP_SIZE, sizeof(kernelMaximum),
    &kernelMaximum, nullptr);
  clGetKernelWorkGroupInfo(
    kernel, this->Device, CL_KERNEL_LOCAL_MEM_SIZE, sizeof(kernelLocal), &kernelLocal, nullptr);
  size_t group = 1;
  for (cl_uint d = 0; localSize && d < dimensions; ++d)
  {
    group *= std::max<size_t>(localSize[d], 1);
  }
  size_t allowed = this->GetMaximumWorkGroupSize();
  if (kernelMaximum > 0)
  {
    allowed = std::min(allowed, kernelMaximum);
  }
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
bool vtkOpenCLContext::RunKernel(cl_kernel kernel, cl_uint dimensions, const size_t* globalSize,
  const size_t* localSize, const char* label, vtkObject* reporter, const size_t* globalOffset)
{
  size_t global[3] = { 1, 1, 1 };
  for (cl_uint d = 0; d < dimensions && d < 3; ++d)
  {
    global[d] = globalSize[d];
    if (global[d] == 0)
    {
      return true; // nothing to do; OpenCL rejects empty ranges
    }
    if (localSize && localSize[d] > 0)
    {
      global[d] = (global[d] + localSize[d] - 1) / localSize[d] * localSize[d];
    }
  }
  const std::string call = std::string("clEnqueueNDRangeKernel(") + label + ")";
  return this->CheckLaunch(kernel, localSize, dimensions, label, reporter) &&
    !this->InjectedFault(call.c_str(), reporter) &&
    this->Check(clEnqueueNDRangeKernel(this->Queue, kernel, dimensions, globalOffset, global,
                  localSize, 0, nullptr, nullptr),
      call.c_str(), reporter);
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

size_t vtkOpenCLContext::GetMaximumWorkGroupSize() const
{
  const size_t device = this->MaxWorkGroupSize > 0 ? this->MaxWorkGroupSize : 1;
  return this->SimulatedMaximumWorkGroupSize > 0
    ? std::min(device, static_cast<size_t>(this->SimulatedMaximumWorkGroupSize))
    : device;
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::Finish(vtkObject* reporter)
{
  return this->Check(clFinish(this->Queue), "clFinish", reporter);
}

//------------------------------------------------------------------------------
void vtkOpenCLContext::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DeviceSelection: " << (this->DeviceSelection ? this->DeviceSelection : "(none)")
     << "\n";
  os << indent << "Ready: " << this->Ready << "\n";
  os << indent << "Platform: " << this->PlatformName << " (" << this->PlatformVersion << ")\n";
  os << indent << "Device: " << this->DeviceName << " [" << (this->IsGPU ? "GPU" : "not GPU")
     << "], " << this->DeviceVersion << ", driver " << this->DriverVersion << "\n";
  os << indent << "ComputeUnits: " << this->ComputeUnits << "\n";
  os << indent << "GlobalMemoryMiB: " << this->GetGlobalMemoryMiB() << "\n";
  os << indent << "BinaryCacheDirectory: " << this->ResolveCacheDirectory()
     << (this->UseBinaryCache ? "" : " (disabled)") << "\n";
  os << indent << "NumberOfSourceBuilds: " << this->NumberOfSourceBuilds << "\n";
  os << indent << "NumberOfBinaryLoads: " << this->NumberOfBinaryLoads << "\n";
  os << indent << "NumberOfMemoryCacheHits: " << this->NumberOfMemoryCacheHits << "\n";
  os << indent << "NumberOfRejectedBinaries: " << this->NumberOfRejectedBinaries << "\n";
  os << indent << "NumberOfEnqueues: " << this->NumberOfEnqueues << "\n";
  os << indent << "MaximumAllocationBytes: " << this->GetMaximumAllocationBytes() << "\n";
  os << indent << "GlobalMemoryBytes: " << this->GetGlobalMemoryBytes() << "\n";
  os << indent << "LocalMemoryBytes: " << this->GetLocalMemoryBytes() << "\n";
  os << indent << "HostMemoryBytes: " << this->GetHostMemoryBytes() << "\n";
  os << indent << "MaximumWorkGroupSize: " << this->GetMaximumWorkGroupSize() << "\n";
  os << indent << "DiskCache:\n";
  this->DiskCache->PrintSelf(os, indent.GetNextIndent());
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
