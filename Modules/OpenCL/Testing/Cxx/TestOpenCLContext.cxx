// Tests of vtkOpenCLContext on the machine's OpenCL device (PoCL's CPU device in CI): an
// embedded kernel runs and its result is checked; a broken kernel yields the build log and the
// process survives; programs come from the memory cache and, in a new context (a new process),
// from the disk binary cache instead of being recompiled (on PoCL only where a folder is named); a
// bad device selection is explained; device copies of host arrays (vtkOpenCLDeviceArrays) last
// exactly while their arrays do.
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLDeviceArrays.h"
#include "vtkOpenCLKernelLibrary.h"
#include "vtkOpenCLKernelProfile.h"
#include "vtkTestErrorObserver.h"

#include <vtksys/Directory.hxx>
#include <vtksys/SystemTools.hxx>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace
{
bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

std::string FreshCacheDirectory(const char* name)
{
  const char* base = std::getenv("REFRACTA_TEST_OUTPUT_DIR");
  std::string dir = std::string(base ? base : ".") + "/" + name;
  vtksys::SystemTools::RemoveADirectory(dir);
  return dir;
}
}

TEST(OpenCLKernelLibrary, EmbedsKernelFiles)
{
  EXPECT_GE(vtkOpenCLKernelLibrary::GetNumberOfKernelFiles(), 2);
  const char* source = vtkOpenCLKernelLibrary::GetKernelSource("selftest.cl");
  ASSERT_NE(source, nullptr);
  EXPECT_TRUE(Contains(source, "__kernel void refracta_saxpy"));
  EXPECT_EQ(vtkOpenCLKernelLibrary::GetKernelSource("missing.cl"), nullptr);
}

TEST(OpenCLContext, SaxpyRunsAndIsCorrect)
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  ASSERT_TRUE(context->Initialize()) << context->GetLastErrorMessage();
  std::cout << "device: " << context->GetDeviceName() << " on " << context->GetPlatformName()
            << "\n";

  cl_program program = context->GetProgram({ "refracta_atomics.cl", "selftest.cl" }, "");
  ASSERT_NE(program, nullptr) << context->GetLastErrorMessage();
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_saxpy");
  ASSERT_TRUE(kernel);

  const unsigned int n = 100003; // not a multiple of any work-group size
  std::vector<float> x(n), y(n);
  for (unsigned int i = 0; i < n; ++i)
  {
    x[i] = static_cast<float>(i % 1000) * 0.5f;
    y[i] = static_cast<float>(i % 17);
  }
  vtkOpenCLBuffer xBuffer =
    context->CreateBuffer(CL_MEM_READ_ONLY, n * sizeof(float), x.data(), "x");
  vtkOpenCLBuffer yBuffer =
    context->CreateBuffer(CL_MEM_READ_WRITE, n * sizeof(float), y.data(), "y");
  ASSERT_TRUE(xBuffer && yBuffer);
  const float a = 3.0f;
  ASSERT_EQ(vtkOpenCLSetKernelArgs(kernel.Get(), a, xBuffer.Get(), yBuffer.Get(), n), CL_SUCCESS);
  const size_t global = n, local = 64;
  ASSERT_TRUE(context->RunKernel(kernel.Get(), 1, &global, &local, "refracta_saxpy"));
  std::vector<float> result(n);
  ASSERT_TRUE(context->ReadBuffer(yBuffer.Get(), n * sizeof(float), result.data()));
  for (unsigned int i = 0; i < n; ++i)
  {
    ASSERT_EQ(result[i], a * x[i] + y[i]) << "at " << i;
  }
}

TEST(OpenCLContext, BrokenKernelReportsBuildLog)
{
  vtkNew<vtkOpenCLContext> context;
  ASSERT_TRUE(context->Initialize());
  vtkNew<vtkTest::ErrorObserver> observer;
  context->AddObserver(vtkCommand::ErrorEvent, observer);
  const std::string broken = "__kernel void broken(__global float* x)\n"
                             "{\n"
                             "  x[get_global_id(0)] = undeclared_variable * 2.0f;\n"
                             "}\n";
  cl_program program = context->GetProgramFromSource(broken, "-DFOO=1", "broken.cl");
  EXPECT_EQ(program, nullptr);
  ASSERT_TRUE(observer->GetError());
  const std::string msg = observer->GetErrorMessage();
  EXPECT_TRUE(Contains(msg, "clBuildProgram")) << msg;
  EXPECT_TRUE(Contains(msg, "CL_BUILD_PROGRAM_FAILURE (-11)")) << msg;
  EXPECT_TRUE(Contains(msg, "broken.cl")) << msg;
  EXPECT_TRUE(Contains(msg, "-DFOO=1")) << msg;
  EXPECT_TRUE(Contains(msg, "Build log:")) << msg;
  EXPECT_TRUE(Contains(msg, "undeclared_variable")) << msg; // the compiler's own words
  EXPECT_EQ(context->GetNumberOfSourceBuilds(), 0);

  // A good program still builds in the same context afterwards.
  observer->Clear();
  EXPECT_NE(context->GetProgram({ "refracta_atomics.cl", "selftest.cl" }, ""), nullptr);
  EXPECT_FALSE(observer->GetError());
}

TEST(OpenCLContext, ErrorsNameCallAndCode)
{
  vtkNew<vtkOpenCLContext> context;
  ASSERT_TRUE(context->Initialize());
  vtkNew<vtkTest::ErrorObserver> observer;
  context->AddObserver(vtkCommand::ErrorEvent, observer);

  cl_program program = context->GetProgram({ "no_such_file.cl" }, "");
  EXPECT_EQ(program, nullptr);
  EXPECT_TRUE(Contains(observer->GetErrorMessage(), "no_such_file.cl"));
  EXPECT_TRUE(Contains(observer->GetErrorMessage(), "selftest.cl")); // lists what exists
  observer->Clear();

  program = context->GetProgram({ "refracta_atomics.cl", "selftest.cl" }, "");
  ASSERT_NE(program, nullptr);
  vtkOpenCLKernel kernel = context->CreateKernel(program, "no_such_kernel");
  EXPECT_FALSE(kernel);
  EXPECT_TRUE(Contains(observer->GetErrorMessage(), "clCreateKernel(no_such_kernel)"));
  EXPECT_TRUE(Contains(observer->GetErrorMessage(), "CL_INVALID_KERNEL_NAME"));
  observer->Clear();

  EXPECT_FALSE(context->Check(CL_OUT_OF_RESOURCES, "clFakeCall"));
  EXPECT_TRUE(
    Contains(observer->GetErrorMessage(), "clFakeCall failed with CL_OUT_OF_RESOURCES (-5)"));
  EXPECT_STREQ(vtkOpenCLContext::GetErrorName(-30), "CL_INVALID_VALUE");
  EXPECT_STREQ(vtkOpenCLContext::GetErrorName(-1001), "CL_PLATFORM_NOT_FOUND_KHR");
}

TEST(OpenCLContext, ProgramsAreCachedInMemoryAndOnDisk)
{
  const std::string cacheDir = FreshCacheDirectory("binary-cache-test");
  const std::vector<std::string> files = { "refracta_atomics.cl", "selftest.cl" };
  {
    vtkNew<vtkOpenCLContext> first;
    first->SetBinaryCacheDirectory(cacheDir.c_str());
    ASSERT_NE(first->GetProgram(files, "-DREFRACTA_FIXED_SCALE=1024.0f"), nullptr);
    EXPECT_EQ(first->GetNumberOfSourceBuilds(), 1);
    EXPECT_EQ(first->GetNumberOfBinaryLoads(), 0);
    // Same source and options: the memory cache answers.
    ASSERT_NE(first->GetProgram(files, "-DREFRACTA_FIXED_SCALE=1024.0f"), nullptr);
    EXPECT_EQ(first->GetNumberOfMemoryCacheHits(), 1);
    EXPECT_EQ(first->GetNumberOfSourceBuilds(), 1);
    // Other options are another program.
    ASSERT_NE(first->GetProgram(files, "-DREFRACTA_FIXED_SCALE=2048.0f"), nullptr);
    EXPECT_EQ(first->GetNumberOfSourceBuilds(), 2);
  }
  {
    vtkNew<vtkOpenCLContext> second; // stands for a second process start
    second->SetBinaryCacheDirectory(cacheDir.c_str());
    cl_program program = second->GetProgram(files, "-DREFRACTA_FIXED_SCALE=1024.0f");
    ASSERT_NE(program, nullptr);
    EXPECT_EQ(second->GetNumberOfSourceBuilds(), 0);
    EXPECT_EQ(second->GetNumberOfBinaryLoads(), 1);
    // The program loaded from a binary runs.
    vtkOpenCLKernel kernel = second->CreateKernel(program, "refracta_saxpy");
    EXPECT_TRUE(kernel);
  }
  {
    // A corrupt binary is ignored and the source compiled instead.
    vtksys::Directory listing;
    ASSERT_TRUE(listing.Load(cacheDir));
    for (unsigned long i = 0; i < listing.GetNumberOfFiles(); ++i)
    {
      const std::string name = listing.GetFile(i);
      if (name.size() > 6 && name.substr(name.size() - 6) == ".clbin")
      {
        FILE* f = std::fopen((cacheDir + "/" + name).c_str(), "wb");
        std::fputs("not a binary", f);
        std::fclose(f);
      }
    }
    vtkNew<vtkOpenCLContext> third;
    third->SetBinaryCacheDirectory(cacheDir.c_str());
    EXPECT_NE(third->GetProgram(files, "-DREFRACTA_FIXED_SCALE=1024.0f"), nullptr);
    EXPECT_EQ(third->GetNumberOfSourceBuilds(), 1);
  }
}

// On PoCL, which keeps compiled programs in its own disk cache, Refracta's binary cache stays off
// unless a folder is named: saving a PoCL binary costs code generation for every kernel of the
// program. With PoCL's cache switched off (POCL_KERNEL_CACHE=0), or a folder named, it is on.
TEST(OpenCLContext, BinaryCacheDefersToTheDriversOwn)
{
  vtkNew<vtkOpenCLContext> probe;
  ASSERT_TRUE(probe->Initialize());
  std::ostringstream printed;
  probe->PrintSelf(printed, vtkIndent());
  const bool pocl = Contains(printed.str(), "Portable Computing Language");
  if (!pocl)
  {
    EXPECT_FALSE(probe->GetDriverCachesPrograms());
    GTEST_SKIP() << "not PoCL: the binary cache is always on";
  }
  // Environment variables this test changes, restored at the end.
  struct SavedVariable
  {
    std::string Name, Value;
    bool Set;
    explicit SavedVariable(const char* name)
      : Name(name)
      , Value(std::getenv(name) ? std::getenv(name) : "")
      , Set(std::getenv(name) != nullptr)
    {
    }
    ~SavedVariable()
    {
      if (this->Set)
      {
        setenv(this->Name.c_str(), this->Value.c_str(), 1);
      }
      else
      {
        unsetenv(this->Name.c_str());
      }
    }
  };
  SavedVariable savedDirectory("REFRACTA_KERNEL_CACHE_DIR"), savedSwitch("POCL_KERNEL_CACHE"),
    savedPoclDirectory("POCL_CACHE_DIR");
  const std::vector<std::string> files = { "refracta_atomics.cl", "selftest.cl" };
  unsetenv("REFRACTA_KERNEL_CACHE_DIR");
  unsetenv("POCL_KERNEL_CACHE");
  const std::string poclCache = FreshCacheDirectory("binary-cache-pocl");
  setenv("POCL_CACHE_DIR", poclCache.c_str(), 1);
  {
    vtkNew<vtkOpenCLContext> context;
    ASSERT_NE(context->GetProgram(files, "-DREFRACTA_FIXED_SCALE=512.0f"), nullptr);
    EXPECT_TRUE(context->GetDriverCachesPrograms());
    EXPECT_EQ(context->GetBinaryCachePath(files, "-DREFRACTA_FIXED_SCALE=512.0f"), "");
    EXPECT_EQ(context->GetNumberOfSourceBuilds(), 1);

    // A named folder is used whatever the driver does.
    const std::string dir = FreshCacheDirectory("binary-cache-named");
    context->SetBinaryCacheDirectory(dir.c_str());
    EXPECT_EQ(context->GetBinaryCachePath(files, "").rfind(dir, 0), 0u);
  }
  // PoCL reads a switch as on only when it starts with '1': "0", "false" and "" turn its cache off.
  for (const char* off : { "0", "false", "" })
  {
    setenv("POCL_KERNEL_CACHE", off, 1);
    vtkNew<vtkOpenCLContext> context;
    ASSERT_TRUE(context->Initialize());
    EXPECT_FALSE(context->GetDriverCachesPrograms()) << "'" << off << "'";
    EXPECT_NE(context->GetBinaryCachePath(files, ""), "") << "'" << off << "'";
  }
}

TEST(OpenCLContext, DeviceSelection)
{
  const std::string devices = vtkOpenCLContext::ListDevices();
  EXPECT_TRUE(Contains(devices, "0:0")) << devices;

  vtkNew<vtkOpenCLContext> byIndex;
  byIndex->SetDeviceSelection("0:0");
  EXPECT_TRUE(byIndex->Initialize());

  vtkNew<vtkOpenCLContext> byName;
  byName->SetDeviceSelection(vtkOpenCLContext::GetDefault()->GetPlatformName());
  EXPECT_TRUE(byName->Initialize()) << byName->GetLastErrorMessage();
  EXPECT_STREQ(byName->GetPlatformName(), vtkOpenCLContext::GetDefault()->GetPlatformName());

  vtkNew<vtkOpenCLContext> missing;
  vtkNew<vtkTest::ErrorObserver> observer;
  missing->AddObserver(vtkCommand::ErrorEvent, observer);
  missing->SetDeviceSelection("no-such-device-xyz");
  EXPECT_FALSE(missing->Initialize());
  EXPECT_FALSE(missing->Initialize()); // stays failed, no crash on a second call
  const std::string msg = observer->GetErrorMessage();
  EXPECT_TRUE(Contains(msg, "no-such-device-xyz")) << msg;
  EXPECT_TRUE(Contains(msg, "0:0")) << msg; // lists what is there
  // Anything needing the device now fails cleanly.
  EXPECT_EQ(missing->GetProgram({ "selftest.cl" }, ""), nullptr);
  EXPECT_FALSE(missing->CreateBuffer(CL_MEM_READ_WRITE, 16, nullptr, "probe"));
}

TEST(OpenCLContext, FixedPointScale)
{
  EXPECT_EQ(vtkOpenCLContext::ChooseFixedPointScale(1.0), std::ldexp(1.0, 62));
  EXPECT_EQ(vtkOpenCLContext::ChooseFixedPointScale(1000.0), std::ldexp(1.0, 52));
  EXPECT_LE(1000.0 * vtkOpenCLContext::ChooseFixedPointScale(1000.0), std::ldexp(1.0, 62));
  EXPECT_EQ(vtkOpenCLContext::ChooseFixedPointScale(0.0), std::ldexp(1.0, 32));
  EXPECT_EQ(vtkOpenCLContext::ChooseFixedPointScale(-5.0), std::ldexp(1.0, 32));
}

// Kernel profiling: off, launches leave nothing; on, every launch is counted under its label
// (also past the fold threshold of 256 pending events) with a positive device time, the labels
// keep their first-launch order and the total is their sum; Reset() forgets them.
TEST(OpenCLContext, KernelProfileCountsLaunchesAndDeviceTime)
{
  vtkNew<vtkOpenCLContext> context;
  ASSERT_TRUE(context->Initialize()) << context->GetLastErrorMessage();
  cl_program program = context->GetProgram({ "refracta_atomics.cl", "selftest.cl" }, "");
  ASSERT_NE(program, nullptr);
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_saxpy");
  const unsigned int n = 4096;
  std::vector<float> x(n, 1.0f);
  vtkOpenCLBuffer xBuffer =
    context->CreateBuffer(CL_MEM_READ_ONLY, n * sizeof(float), x.data(), "x");
  vtkOpenCLBuffer yBuffer =
    context->CreateBuffer(CL_MEM_READ_WRITE, n * sizeof(float), x.data(), "y");
  ASSERT_EQ(
    vtkOpenCLSetKernelArgs(kernel.Get(), 1.0f, xBuffer.Get(), yBuffer.Get(), n), CL_SUCCESS);
  const size_t global = n, local = 64;

  context->ProfileKernelsOff();
  ASSERT_TRUE(context->RunKernel(kernel.Get(), 1, &global, &local, "unprofiled"));
  EXPECT_EQ(context->GetKernelProfile()->GetNumberOfKernels(), 0);

  context->ProfileKernelsOn();
  for (int i = 0; i < 300; ++i)
  {
    ASSERT_TRUE(context->RunKernel(kernel.Get(), 1, &global, &local, "saxpy a"));
  }
  for (int i = 0; i < 3; ++i)
  {
    ASSERT_TRUE(context->RunKernel(kernel.Get(), 1, &global, &local, "saxpy b"));
  }
  vtkOpenCLKernelProfile* profile = context->GetKernelProfile();
  ASSERT_EQ(profile->GetNumberOfKernels(), 2);
  EXPECT_STREQ(profile->GetKernelLabel(0), "saxpy a");
  EXPECT_EQ(profile->GetNumberOfLaunches(0), 300);
  EXPECT_EQ(profile->GetNumberOfLaunches(1), 3);
  EXPECT_GT(profile->GetDeviceSeconds(0), 0.0);
  EXPECT_GT(profile->GetDeviceSeconds(1), 0.0);
  EXPECT_DOUBLE_EQ(
    profile->GetTotalDeviceSeconds(), profile->GetDeviceSeconds(0) + profile->GetDeviceSeconds(1));
  EXPECT_TRUE(Contains(profile->GetTable(), "| saxpy a | 300 |"));
  std::cout << profile->GetTable();
  profile->Reset();

  // Transfers and waits: bracketed entries with the host's time inside each call.
  std::vector<float> back(n);
  ASSERT_TRUE(context->WriteBuffer(xBuffer.Get(), n * sizeof(float), x.data()));
  ASSERT_TRUE(context->ReadBuffer(yBuffer.Get(), n * sizeof(float), back.data()));
  ASSERT_TRUE(context->ReadBuffer(yBuffer.Get(), n * sizeof(float), back.data()));
  ASSERT_TRUE(context->Finish());
  profile = context->GetKernelProfile();
  ASSERT_EQ(profile->GetNumberOfKernels(), 3);
  EXPECT_STREQ(profile->GetKernelLabel(0), "[write]");
  EXPECT_STREQ(profile->GetKernelLabel(1), "[read]");
  EXPECT_EQ(profile->GetNumberOfLaunches(1), 2);
  EXPECT_STREQ(profile->GetKernelLabel(2), "[finish]");
  EXPECT_EQ(profile->GetDeviceSeconds(2), 0.0); // no device work of its own
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_GT(profile->GetHostSeconds(i), 0.0) << profile->GetKernelLabel(i);
  }
  EXPECT_DOUBLE_EQ(profile->GetTotalHostSeconds(),
    profile->GetHostSeconds(0) + profile->GetHostSeconds(1) + profile->GetHostSeconds(2));
  EXPECT_EQ(profile->GetBytes(0), n * sizeof(float));
  EXPECT_EQ(profile->GetBytes(1), 2 * n * sizeof(float));
  EXPECT_EQ(profile->GetBytes(2), 0.0);
  EXPECT_EQ(profile->GetTotalBytes(), 3 * n * sizeof(float));
  profile->Reset();

  // A transfer asked for by an object is booked under its class: who moves how much.
  vtkNew<vtkFloatArray> requester;
  ASSERT_TRUE(context->ReadBuffer(yBuffer.Get(), n * sizeof(float), back.data(), requester));
  ASSERT_TRUE(context->ZeroBuffer(yBuffer.Get(), n * sizeof(float), requester));
  profile = context->GetKernelProfile();
  ASSERT_EQ(profile->GetNumberOfKernels(), 2);
  EXPECT_STREQ(profile->GetKernelLabel(0), "[read] vtkFloatArray");
  EXPECT_STREQ(profile->GetKernelLabel(1), "[fill] vtkFloatArray");
  EXPECT_EQ(profile->GetBytes(1), n * sizeof(float));
  EXPECT_TRUE(Contains(profile->GetTable(), "| [read] vtkFloatArray | 1 |"));
  profile->Reset();
  EXPECT_EQ(profile->GetNumberOfKernels(), 0);
  EXPECT_EQ(profile->GetTotalDeviceSeconds(), 0.0);
}

// A device copy stands for its array only while the array lives unmodified; the registry holds
// (retains) the buffers it remembers and releases them when it forgets.
TEST(OpenCLDeviceArrays, CopiesLastWhileTheirArraysDo)
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  ASSERT_TRUE(context->Initialize()) << context->GetLastErrorMessage();
  vtkNew<vtkOpenCLDeviceArrays> copies;
  const long long buffersBefore = vtkOpenCLLiveHandles(0);
  auto floats = [](vtkIdType tuples)
  {
    auto a = vtkSmartPointer<vtkFloatArray>::New();
    a->SetNumberOfComponents(3);
    a->SetNumberOfTuples(tuples);
    a->FillValue(1.0f);
    return a;
  };
  auto a = floats(100);
  auto b = floats(100);
  {
    vtkOpenCLBuffer buffer = context->CreateBuffer(CL_MEM_READ_WRITE, 1200, nullptr, "a", nullptr);
    vtkOpenCLBuffer small = context->CreateBuffer(CL_MEM_READ_WRITE, 1104, nullptr, "b", nullptr);
    ASSERT_TRUE(buffer && small);
    copies->Remember(a, buffer.Get(), &a);
    copies->Remember(b, small.Get(), &b); // smaller than b's values: not a copy
    EXPECT_EQ(copies->GetNumberOfArrays(), 1);
    EXPECT_EQ(copies->Find(a), buffer.Get());
    EXPECT_EQ(copies->Find(b), nullptr);
    copies->Remember(b, buffer.Get(), &b); // one buffer may hold two arrays' equal values
  }
  // The handles above are gone; the registry keeps the buffer alive (retained).
  EXPECT_EQ(copies->GetNumberOfArrays(), 2);
  EXPECT_DOUBLE_EQ(copies->GetBytes(), 2 * 1200.0);
  vtkOpenCLBuffer shared = copies->Share(a);
  ASSERT_TRUE(shared);
  EXPECT_EQ(copies->GetNumberOfHits(), 2); // Find(a) and Share(a); Find(b) missed
  std::vector<float> zeros(300, 0.0f);
  ASSERT_TRUE(context->WriteBuffer(shared.Get(), 1200, zeros.data()));

  a->SetValue(0, 2.0f); // modified on the host: its copy is stale
  a->Modified();
  EXPECT_EQ(copies->Find(a), nullptr);
  EXPECT_EQ(copies->GetNumberOfArrays(), 1);
  copies->ForgetOwner(&a); // no effect: a's copy is already gone
  EXPECT_EQ(copies->GetNumberOfArrays(), 1);
  copies->ForgetOwner(&b);
  EXPECT_EQ(copies->GetNumberOfArrays(), 0);

  copies->Remember(b, shared.Get());
  b = nullptr; // deleted: its copy goes with it
  EXPECT_EQ(copies->GetNumberOfArrays(), 0);
  copies->Remember(a, shared.Get());
  copies->Remember(nullptr, shared.Get());
  copies->Remember(a, nullptr); // forgets a's copy
  EXPECT_EQ(copies->Find(a), nullptr);
  copies->Remember(a, shared.Get());
  copies->Clear();
  EXPECT_EQ(copies->GetNumberOfArrays(), 0);
  shared.Reset();
  EXPECT_EQ(vtkOpenCLLiveHandles(0), buffersBefore);
  // The context's own registry is the one the passes share.
  EXPECT_NE(context->GetDeviceArrays(), nullptr);
}

// On a CPU device, buffers of 64 KiB and more start at distinct offsets within a 4 KiB page
// (regions of a larger allocation, aligned as the device requires), or where the caller places
// them; they hold, fill and return data like any buffer; off, or below 64 KiB, a buffer is a
// plain allocation.
TEST(OpenCLContext, StaggeredBuffersStartAtDistinctPageOffsets)
{
  vtkNew<vtkOpenCLContext> context;
  ASSERT_TRUE(context->Initialize()) << context->GetLastErrorMessage();
  context->StaggerBuffersOn();
  cl_uint alignBits = 0;
  clGetDeviceInfo(
    context->GetDevice(), CL_DEVICE_MEM_BASE_ADDR_ALIGN, sizeof(alignBits), &alignBits, nullptr);
  const size_t align = alignBits / 8;
  const bool staggers = !context->GetIsGPU() && align > 0 && align < 4096;
  auto offsetOf = [](cl_mem b)
  {
    size_t offset = 0;
    clGetMemObjectInfo(b, CL_MEM_OFFSET, sizeof(offset), &offset, nullptr);
    return offset;
  };
  const size_t bytes = 1 << 20;
  std::vector<vtkOpenCLBuffer> buffers;
  std::vector<size_t> offsets;
  for (int k = 0; k < 4; ++k)
  {
    buffers.push_back(context->CreateBuffer(CL_MEM_READ_WRITE, bytes, nullptr, "staggered"));
    ASSERT_TRUE(buffers.back());
    size_t size = 0;
    clGetMemObjectInfo(buffers.back().Get(), CL_MEM_SIZE, sizeof(size), &size, nullptr);
    EXPECT_EQ(size, bytes);
    offsets.push_back(offsetOf(buffers.back().Get()));
    if (staggers)
    {
      EXPECT_LT(offsets.back(), 4096u);
      EXPECT_EQ(offsets.back() % align, 0u);
    }
    else
    {
      EXPECT_EQ(offsets.back(), 0u);
    }
  }
  if (staggers)
  {
    std::vector<size_t> sorted = offsets;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::unique(sorted.begin(), sorted.end()), sorted.end()) << "distinct offsets";
  }
  // Data in, a fill, data out: a staggered buffer is an ordinary buffer to its users.
  std::vector<float> values(bytes / 4), back(bytes / 4);
  for (size_t i = 0; i < values.size(); ++i)
  {
    values[i] = static_cast<float>(i);
  }
  vtkOpenCLBuffer copy =
    context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes, values.data(), "copy");
  ASSERT_TRUE(copy);
  ASSERT_TRUE(context->ReadBuffer(copy.Get(), bytes, back.data()));
  EXPECT_EQ(back, values);
  ASSERT_TRUE(context->ZeroBuffer(buffers[1].Get(), bytes));
  ASSERT_TRUE(context->WriteBuffer(buffers[2].Get(), bytes, values.data()));
  ASSERT_TRUE(context->ReadBuffer(buffers[1].Get(), bytes, back.data()));
  EXPECT_EQ(back, std::vector<float>(bytes / 4, 0.0f));
  ASSERT_TRUE(context->ReadBuffer(buffers[2].Get(), bytes, back.data()));
  EXPECT_EQ(back, values);

  // A placed buffer: the offset asked for, rounded down to the alignment (mod 4 KiB).
  vtkOpenCLBuffer placed =
    context->CreateBufferAt(CL_MEM_READ_WRITE, bytes, nullptr, "placed", nullptr, 4096 + 1000);
  ASSERT_TRUE(placed);
  EXPECT_EQ(offsetOf(placed.Get()), staggers ? 1000 / align * align : 0u);
  vtkOpenCLBuffer small = context->CreateBuffer(CL_MEM_READ_WRITE, 4096, nullptr, "small");
  EXPECT_EQ(offsetOf(small.Get()), 0u);
  context->StaggerBuffersOff();
  vtkOpenCLBuffer plain = context->CreateBuffer(CL_MEM_READ_WRITE, bytes, nullptr, "plain");
  EXPECT_EQ(offsetOf(plain.Get()), 0u);
}
