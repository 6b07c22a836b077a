#include "vtkOpenCLContext.h"

#include "vtkObjectFactory.h"
#include "vtkOpenCLKernelLibrary.h"
#include "vtkSmartPointer.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <unistd.h>

vtkStandardNewMacro(vtkOpenCLContext);

namespace
{
// Refracta's version goes into the binary-cache key: a new release never loads an old binary.
constexpr const char* RefractaCacheVersion = "refracta-0.1.0";

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
  , KernelProfile(vtkSmartPointer<vtkOpenCLKernelProfile>::New())
  , DeviceArrays(vtkSmartPointer<vtkOpenCLDeviceArrays>::New())
{
  const char* profile = std::getenv("REFRACTA_PROFILE_KERNELS");
  this->ProfileKernels = profile && std::string(profile) == "1";
  const char* stagger = std::getenv("REFRACTA_STAGGER_BUFFERS");
  this->StaggerBuffers = !stagger || std::string(stagger) != "0";
}

//------------------------------------------------------------------------------
vtkOpenCLContext::~vtkOpenCLContext()
{
  // Wait for the queue's work before letting go: clReleaseCommandQueue does not wait, and PoCL
  // compiles a kernel's work-group function in its worker thread when the launch runs. A process
  // that returned from main with a launch still queued had that thread compiling while the exit
  // handlers destroyed LLVM's statics: an abort ("Failed to create kernel compiler pass") or a
  // segmentation fault in 7 to 8 of 10 runs of RefractaOpenCL.Faults with a cold PoCL cache.
  if (this->Queue)
  {
    clFinish(this->Queue);
  }
  this->KernelProfile->Reset(); // its events belong to this context
  this->DeviceArrays->Clear();  // and so do these buffers
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
std::string vtkOpenCLContext::FloatLiteral(double value)
{
  std::ostringstream s;
  s.precision(9);
  s << std::scientific << static_cast<float>(value) << "f";
  return s.str();
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
  if (this->GetDriverCachesPrograms())
  {
    return std::string();
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
bool vtkOpenCLContext::GetDriverCachesPrograms() const
{
  if (this->PlatformName.find("Portable Computing Language") == std::string::npos)
  {
    return false;
  }
  // PoCL's kernel cache is on when POCL_KERNEL_CACHE is unset or, as PoCL reads its switches,
  // starts with '1'; it lives in POCL_CACHE_DIR, else $XDG_CACHE_HOME/pocl, else ~/.cache/pocl:
  // with none of them set it has nowhere to write.
  const char* switchVariable = std::getenv("POCL_KERNEL_CACHE");
  if (switchVariable && switchVariable[0] != '1')
  {
    return false;
  }
  for (const char* variable : { "POCL_CACHE_DIR", "XDG_CACHE_HOME", "HOME" })
  {
    const char* value = std::getenv(variable);
    if (value && *value)
    {
      return true;
    }
  }
  return false;
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
  return this->CreateStaggeredBuffer(
    flags, bytes, hostData, what, reporter, std::numeric_limits<size_t>::max());
}

//------------------------------------------------------------------------------
vtkOpenCLBuffer vtkOpenCLContext::CreateBufferAt(cl_mem_flags flags, size_t bytes,
  const void* hostData, const char* what, vtkObject* reporter, size_t pageOffset)
{
  return this->CreateStaggeredBuffer(flags, bytes, hostData, what, reporter, pageOffset % 4096);
}

//------------------------------------------------------------------------------
vtkOpenCLBuffer vtkOpenCLContext::CreateStaggeredBuffer(cl_mem_flags flags, size_t bytes,
  const void* hostData, const char* what, vtkObject* reporter, size_t wanted)
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
  const size_t stagger = (flags & CL_MEM_ALLOC_HOST_PTR) ? 0 : this->Stagger(allocated, wanted);
  cl_int error = CL_SUCCESS;
  const double start = HostClock();
  cl_mem buffer = clCreateBuffer(this->Context, flags, allocated + stagger, nullptr, &error);
  std::ostringstream call;
  call << "clCreateBuffer(" << what << ", " << bytes << " bytes)";
  if (!this->Check(error, call.str().c_str(), reporter))
  {
    return vtkOpenCLBuffer();
  }
  if (stagger > 0)
  {
    // The buffer is the region past `stagger`; the allocation lives as long as the region does.
    const cl_buffer_region region = { stagger, allocated };
    const cl_mem_flags access = flags & (CL_MEM_READ_WRITE | CL_MEM_WRITE_ONLY | CL_MEM_READ_ONLY);
    cl_mem sub = clCreateSubBuffer(buffer, access, CL_BUFFER_CREATE_TYPE_REGION, &region, &error);
    clReleaseMemObject(buffer);
    buffer = sub;
    if (!this->Check(error, "clCreateSubBuffer(staggered buffer)", reporter))
    {
      return vtkOpenCLBuffer();
    }
  }
  this->RecordLaunch("[create buffer]", nullptr, start);
  vtkOpenCLBuffer owned(buffer);
  if (hostData && !this->WriteBuffer(buffer, bytes, hostData, reporter))
  {
    return vtkOpenCLBuffer();
  }
  return owned;
}

//------------------------------------------------------------------------------
size_t vtkOpenCLContext::Stagger(size_t bytes, size_t wanted)
{
  // The device's memory is the host's: its allocator returns every large block at the same
  // offset in a page, so element i of every buffer falls in the same cache set and 4 KiB alias. A
  // kernel that streams many buffers at once (the lattice step: two states, coefficients, source)
  // then loses to conflict misses and to loads falsely waiting on stores 4 KiB apart. Successive
  // buffers start at offsets that step through the 4 KiB page in the base-address alignment's
  // units, in an order that puts consecutive allocations far apart (an odd stride through a power
  // of two).
  constexpr size_t Page = 4096;
  constexpr size_t Smallest = 64 * 1024;
  // (A buffer near the allocation limit is not staggered: its extra page might not fit.)
  if (!this->StaggerBuffers || this->IsGPU || bytes < Smallest ||
    static_cast<double>(bytes + Page) > this->MaxAllocationBytes)
  {
    return 0;
  }
  if (this->BaseAddressAlignment == 0)
  {
    cl_uint bits = 0;
    clGetDeviceInfo(this->Device, CL_DEVICE_MEM_BASE_ADDR_ALIGN, sizeof(bits), &bits, nullptr);
    this->BaseAddressAlignment = std::max<size_t>(bits / 8, 1);
  }
  const size_t slots = Page / this->BaseAddressAlignment;
  if (slots < 2 || (slots & (slots - 1)) != 0)
  {
    return 0;
  }
  if (wanted != std::numeric_limits<size_t>::max())
  {
    return wanted / this->BaseAddressAlignment * this->BaseAddressAlignment;
  }
  return (this->NumberOfStaggeredBuffers++ * 13 % slots) * this->BaseAddressAlignment;
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
  cl_mem buffer, size_t bytes, const void* data, vtkObject* reporter, size_t offset)
{
  return bytes == 0 ||
    this->Enqueue("clEnqueueWriteBuffer", "[write]", bytes, reporter,
      [&](cl_event* event)
      {
        return clEnqueueWriteBuffer(
          this->Queue, buffer, CL_TRUE, offset, bytes, data, 0, nullptr, event);
      });
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::ReadBuffer(
  cl_mem buffer, size_t bytes, void* data, vtkObject* reporter, size_t offset)
{
  return bytes == 0 ||
    this->Enqueue("clEnqueueReadBuffer", "[read]", bytes, reporter,
      [&](cl_event* event)
      {
        return clEnqueueReadBuffer(
          this->Queue, buffer, CL_TRUE, offset, bytes, data, 0, nullptr, event);
      });
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::ZeroBuffer(cl_mem buffer, size_t bytes, vtkObject* reporter)
{
  const cl_uint zero = 0;
  return bytes == 0 ||
    this->Enqueue("clEnqueueFillBuffer", "[fill]", bytes, reporter,
      [&](cl_event* event)
      {
        return clEnqueueFillBuffer(this->Queue, buffer, &zero, sizeof(zero), 0,
          (bytes / sizeof(zero)) * sizeof(zero), 0, nullptr, event);
      });
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::CopyBuffer(
  cl_mem source, cl_mem destination, size_t bytes, vtkObject* reporter, size_t destinationOffset)
{
  return bytes == 0 ||
    this->Enqueue("clEnqueueCopyBuffer", "[copy]", bytes, reporter,
      [&](cl_event* event)
      {
        return clEnqueueCopyBuffer(
          this->Queue, source, destination, 0, destinationOffset, bytes, 0, nullptr, event);
      });
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::Enqueue(const char* call, const char* label, size_t bytes,
  vtkObject* reporter, const std::function<cl_int(cl_event*)>& enqueue)
{
  if (this->InjectedFault(call, reporter))
  {
    return false;
  }
  const double start = HostClock();
  cl_event event = nullptr;
  if (!this->Check(enqueue(this->ProfileKernels ? &event : nullptr), call, reporter))
  {
    return false;
  }
  const std::string entry =
    this->ProfileKernels && reporter ? std::string(label) + " " + reporter->GetClassName() : label;
  return this->RecordLaunch(entry.c_str(), event, start, bytes);
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
  const double start = HostClock();
  cl_event event = nullptr;
  return this->CheckLaunch(kernel, localSize, dimensions, label, reporter) &&
    !this->InjectedFault(call.c_str(), reporter) &&
    this->Check(clEnqueueNDRangeKernel(this->Queue, kernel, dimensions, globalOffset, global,
                  localSize, 0, nullptr, this->ProfileKernels ? &event : nullptr),
      call.c_str(), reporter) &&
    this->RecordLaunch(label, event, start);
}

//------------------------------------------------------------------------------
double vtkOpenCLContext::HostClock()
{
  using Clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::RecordLaunch(
  const char* label, cl_event event, double hostStart, size_t bytes)
{
  if (this->ProfileKernels)
  {
    this->KernelProfile->Record(
      label, vtkOpenCLEvent(event), HostClock() - hostStart, static_cast<double>(bytes));
  }
  else if (event)
  {
    clReleaseEvent(event);
  }
  return true;
}

//------------------------------------------------------------------------------
vtkOpenCLDeviceArrays* vtkOpenCLContext::GetDeviceArrays()
{
  return this->DeviceArrays;
}

//------------------------------------------------------------------------------
vtkOpenCLKernelProfile* vtkOpenCLContext::GetKernelProfile()
{
  if (this->Queue)
  {
    clFinish(this->Queue);
  }
  this->KernelProfile->Collect();
  return this->KernelProfile;
}

//------------------------------------------------------------------------------
bool vtkOpenCLContext::Finish(vtkObject* reporter)
{
  const double start = HostClock();
  return this->Check(clFinish(this->Queue), "clFinish", reporter) &&
    this->RecordLaunch("[finish]", nullptr, start);
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
  os << indent << "DriverCachesPrograms: " << (this->GetDriverCachesPrograms() ? "yes" : "no")
     << "\n";
  os << indent << "ProfileKernels: " << (this->ProfileKernels ? "on" : "off") << "\n";
  os << indent << "StaggerBuffers: " << (this->StaggerBuffers ? "on" : "off") << "\n";
  os << indent << "NumberOfSourceBuilds: " << this->NumberOfSourceBuilds << "\n";
  os << indent << "NumberOfBinaryLoads: " << this->NumberOfBinaryLoads << "\n";
  os << indent << "NumberOfMemoryCacheHits: " << this->NumberOfMemoryCacheHits << "\n";
  os << indent << "NumberOfRejectedBinaries: " << this->NumberOfRejectedBinaries << "\n";
  os << indent << "NumberOfEnqueues: " << this->NumberOfEnqueues << "\n";
  os << indent << "MaximumAllocationBytes: " << this->GetMaximumAllocationBytes() << "\n";
  os << indent << "GlobalMemoryBytes: " << this->GetGlobalMemoryBytes() << "\n";
  os << indent << "LocalMemoryBytes: " << this->GetLocalMemoryBytes() << "\n";
  os << indent << "DedicatedLocalMemory: " << (this->DedicatedLocalMemory ? "yes" : "no") << "\n";
  os << indent << "HostMemoryBytes: " << this->GetHostMemoryBytes() << "\n";
  os << indent << "MaximumWorkGroupSize: " << this->GetMaximumWorkGroupSize() << "\n";
  os << indent << "DiskCache:\n";
  this->DiskCache->PrintSelf(os, indent.GetNextIndent());
}
