// Faults of the OpenCL layer, each provoked on purpose: damaged kernel-cache entries (truncated,
// corrupt, foreign) are detected and rebuilt; an unwritable cache folder costs one warning and
// nothing else; processes writing the same entry at once leave one valid entry and no temporary
// files; a device without a needed extension, with small work-groups or small local memory is
// refused with a message naming the device and the limit; an injected enqueue failure is
// reported and the context stays usable; the live-handle counts return to where they were.
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLMemoryPlan.h"
#include "vtkTestErrorObserver.h"

#include <vtksys/Directory.hxx>
#include <vtksys/SystemTools.hxx>

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <vector>

extern char** environ;

namespace
{
const std::vector<std::string> Files = { "refracta_atomics.cl", "selftest.cl" };

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

std::string FreshDirectory(const char* name)
{
  const char* base = std::getenv("REFRACTA_TEST_OUTPUT_DIR");
  std::string dir = std::string(base ? base : ".") + "/" + name;
  vtksys::SystemTools::RemoveADirectory(dir);
  return dir;
}

vtkSmartPointer<vtkOpenCLContext> ContextWithCache(const std::string& dir)
{
  auto context = vtkSmartPointer<vtkOpenCLContext>::New();
  context->SetBinaryCacheDirectory(dir.c_str());
  EXPECT_TRUE(context->Initialize());
  return context;
}

std::vector<char> ReadFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void WriteFile(const std::string& path, const std::vector<char>& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Starts `count` copies of this test program running the tests of `filter`, with `variables`
// ("NAME=value", replacing an inherited NAME) in their environment (the child tests skip
// themselves without theirs), and returns how many of them exited normally with status 0.
int RunChildren(int count, const std::string& filter, const std::vector<std::string>& variables)
{
  const std::string self = vtksys::SystemTools::GetRealPath("/proc/self/exe");
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
  {
    const std::string entry = *e;
    bool replaced = false;
    for (const std::string& v : variables)
    {
      replaced = replaced || entry.compare(0, v.find('=') + 1, v, 0, v.find('=') + 1) == 0;
    }
    if (!replaced)
    {
      env.push_back(entry);
    }
  }
  env.insert(env.end(), variables.begin(), variables.end());
  std::vector<char*> envp;
  for (auto& e : env)
  {
    envp.push_back(&e[0]);
  }
  envp.push_back(nullptr);
  std::string program = self, filterArgument = "--gtest_filter=" + filter;
  char* argv[] = { &program[0], &filterArgument[0], nullptr };
  std::vector<pid_t> children;
  for (int c = 0; c < count; ++c)
  {
    pid_t pid = 0;
    if (posix_spawn(&pid, self.c_str(), nullptr, nullptr, argv, envp.data()) == 0)
    {
      children.push_back(pid);
    }
  }
  int clean = 0;
  for (pid_t pid : children)
  {
    int status = 0;
    clean += waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  }
  return clean;
}

int CountTemporaryFiles(const std::string& dir)
{
  vtksys::Directory listing;
  listing.Load(dir);
  int count = 0;
  for (unsigned long i = 0; i < listing.GetNumberOfFiles(); ++i)
  {
    count += Contains(listing.GetFile(i), ".tmp.") ? 1 : 0;
  }
  return count;
}
}

// Each kind of damage: the next process rejects the entry (counted), compiles from source, and
// stores a good entry again, which the process after it loads.
TEST(OpenCLFaults, DamagedCacheEntriesAreRebuilt)
{
  const std::string dir = FreshDirectory("fault-cache-damage");
  std::string path, otherPath;
  {
    auto writer = ContextWithCache(dir);
    ASSERT_NE(writer->GetProgram(Files, ""), nullptr);
    ASSERT_NE(writer->GetProgram(Files, "-DOTHER=1"), nullptr);
    path = writer->GetBinaryCachePath(Files, "");
    otherPath = writer->GetBinaryCachePath(Files, "-DOTHER=1");
  }
  const std::vector<char> good = ReadFile(path);
  ASSERT_GT(good.size(), 64u);
  struct Damage
  {
    const char* Name;
    std::vector<char> Bytes;
  };
  std::vector<char> truncated(good.begin(), good.begin() + good.size() / 2);
  std::vector<char> corrupt = good;
  corrupt[good.size() - 7] ^= 0x5a;
  const std::vector<Damage> damages = { { "truncated", truncated }, { "corrupt", corrupt },
    { "foreign", ReadFile(otherPath) }, { "junk", { 'h', 'e', 'l', 'l', 'o' } }, { "empty", {} } };
  for (const Damage& d : damages)
  {
    WriteFile(path, d.Bytes);
    auto reader = ContextWithCache(dir);
    EXPECT_NE(reader->GetProgram(Files, ""), nullptr) << d.Name;
    EXPECT_EQ(reader->GetNumberOfRejectedBinaries(), 1) << d.Name;
    EXPECT_EQ(reader->GetNumberOfSourceBuilds(), 1) << d.Name;
    EXPECT_EQ(reader->GetNumberOfBinaryLoads(), 0) << d.Name;
    auto next = ContextWithCache(dir);
    EXPECT_NE(next->GetProgram(Files, ""), nullptr) << d.Name;
    EXPECT_EQ(next->GetNumberOfBinaryLoads(), 1) << d.Name << ": the rebuilt entry is good";
    EXPECT_EQ(next->GetNumberOfRejectedBinaries(), 0) << d.Name;
  }
}

// A cache folder that cannot be created (its parent is a regular file; this holds for root too):
// programs still build, and one warning says so for the whole life of the context.
TEST(OpenCLFaults, UnwritableCacheFolderWarnsOnce)
{
  const std::string base = FreshDirectory("fault-cache-unwritable");
  vtksys::SystemTools::MakeDirectory(base);
  WriteFile(base + "/a-file", { 'x' });
  auto context = ContextWithCache(base + "/a-file/kernels");
  vtkNew<vtkTest::ErrorObserver> observer;
  context->AddObserver(vtkCommand::WarningEvent, observer);
  context->AddObserver(vtkCommand::ErrorEvent, observer);
  EXPECT_NE(context->GetProgram(Files, ""), nullptr);
  EXPECT_NE(context->GetProgram(Files, "-DSECOND=1"), nullptr);
  EXPECT_NE(context->GetProgram(Files, "-DTHIRD=1"), nullptr);
  EXPECT_EQ(context->GetNumberOfSourceBuilds(), 3);
  const std::string warnings = observer->GetWarningMessage();
  size_t count = 0;
  for (size_t at = warnings.find("kernel cache off"); at != std::string::npos;
       at = warnings.find("kernel cache off", at + 1))
  {
    ++count;
  }
  EXPECT_EQ(count, 1u) << warnings;
  EXPECT_FALSE(observer->GetError()) << observer->GetErrorMessage();
  EXPECT_TRUE(Contains(observer->GetWarningMessage(), "a-file/kernels"))
    << observer->GetWarningMessage();
  EXPECT_TRUE(Contains(observer->GetWarningMessage(), "REFRACTA_KERNEL_CACHE_DIR"));
}

// Child of ConcurrentWritersLeaveOneValidEntry: builds the program into the shared folder.
TEST(OpenCLFaultsChild, BuildIntoSharedCache)
{
  const char* dir = std::getenv("REFRACTA_FAULT_CHILD_CACHE");
  if (!dir)
  {
    GTEST_SKIP() << "only run as a child process";
  }
  auto context = ContextWithCache(dir);
  ASSERT_NE(context->GetProgram(Files, "-DCONCURRENT=1"), nullptr);
}

// Four processes build the same program into an empty folder at the same time (each compiles and
// writes the same entry): afterwards a new process loads the entry without rejecting it, and no
// temporary file is left.
TEST(OpenCLFaults, ConcurrentWritersLeaveOneValidEntry)
{
  const std::string dir = FreshDirectory("fault-cache-concurrent");
  EXPECT_EQ(RunChildren(
              4, "OpenCLFaultsChild.BuildIntoSharedCache", { "REFRACTA_FAULT_CHILD_CACHE=" + dir }),
    4);
  auto reader = ContextWithCache(dir);
  EXPECT_NE(reader->GetProgram(Files, "-DCONCURRENT=1"), nullptr);
  EXPECT_EQ(reader->GetNumberOfBinaryLoads(), 1);
  EXPECT_EQ(reader->GetNumberOfRejectedBinaries(), 0);
  EXPECT_EQ(CountTemporaryFiles(dir), 0);
}

// Capabilities: a missing extension (64-bit atomics; double precision), too small work-groups and
// too little local memory are refused with messages naming the device and the limit.
TEST(OpenCLFaults, DeviceCapabilitiesAreCheckedWithClearMessages)
{
  vtkNew<vtkOpenCLContext> context;
  context->UseBinaryCacheOff();
  ASSERT_TRUE(context->Initialize());
  vtkNew<vtkTest::ErrorObserver> observer;
  context->AddObserver(vtkCommand::ErrorEvent, observer);

  context->SetSimulatedMissingExtensions("cl_khr_int64_base_atomics cl_khr_fp64");
  EXPECT_EQ(context->GetProgram(Files, "-DCAPS=1"), nullptr);
  std::string msg = observer->GetErrorMessage();
  EXPECT_TRUE(Contains(msg, "cl_khr_int64_base_atomics")) << msg;
  EXPECT_TRUE(Contains(msg, context->GetDeviceName())) << msg;
  EXPECT_TRUE(Contains(msg, "REFRACTA_OPENCL_DEVICE")) << msg;
  observer->Clear();
  const std::string fp64 = "#pragma OPENCL EXTENSION cl_khr_fp64 : enable\n"
                           "__kernel void twice(__global double* x) { x[0] *= 2.0; }\n";
  EXPECT_EQ(context->GetProgramFromSource(fp64, "", "fp64.cl"), nullptr);
  msg = observer->GetErrorMessage();
  EXPECT_TRUE(Contains(msg, "cl_khr_fp64") && Contains(msg, "double precision")) << msg;
  context->SetSimulatedMissingExtensions(nullptr);
  observer->Clear();

  cl_program program = context->GetProgram(Files, "");
  ASSERT_NE(program, nullptr);
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_saxpy");
  std::vector<float> y(256, 1.0f);
  vtkOpenCLBuffer yBuffer = context->CreateBuffer(CL_MEM_READ_WRITE, y.size() * 4, y.data(), "y");
  const float a = 2.0f;
  const cl_uint n = 256;
  ASSERT_EQ(vtkOpenCLSetKernelArgs(kernel.Get(), a, yBuffer.Get(), yBuffer.Get(), n), CL_SUCCESS);
  const size_t global = 256, local = 64;
  context->SetSimulatedMaximumWorkGroupSize(32);
  EXPECT_FALSE(context->RunKernel(kernel.Get(), 1, &global, &local, "refracta_saxpy"));
  msg = observer->GetErrorMessage();
  EXPECT_TRUE(Contains(msg, "work-groups of 64") && Contains(msg, "at most 32")) << msg;
  context->SetSimulatedMaximumWorkGroupSize(0);
  observer->Clear();
  EXPECT_TRUE(context->RunKernel(kernel.Get(), 1, &global, &local, "refracta_saxpy"));

  const std::string tiled = "__kernel void tiled(__global float* x)\n"
                            "{\n"
                            "  __local float tile[1024];\n"
                            "  tile[get_local_id(0)] = x[get_global_id(0)];\n"
                            "  barrier(CLK_LOCAL_MEM_FENCE);\n"
                            "  x[get_global_id(0)] = tile[0];\n"
                            "}\n";
  cl_program localProgram = context->GetProgramFromSource(tiled, "", "tiled.cl");
  ASSERT_NE(localProgram, nullptr);
  vtkOpenCLKernel localKernel = context->CreateKernel(localProgram, "tiled");
  ASSERT_EQ(vtkOpenCLSetKernelArgs(localKernel.Get(), yBuffer.Get()), CL_SUCCESS);
  context->SetSimulatedLocalMemoryBytes(1024);
  EXPECT_FALSE(context->RunKernel(localKernel.Get(), 1, &global, &local, "tiled"));
  msg = observer->GetErrorMessage();
  EXPECT_TRUE(Contains(msg, "local memory") && Contains(msg, "CL_DEVICE_LOCAL_MEM_SIZE")) << msg;
  context->SetSimulatedLocalMemoryBytes(0);
  observer->Clear();
  EXPECT_TRUE(context->RunKernel(localKernel.Get(), 1, &global, &local, "tiled"));
}

// An injected enqueue failure is an ordinary reported OpenCL error; the next enqueue works.
// Buffers are counted while alive.
TEST(OpenCLFaults, InjectedEnqueueFailureIsReportedOnce)
{
  vtkNew<vtkOpenCLContext> context;
  context->UseBinaryCacheOff();
  ASSERT_TRUE(context->Initialize());
  vtkNew<vtkTest::ErrorObserver> observer;
  context->AddObserver(vtkCommand::ErrorEvent, observer);
  const long long before = vtkOpenCLLiveHandles(0);
  {
    std::vector<float> data(64, 3.0f), back(64, 0.0f);
    vtkOpenCLBuffer buffer = context->CreateBuffer(CL_MEM_READ_WRITE, 256, data.data(), "data");
    EXPECT_EQ(vtkOpenCLLiveHandles(0), before + 1);
    context->SetFailingEnqueue(2);
    EXPECT_TRUE(context->ZeroBuffer(buffer.Get(), 256));
    EXPECT_FALSE(context->ReadBuffer(buffer.Get(), 256, back.data()));
    const std::string msg = observer->GetErrorMessage();
    EXPECT_TRUE(Contains(msg, "clEnqueueReadBuffer") && Contains(msg, "CL_OUT_OF_RESOURCES") &&
      Contains(msg, "injected"))
      << msg;
    EXPECT_TRUE(context->ReadBuffer(buffer.Get(), 256, back.data()));
    EXPECT_EQ(back[10], 0.0f);
  }
  EXPECT_EQ(vtkOpenCLLiveHandles(0), before);
}

// The memory plan's message names what needs how much, the limit and the setting to lower.
TEST(OpenCLFaults, MemoryPlanNamesTheLimitAndTheSetting)
{
  vtkNew<vtkOpenCLContext> context;
  ASSERT_TRUE(context->Initialize());
  context->SetSimulatedMaximumAllocationBytes(1024.0 * 1024 * 1024);
  context->SetSimulatedGlobalMemoryBytes(8.0 * 1024 * 1024 * 1024);
  vtkNew<vtkOpenCLMemoryPlan> plan;
  plan->Reset("view pass");
  plan->AddDeviceBuffer(
    "image 16384 x 16384", "HDR buffer", 16384.0 * 16384 * 16, "the image size");
  EXPECT_FALSE(plan->Fits(context));
  EXPECT_EQ(plan->GetMessage(),
    std::string("view pass: image 16384 x 16384 needs 4.0 GiB for the HDR buffer; device '") +
      context->GetDeviceName() +
      "' allows 1.0 GiB per allocation (CL_DEVICE_MAX_MEM_ALLOC_SIZE): lower the image size.");
  plan->Reset("photon pass");
  plan->AddDeviceBuffer("2^26 photons", "photon positions", 1.0e9, "NumberOfPhotons");
  plan->AddDeviceBuffer("2^26 photons", "photon directions", 1.0e9, "NumberOfPhotons");
  plan->AddDeviceBuffer("grid 512 x 512 x 512", "radiance accumulator", 0.9e9, "the grid size");
  context->SetSimulatedGlobalMemoryBytes(2.0e9);
  EXPECT_FALSE(plan->Fits(context));
  EXPECT_TRUE(Contains(plan->GetMessage(), "2.7 GiB of device memory in all"))
    << plan->GetMessage();
  EXPECT_TRUE(Contains(plan->GetMessage(), "lower NumberOfPhotons or the grid size"))
    << plan->GetMessage();
  context->SetSimulatedGlobalMemoryBytes(0);
  context->SetSimulatedMaximumAllocationBytes(0);
  EXPECT_TRUE(plan->Fits(context)) << plan->GetMessage();
}

// Child of ProcessesExitCleanlyAfterALaunch: launches a kernel and returns at once (the context
// is destroyed while the launch may still be running in the driver's threads).
TEST(OpenCLFaultsChild, LaunchThenExit)
{
  if (!std::getenv("REFRACTA_FAULT_CHILD_LAUNCH"))
  {
    GTEST_SKIP() << "only run as a child process";
  }
  vtkNew<vtkOpenCLContext> context;
  context->UseBinaryCacheOff();
  ASSERT_TRUE(context->Initialize());
  cl_program program = context->GetProgram(Files, "");
  ASSERT_NE(program, nullptr);
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_saxpy");
  std::vector<float> y(1 << 16, 1.0f);
  vtkOpenCLBuffer buffer = context->CreateBuffer(CL_MEM_READ_WRITE, y.size() * 4, y.data(), "y");
  const float a = 2.0f;
  const cl_uint n = static_cast<cl_uint>(y.size());
  ASSERT_EQ(vtkOpenCLSetKernelArgs(kernel.Get(), a, buffer.Get(), buffer.Get(), n), CL_SUCCESS);
  const size_t global = y.size(), local = 64;
  ASSERT_TRUE(context->RunKernel(kernel.Get(), 1, &global, &local, "refracta_saxpy"));
}

// A process that ends right after a launch exits cleanly: the context waits for its queue before
// releasing it. Without that wait, PoCL's worker thread was still compiling the launched kernel
// while the exit handlers ran, and most children (with a cold PoCL kernel cache) aborted with
// "Failed to create kernel compiler pass" or crashed, after their test had passed. With a warm
// cache the compile is skipped and the race is rare, so the children use their own empty cache
// (3 children: without the wait, all 3 survived in about 1 run of 60).
TEST(OpenCLFaults, ProcessesExitCleanlyAfterALaunch)
{
  const std::string pocl = FreshDirectory("fault-exit-pocl-cache");
  EXPECT_EQ(RunChildren(3, "OpenCLFaultsChild.LaunchThenExit",
              { "REFRACTA_FAULT_CHILD_LAUNCH=1", "POCL_CACHE_DIR=" + pocl }),
    3);
}
