#include "vtkOpenCLMemoryPlan.h"

#include "vtkObjectFactory.h"
#include "vtkOpenCLContext.h"

#include <algorithm>
#include <cstdio>
#include <set>
#include <sstream>

vtkStandardNewMacro(vtkOpenCLMemoryPlan);

namespace
{
// The settings of the largest entries, most bytes first, without repeats: "lower A or B".
template <typename Entries>
std::string SettingsToLower(const Entries& entries)
{
  std::vector<const typename Entries::value_type*> sorted;
  for (const auto& e : entries)
  {
    sorted.push_back(&e);
  }
  std::sort(sorted.begin(), sorted.end(), [](auto* a, auto* b) { return a->Bytes > b->Bytes; });
  std::set<std::string> seen;
  std::string text;
  for (const auto* e : sorted)
  {
    if (seen.insert(e->Setting).second && seen.size() <= 2)
    {
      text += (text.empty() ? "" : " or ") + e->Setting;
    }
  }
  return text;
}

template <typename Entries>
double Sum(const Entries& entries)
{
  double total = 0;
  for (const auto& e : entries)
  {
    total += e.Bytes;
  }
  return total;
}

template <typename Entries>
const typename Entries::value_type* Largest(const Entries& entries, bool newOnly = false)
{
  const typename Entries::value_type* best = nullptr;
  for (const auto& e : entries)
  {
    if (newOnly && e.Resident)
    {
      continue;
    }
    if (!best || e.Bytes > best->Bytes)
    {
      best = &e;
    }
  }
  return best;
}
}

//------------------------------------------------------------------------------
void vtkOpenCLMemoryPlan::Reset(const std::string& pass)
{
  this->Pass = pass;
  this->Device.clear();
  this->Host.clear();
  this->Message.clear();
}

void vtkOpenCLMemoryPlan::AddDeviceBuffer(
  const std::string& subject, const std::string& what, double bytes, const std::string& setting)
{
  this->Device.push_back({ subject, what, bytes, setting, false });
}

void vtkOpenCLMemoryPlan::AddResidentDeviceBuffer(
  const std::string& subject, const std::string& what, double bytes, const std::string& setting)
{
  this->Device.push_back({ subject, what, bytes, setting, true });
}

void vtkOpenCLMemoryPlan::AddHostMemory(
  const std::string& subject, const std::string& what, double bytes, const std::string& setting)
{
  this->Host.push_back({ subject, what, bytes, setting, false });
}

double vtkOpenCLMemoryPlan::GetDeviceBytes() const
{
  return Sum(this->Device);
}

double vtkOpenCLMemoryPlan::GetHostBytes() const
{
  return Sum(this->Host);
}

double vtkOpenCLMemoryPlan::GetLargestDeviceBufferBytes() const
{
  const Entry* e = Largest(this->Device);
  return e ? e->Bytes : 0.0;
}

//------------------------------------------------------------------------------
std::string vtkOpenCLMemoryPlan::FormatBytes(double bytes)
{
  const char* units[] = { "bytes", "KiB", "MiB", "GiB", "TiB" };
  int u = 0;
  while (bytes >= 1024.0 && u < 4)
  {
    bytes /= 1024.0;
    ++u;
  }
  char text[64];
  std::snprintf(text, sizeof(text), u == 0 ? "%.0f %s" : "%.1f %s", bytes, units[u]);
  return text;
}

//------------------------------------------------------------------------------
bool vtkOpenCLMemoryPlan::Fits(vtkOpenCLContext* context)
{
  this->Message.clear();
  std::ostringstream msg;
  const double perAllocation = context->GetMaximumAllocationBytes();
  const Entry* largestNew = Largest(this->Device, true);
  const Entry* largest = Largest(this->Device);
  const std::string device = std::string("device '") + context->GetDeviceName() + "'";
  if (largestNew && perAllocation > 0 && largestNew->Bytes > perAllocation)
  {
    msg << this->Pass << ": " << largestNew->Subject << " needs " << FormatBytes(largestNew->Bytes)
        << " for the " << largestNew->What << "; " << device << " allows "
        << FormatBytes(perAllocation) << " per allocation (CL_DEVICE_MAX_MEM_ALLOC_SIZE): lower "
        << largestNew->Setting << ".";
  }
  const double global = context->GetGlobalMemoryBytes();
  const double deviceTotal = this->GetDeviceBytes();
  if (msg.str().empty() && global > 0 && deviceTotal > global)
  {
    msg << this->Pass << " needs " << FormatBytes(deviceTotal)
        << " of device memory in all (the largest buffer: " << largest->What << " for "
        << largest->Subject << ", " << FormatBytes(largest->Bytes) << "); " << device << " has "
        << FormatBytes(global) << " (CL_DEVICE_GLOBAL_MEM_SIZE): lower "
        << SettingsToLower(this->Device) << ".";
  }
  const double host = context->GetHostMemoryBytes();
  const double hostTotal = this->GetHostBytes();
  const Entry* largestHost = Largest(this->Host);
  if (msg.str().empty() && host > 0 && hostTotal > host)
  {
    msg << this->Pass << " needs " << FormatBytes(hostTotal)
        << " of host memory (the largest part: " << largestHost->What << " for "
        << largestHost->Subject << ", " << FormatBytes(largestHost->Bytes) << "); this machine has "
        << FormatBytes(host) << ": lower " << SettingsToLower(this->Host) << ".";
  }
  this->Message = msg.str();
  return this->Message.empty();
}

//------------------------------------------------------------------------------
std::string vtkOpenCLMemoryPlan::GetSummary() const
{
  std::ostringstream out;
  out << "device " << FormatBytes(this->GetDeviceBytes());
  if (const Entry* e = Largest(this->Device))
  {
    out << " (largest: " << e->What << " " << FormatBytes(e->Bytes) << ")";
  }
  out << ", host " << FormatBytes(this->GetHostBytes());
  return out.str();
}

//------------------------------------------------------------------------------
void vtkOpenCLMemoryPlan::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Pass: " << this->Pass << "\n";
  for (const auto& e : this->Device)
  {
    os << indent << "device: " << e.What << " (" << e.Subject << ") " << FormatBytes(e.Bytes)
       << ", set by " << e.Setting << "\n";
  }
  for (const auto& e : this->Host)
  {
    os << indent << "host: " << e.What << " (" << e.Subject << ") " << FormatBytes(e.Bytes)
       << ", set by " << e.Setting << "\n";
  }
  os << indent << "Summary: " << this->GetSummary() << "\n";
  os << indent << "Message: " << (this->Message.empty() ? "(fits)" : this->Message) << "\n";
}
