#include "vtkRefractaGridFrame.h"

#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkRefractaGridFrame);

//------------------------------------------------------------------------------
vtkRefractaGridFrame::vtkRefractaGridFrame()
{
  const double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  const double direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  const int extent[6] = { 0, 0, 0, 0, 0, 0 };
  this->SetGrid(origin, spacing, extent, direction);
}

//------------------------------------------------------------------------------
void vtkRefractaGridFrame::SetImage(vtkImageData* image)
{
  if (!image)
  {
    vtkRefractaGridFrame* blank = vtkRefractaGridFrame::New();
    this->SetGrid(blank->Origin, blank->Spacing, blank->Extent, blank->Direction);
    blank->Delete();
    return;
  }
  this->SetGrid(image->GetOrigin(), image->GetSpacing(), image->GetExtent(),
    image->GetDirectionMatrix()->GetData());
}

//------------------------------------------------------------------------------
void vtkRefractaGridFrame::SetGrid(
  const double origin[3], const double spacing[3], const int extent[6], const double direction[9])
{
  std::copy(origin, origin + 3, this->Origin);
  std::copy(spacing, spacing + 3, this->Spacing);
  std::copy(extent, extent + 6, this->Extent);
  std::copy(direction, direction + 9, this->Direction);

  // Local -> world: world = D local + first point, first point = Origin + D (Spacing * ext min).
  double first[3];
  this->GetFirstPoint(first);
  std::fill(this->LocalToWorld, this->LocalToWorld + 16, 0.0);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      this->LocalToWorld[4 * r + c] = direction[3 * r + c];
    }
    this->LocalToWorld[4 * r + 3] = first[r];
  }
  this->LocalToWorld[15] = 1.0;
  vtkMatrix4x4::Invert(this->LocalToWorld, this->WorldToLocal);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkRefractaGridFrame::GetFirstPoint(double world[3]) const
{
  const double* d = this->Direction;
  double s[3];
  for (int a = 0; a < 3; ++a)
  {
    s[a] = this->Spacing[a] * this->Extent[2 * a];
  }
  for (int r = 0; r < 3; ++r)
  {
    world[r] = this->Origin[r] + d[3 * r] * s[0] + d[3 * r + 1] * s[1] + d[3 * r + 2] * s[2];
  }
}

//------------------------------------------------------------------------------
void vtkRefractaGridFrame::GetWorldToLocalMatrix(vtkMatrix4x4* m) const
{
  m->DeepCopy(this->WorldToLocal);
}

//------------------------------------------------------------------------------
void vtkRefractaGridFrame::GetLocalToWorldMatrix(vtkMatrix4x4* m) const
{
  m->DeepCopy(this->LocalToWorld);
}

//------------------------------------------------------------------------------
void vtkRefractaGridFrame::GetWorldToIndexMatrix(vtkMatrix4x4* m) const
{
  m->DeepCopy(this->WorldToLocal);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      m->SetElement(r, c, m->GetElement(r, c) / this->Spacing[r]);
    }
  }
}

//------------------------------------------------------------------------------
void vtkRefractaGridFrame::GetIndexToWorldMatrix(vtkMatrix4x4* m) const
{
  m->DeepCopy(this->LocalToWorld);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m->SetElement(r, c, m->GetElement(r, c) * this->Spacing[c]);
    }
  }
}

//------------------------------------------------------------------------------
bool vtkRefractaGridFrame::SameGrid(vtkImageData* a, vtkImageData* b, double tolerance)
{
  if (!a || !b)
  {
    return false;
  }
  int da[3], db[3];
  a->GetDimensions(da);
  b->GetDimensions(db);
  const double* sa = a->GetSpacing();
  const double* sb = b->GetSpacing();
  for (int i = 0; i < 3; ++i)
  {
    if (da[i] != db[i] || std::abs(sa[i] - sb[i]) > tolerance * std::abs(sa[i]))
    {
      return false;
    }
  }
  const double* ma = a->GetDirectionMatrix()->GetData();
  const double* mb = b->GetDirectionMatrix()->GetData();
  for (int i = 0; i < 9; ++i)
  {
    if (std::abs(ma[i] - mb[i]) > tolerance)
    {
      return false;
    }
  }
  vtkRefractaGridFrame* fa = vtkRefractaGridFrame::New();
  vtkRefractaGridFrame* fb = vtkRefractaGridFrame::New();
  fa->SetImage(a);
  fb->SetImage(b);
  double pa[3], pb[3];
  fa->GetFirstPoint(pa);
  fb->GetFirstPoint(pb);
  fa->Delete();
  fb->Delete();
  const double minSpacing = std::min({ sa[0], sa[1], sa[2] });
  for (int i = 0; i < 3; ++i)
  {
    if (!(std::abs(pa[i] - pb[i]) <= tolerance * minSpacing))
    {
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
std::string vtkRefractaGridFrame::DescribeGrid(vtkImageData* image)
{
  if (!image)
  {
    return "no image";
  }
  int dims[3];
  image->GetDimensions(dims);
  const double* s = image->GetSpacing();
  const double* d = image->GetDirectionMatrix()->GetData();
  vtkRefractaGridFrame* frame = vtkRefractaGridFrame::New();
  frame->SetImage(image);
  double first[3];
  frame->GetFirstPoint(first);
  frame->Delete();
  std::ostringstream os;
  os << "dimensions " << dims[0] << "x" << dims[1] << "x" << dims[2] << ", spacing (" << s[0]
     << ", " << s[1] << ", " << s[2] << "), first point at (" << first[0] << ", " << first[1]
     << ", " << first[2] << "), direction (" << d[0];
  for (int i = 1; i < 9; ++i)
  {
    os << ", " << d[i];
  }
  os << ")";
  return os.str();
}

//------------------------------------------------------------------------------
void vtkRefractaGridFrame::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Origin: (" << this->Origin[0] << ", " << this->Origin[1] << ", "
     << this->Origin[2] << ")\n";
  os << indent << "Spacing: (" << this->Spacing[0] << ", " << this->Spacing[1] << ", "
     << this->Spacing[2] << ")\n";
  os << indent << "Extent: (" << this->Extent[0] << ", " << this->Extent[1] << ", "
     << this->Extent[2] << ", " << this->Extent[3] << ", " << this->Extent[4] << ", "
     << this->Extent[5] << ")\n";
  os << indent << "Direction: (";
  for (int i = 0; i < 9; ++i)
  {
    os << this->Direction[i] << (i < 8 ? ", " : ")\n");
  }
}
