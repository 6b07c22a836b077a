#include "vtkOpenCLDeviceArrays.h"

#include "vtkFloatArray.h"
#include "vtkObjectFactory.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkOpenCLDeviceArrays);

struct vtkOpenCLDeviceArrays::Entries
{
  struct Entry
  {
    vtkWeakPointer<vtkDataArray> Array;
    vtkMTimeType Time = 0;
    vtkOpenCLBuffer Buffer;
    size_t Bytes = 0;
    const void* Owner = nullptr;
  };
  std::vector<Entry> List;

  // Drops the copies of deleted or modified arrays: what is left is valid.
  void Prune()
  {
    this->List.erase(std::remove_if(this->List.begin(), this->List.end(),
                       [](const Entry& e) { return !e.Array || e.Array->GetMTime() != e.Time; }),
      this->List.end());
  }

  Entry* Lookup(vtkDataArray* array)
  {
    this->Prune();
    for (Entry& e : this->List)
    {
      if (array && e.Array == array)
      {
        return &e;
      }
    }
    return nullptr;
  }
};

//------------------------------------------------------------------------------
vtkOpenCLDeviceArrays::vtkOpenCLDeviceArrays()
  : Held(new Entries)
{
}

vtkOpenCLDeviceArrays::~vtkOpenCLDeviceArrays() = default;

//------------------------------------------------------------------------------
void vtkOpenCLDeviceArrays::Remember(vtkFloatArray* array, cl_mem buffer, const void* owner)
{
  this->Forget(array);
  if (!array || !buffer)
  {
    return;
  }
  const size_t bytes = static_cast<size_t>(array->GetNumberOfValues()) * sizeof(float);
  const size_t size = vtkOpenCLBufferBytes(buffer);
  if (size < bytes)
  {
    return;
  }
  clRetainMemObject(buffer);
  Entries::Entry e;
  e.Array = array;
  e.Time = array->GetMTime();
  e.Buffer.Reset(buffer);
  e.Bytes = size;
  e.Owner = owner;
  this->Held->List.push_back(std::move(e));
}

//------------------------------------------------------------------------------
cl_mem vtkOpenCLDeviceArrays::Find(vtkDataArray* array)
{
  Entries::Entry* e = this->Held->Lookup(array);
  if (!e)
  {
    return nullptr;
  }
  ++this->NumberOfHits;
  return e->Buffer.Get();
}

//------------------------------------------------------------------------------
vtkOpenCLBuffer vtkOpenCLDeviceArrays::Share(vtkDataArray* array)
{
  cl_mem buffer = this->Find(array);
  if (buffer)
  {
    clRetainMemObject(buffer);
  }
  return vtkOpenCLBuffer(buffer);
}

//------------------------------------------------------------------------------
void vtkOpenCLDeviceArrays::Forget(vtkDataArray* array)
{
  this->Held->Prune();
  auto& list = this->Held->List;
  list.erase(std::remove_if(list.begin(), list.end(),
               [array](const Entries::Entry& e) { return e.Array == array; }),
    list.end());
}

//------------------------------------------------------------------------------
void vtkOpenCLDeviceArrays::ForgetOwner(const void* owner)
{
  auto& list = this->Held->List;
  list.erase(std::remove_if(list.begin(), list.end(),
               [owner](const Entries::Entry& e) { return owner && e.Owner == owner; }),
    list.end());
}

//------------------------------------------------------------------------------
void vtkOpenCLDeviceArrays::Clear()
{
  this->Held->List.clear();
}

//------------------------------------------------------------------------------
int vtkOpenCLDeviceArrays::GetNumberOfArrays()
{
  this->Held->Prune();
  return static_cast<int>(this->Held->List.size());
}

//------------------------------------------------------------------------------
double vtkOpenCLDeviceArrays::GetBytes()
{
  this->Held->Prune();
  double total = 0;
  for (const Entries::Entry& e : this->Held->List)
  {
    total += static_cast<double>(e.Bytes);
  }
  return total;
}

//------------------------------------------------------------------------------
void vtkOpenCLDeviceArrays::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfArrays: " << this->GetNumberOfArrays() << "\n";
  os << indent << "Bytes: " << this->GetBytes() << "\n";
  os << indent << "NumberOfHits: " << this->NumberOfHits << "\n";
}
