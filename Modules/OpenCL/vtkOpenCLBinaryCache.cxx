#include "vtkOpenCLBinaryCache.h"

#include "vtkObjectFactory.h"

#include <vtksys/SystemTools.hxx>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <unistd.h>

vtkStandardNewMacro(vtkOpenCLBinaryCache);

namespace
{
constexpr char Magic[8] = { 'R', 'F', 'C', 'L', 'B', 'I', 'N', '1' };

// The fixed-size header in front of every payload.
struct EntryHeader
{
  char Magic[8];
  std::uint64_t KeyHash;
  std::uint64_t KeyLength;
  std::uint64_t PayloadSize;
  std::uint64_t PayloadChecksum;
};

EntryHeader MakeHeader(const std::string& key, const std::vector<unsigned char>& payload)
{
  EntryHeader header{};
  std::memcpy(header.Magic, Magic, sizeof(Magic));
  header.KeyHash = vtkOpenCLBinaryCache::Checksum(key.data(), key.size());
  header.KeyLength = key.size();
  header.PayloadSize = payload.size();
  header.PayloadChecksum = vtkOpenCLBinaryCache::Checksum(payload.data(), payload.size());
  return header;
}

// Distinct temporary names for every writer: the process id and a process-wide counter.
std::string TemporaryName(const std::string& path)
{
  static std::atomic<unsigned long> counter{ 0 };
  return path + ".tmp." + std::to_string(static_cast<long>(getpid())) + "." +
    std::to_string(counter++);
}
}

//------------------------------------------------------------------------------
std::uint64_t vtkOpenCLBinaryCache::Checksum(const void* data, size_t size)
{
  std::uint64_t hash = 1469598103934665603ull;
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i)
  {
    hash ^= bytes[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

//------------------------------------------------------------------------------
std::string vtkOpenCLBinaryCache::GetEntryPath(const std::string& key) const
{
  if (this->Directory.empty())
  {
    return std::string();
  }
  char name[32];
  std::snprintf(name, sizeof(name), "%016llx.clbin",
    static_cast<unsigned long long>(Checksum(key.data(), key.size())));
  return this->Directory + "/" + name;
}

//------------------------------------------------------------------------------
int vtkOpenCLBinaryCache::Load(
  const std::string& key, std::vector<unsigned char>& payload, std::string* why)
{
  payload.clear();
  if (!this->IsEnabled())
  {
    return MISSING;
  }
  const std::string path = this->GetEntryPath(key);
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    return MISSING;
  }
  const std::vector<unsigned char> file(
    (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const EntryHeader expected = MakeHeader(key, {});
  EntryHeader found{};
  std::string problem;
  if (file.size() < sizeof(EntryHeader))
  {
    problem = "truncated (" + std::to_string(file.size()) + " bytes, shorter than its header)";
  }
  else
  {
    std::memcpy(&found, file.data(), sizeof(EntryHeader));
    const size_t stored = file.size() - sizeof(EntryHeader);
    if (std::memcmp(found.Magic, Magic, sizeof(Magic)) != 0)
    {
      problem = "foreign (not a Refracta kernel-cache entry of this format)";
    }
    else if (found.KeyHash != expected.KeyHash || found.KeyLength != expected.KeyLength)
    {
      problem = "foreign (written for another program, version or device)";
    }
    else if (found.PayloadSize != stored)
    {
      problem = "truncated (" + std::to_string(stored) + " of " +
        std::to_string(found.PayloadSize) + " payload bytes)";
    }
    else if (Checksum(file.data() + sizeof(EntryHeader), stored) != found.PayloadChecksum)
    {
      problem = "corrupt (checksum mismatch)";
    }
  }
  if (!problem.empty())
  {
    ++this->NumberOfRejectedEntries;
    vtksys::SystemTools::RemoveFile(path);
    vtkDebugMacro("Rejected kernel-cache entry " << path << ": " << problem);
    if (why)
    {
      *why = problem;
    }
    return REJECTED;
  }
  payload.assign(file.begin() + sizeof(EntryHeader), file.end());
  ++this->NumberOfLoadedEntries;
  return LOADED;
}

//------------------------------------------------------------------------------
bool vtkOpenCLBinaryCache::Store(const std::string& key, const std::vector<unsigned char>& payload)
{
  if (!this->IsEnabled() || payload.empty())
  {
    return false;
  }
  if (!vtksys::SystemTools::MakeDirectory(this->Directory))
  {
    this->Disable("the folder cannot be created");
    return false;
  }
  const std::string path = this->GetEntryPath(key);
  const std::string temporary = TemporaryName(path);
  const EntryHeader header = MakeHeader(key, payload);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out)
    {
      this->Disable(std::string("a file cannot be created in it (") + std::strerror(errno) + ")");
      return false;
    }
    out.write(reinterpret_cast<const char*>(&header), sizeof(header));
    out.write(
      reinterpret_cast<const char*>(payload.data()), static_cast<std::streamsize>(payload.size()));
    out.close();
    if (!out)
    {
      vtksys::SystemTools::RemoveFile(temporary);
      this->Disable("writing an entry failed (disk full?)");
      return false;
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    const std::string reason = std::strerror(errno);
    vtksys::SystemTools::RemoveFile(temporary);
    this->Disable("renaming an entry into place failed (" + reason + ")");
    return false;
  }
  ++this->NumberOfStoredEntries;
  return true;
}

//------------------------------------------------------------------------------
void vtkOpenCLBinaryCache::Remove(const std::string& key)
{
  const std::string path = this->GetEntryPath(key);
  if (!path.empty())
  {
    vtksys::SystemTools::RemoveFile(path);
  }
}

//------------------------------------------------------------------------------
void vtkOpenCLBinaryCache::Disable(const std::string& reason)
{
  if (this->DisabledReason.empty())
  {
    this->DisabledReason =
      "the kernel cache folder '" + this->Directory + "' is not usable: " + reason;
  }
}

//------------------------------------------------------------------------------
void vtkOpenCLBinaryCache::SetDirectory(const std::string& directory)
{
  if (directory != this->Directory)
  {
    this->Directory = directory;
    this->DisabledReason.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkOpenCLBinaryCache::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Directory: " << (this->Directory.empty() ? "(none)" : this->Directory) << "\n";
  os << indent
     << "DisabledReason: " << (this->DisabledReason.empty() ? "(none)" : this->DisabledReason)
     << "\n";
  os << indent << "NumberOfLoadedEntries: " << this->NumberOfLoadedEntries << "\n";
  os << indent << "NumberOfRejectedEntries: " << this->NumberOfRejectedEntries << "\n";
  os << indent << "NumberOfStoredEntries: " << this->NumberOfStoredEntries << "\n";
}
