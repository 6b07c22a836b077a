#include "vtkOpenCLKernelProfile.h"

#include "vtkObjectFactory.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

vtkStandardNewMacro(vtkOpenCLKernelProfile);

namespace
{
// Fold finished events in once this many are pending: bounds the memory of a long run (the
// lattice launches thousands of iterations) without a status query per launch.
constexpr size_t FoldThreshold = 256;
constexpr double MiB = 1048576.0;
}

struct vtkOpenCLKernelProfile::Pending
{
  std::string Label;
  vtkOpenCLEvent Event;
};

vtkOpenCLKernelProfile::vtkOpenCLKernelProfile()
  : PendingLaunches(new std::vector<Pending>)
{
}

vtkOpenCLKernelProfile::~vtkOpenCLKernelProfile() = default;

void vtkOpenCLKernelProfile::Record(
  const char* label, vtkOpenCLEvent event, double hostSeconds, double bytes)
{
  const std::string name = label ? label : "(unnamed)";
  this->TotalOf(name).HostSeconds += hostSeconds;
  this->TotalOf(name).Bytes += bytes;
  if (!event)
  {
    ++this->TotalOf(name).Launches;
    this->Modified();
    return;
  }
  this->PendingLaunches->push_back({ name, std::move(event) });
  if (this->PendingLaunches->size() >= FoldThreshold)
  {
    this->Fold(false);
  }
  this->Modified();
}

vtkOpenCLKernelProfile::Total& vtkOpenCLKernelProfile::TotalOf(const std::string& label)
{
  for (Total& t : this->Totals)
  {
    if (t.Label == label)
    {
      return t;
    }
  }
  this->Totals.push_back({ label, 0, 0.0, 0.0, 0.0 });
  return this->Totals.back();
}

void vtkOpenCLKernelProfile::Fold(bool wait)
{
  std::vector<Pending> stillRunning;
  for (Pending& p : *this->PendingLaunches)
  {
    cl_event e = p.Event.Get();
    cl_int status = CL_COMPLETE;
    if (wait)
    {
      clWaitForEvents(1, &e);
    }
    clGetEventInfo(e, CL_EVENT_COMMAND_EXECUTION_STATUS, sizeof(status), &status, nullptr);
    if (status > CL_COMPLETE) // queued, submitted or running
    {
      stillRunning.push_back(std::move(p));
      continue;
    }
    Total& total = this->TotalOf(p.Label);
    ++total.Launches;
    cl_ulong start = 0, end = 0;
    // A failed launch (status < 0) or a device without profiling counts the launch, not time.
    if (status == CL_COMPLETE &&
      clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_START, sizeof(start), &start, nullptr) ==
        CL_SUCCESS &&
      clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_END, sizeof(end), &end, nullptr) ==
        CL_SUCCESS &&
      end > start)
    {
      total.Seconds += static_cast<double>(end - start) * 1e-9;
    }
  }
  this->PendingLaunches->swap(stillRunning);
}

void vtkOpenCLKernelProfile::Collect()
{
  this->Fold(true);
}

void vtkOpenCLKernelProfile::Reset()
{
  this->PendingLaunches->clear();
  this->Totals.clear();
  this->Modified();
}

int vtkOpenCLKernelProfile::GetNumberOfKernels() const
{
  return static_cast<int>(this->Totals.size());
}

const char* vtkOpenCLKernelProfile::GetKernelLabel(int i) const
{
  return i >= 0 && i < this->GetNumberOfKernels() ? this->Totals[i].Label.c_str() : nullptr;
}

int vtkOpenCLKernelProfile::GetNumberOfLaunches(int i) const
{
  return i >= 0 && i < this->GetNumberOfKernels() ? this->Totals[i].Launches : 0;
}

double vtkOpenCLKernelProfile::EntryValue(int i, double Total::*field) const
{
  return i >= 0 && i < this->GetNumberOfKernels() ? this->Totals[i].*field : 0.0;
}

double vtkOpenCLKernelProfile::SumOf(double Total::*field) const
{
  double sum = 0.0;
  for (const Total& t : this->Totals)
  {
    sum += t.*field;
  }
  return sum;
}

double vtkOpenCLKernelProfile::GetDeviceSeconds(int i) const
{
  return this->EntryValue(i, &Total::Seconds);
}

double vtkOpenCLKernelProfile::GetTotalDeviceSeconds() const
{
  return this->SumOf(&Total::Seconds);
}

double vtkOpenCLKernelProfile::GetHostSeconds(int i) const
{
  return this->EntryValue(i, &Total::HostSeconds);
}

double vtkOpenCLKernelProfile::GetTotalHostSeconds() const
{
  return this->SumOf(&Total::HostSeconds);
}

double vtkOpenCLKernelProfile::GetBytes(int i) const
{
  return this->EntryValue(i, &Total::Bytes);
}

double vtkOpenCLKernelProfile::GetTotalBytes() const
{
  return this->SumOf(&Total::Bytes);
}

std::string vtkOpenCLKernelProfile::GetTable() const
{
  std::vector<Total> sorted = this->Totals;
  std::stable_sort(sorted.begin(), sorted.end(),
    [](const Total& a, const Total& b) { return a.Seconds > b.Seconds; });
  const double all = this->GetTotalDeviceSeconds();
  std::ostringstream os;
  os << "| kernel | launches | device s | share | host s in call | MiB moved |\n"
        "|---|---|---|---|---|---|\n";
  for (const Total& t : sorted)
  {
    os << "| " << t.Label << " | " << t.Launches << " | " << std::setprecision(4) << t.Seconds
       << " | " << std::setprecision(3) << (all > 0 ? 100.0 * t.Seconds / all : 0.0) << "% | "
       << std::setprecision(4) << t.HostSeconds << " | " << t.Bytes / MiB << " |\n";
  }
  os << "| total | | " << std::setprecision(4) << all << " | | " << this->GetTotalHostSeconds()
     << " | " << this->GetTotalBytes() / MiB << " |\n";
  return os.str();
}

void vtkOpenCLKernelProfile::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfKernels: " << this->GetNumberOfKernels() << "\n";
  os << indent << "PendingLaunches: " << this->PendingLaunches->size() << "\n";
  os << indent << "TotalDeviceSeconds: " << this->GetTotalDeviceSeconds() << "\n";
  os << indent << "TotalHostSeconds: " << this->GetTotalHostSeconds() << "\n";
  os << indent << "TotalBytes: " << this->GetTotalBytes() << "\n";
}
