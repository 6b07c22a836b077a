#include "vtkRefractaActorSurfaces.h"

#include "vtkAbstractMapper.h"
#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProp3D.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkSkybox.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"

#include <algorithm>
#include <cstdint>

vtkStandardNewMacro(vtkRefractaActorSurfaces);

namespace
{
// The colours VTK draws `mapper`'s input with, RGBA per point (cellFlag 0) or per cell (1), or
// nullptr where it shows no scalars.
vtkSmartPointer<vtkUnsignedCharArray> MappedColours(
  vtkPolyDataMapper* mapper, vtkPolyData* input, int& cellFlag)
{
  cellFlag = 0;
  if (!mapper->GetScalarVisibility())
  {
    return nullptr;
  }
  vtkSmartPointer<vtkUnsignedCharArray> colours = mapper->MapScalars(1.0, cellFlag);
  if (colours)
  {
    return colours;
  }
  // InterpolateScalarsBeforeMapping maps through a colour texture instead: apply the lookup
  // table to the scalars directly (per point or cell, as they are).
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(input, mapper->GetScalarMode(),
    mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), cellFlag);
  if (!scalars)
  {
    return nullptr;
  }
  vtkScalarsToColors* lut = mapper->GetLookupTable();
  if (mapper->GetUseLookupTableScalarRange() == 0)
  {
    lut->SetRange(mapper->GetScalarRange());
  }
  colours = vtk::TakeSmartPointer(
    lut->MapScalars(scalars, mapper->GetColorMode(), mapper->GetArrayComponent()));
  return colours;
}

// The image of `actor`'s texture where it has one and its input texture coordinates to map it
// with; nullptr otherwise.
vtkImageData* TextureImage(vtkActor* actor)
{
  vtkTexture* texture = actor->GetTexture();
  auto* mapper = vtkPolyDataMapper::SafeDownCast(actor->GetMapper());
  vtkPolyData* input = mapper ? mapper->GetInput() : nullptr;
  if (!texture || !input || !input->GetPointData()->GetTCoords())
  {
    return nullptr;
  }
  if (vtkAlgorithm* producer = texture->GetInputAlgorithm())
  {
    producer->Update();
  }
  return texture->GetInput();
}

// The surface of one taken actor: its mesh (structure, texture coordinates and, where it shows
// scalars, its colours as the only scalars) and its material.
void AddActor(vtkRefractaSurfaceSet* set, vtkActor* actor, vtkPolyData* input)
{
  auto* mapper = vtkPolyDataMapper::SafeDownCast(actor->GetMapper());
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->CopyStructure(input);
  mesh->GetPointData()->SetTCoords(input->GetPointData()->GetTCoords());
  auto material = vtkSmartPointer<vtkRefractaSurfaceMaterial>::New();
  material->SetAlbedo(actor->GetProperty()->GetDiffuseColor());
  if (vtkImageData* image = TextureImage(actor))
  {
    // Sampled at the mesh's texture coordinates as vtkTexture maps them, times the colour.
    material->SetTexture(image);
    material->SetTextureRepeat(actor->GetTexture()->GetRepeat());
    material->SetTextureInterpolate(actor->GetTexture()->GetInterpolate());
  }
  int cellFlag = 0;
  if (vtkSmartPointer<vtkUnsignedCharArray> colours = MappedColours(mapper, input, cellFlag))
  {
    colours->SetName("Colors");
    if (cellFlag == 1)
    {
      mesh->GetCellData()->SetScalars(colours);
    }
    else if (cellFlag == 0)
    {
      mesh->GetPointData()->SetScalars(colours);
    }
    material->SetUseScalarColors(cellFlag == 0 || cellFlag == 1);
  }
  set->AddSurface(mesh, material, actor->GetMatrix());
}
}

//------------------------------------------------------------------------------
vtkRefractaActorSurfaces::vtkRefractaActorSurfaces()
  : Surfaces(vtkSmartPointer<vtkRefractaSurfaceSet>::New())
{
}

vtkRefractaActorSurfaces::~vtkRefractaActorSurfaces() = default;

vtkRefractaSurfaceSet* vtkRefractaActorSurfaces::GetSurfaces()
{
  return this->Surfaces;
}

vtkActor* vtkRefractaActorSurfaces::GetActor(int i) const
{
  return i >= 0 && i < this->GetNumberOfActors() ? this->Taken[i].Get() : nullptr;
}

//------------------------------------------------------------------------------
vtkPolyData* vtkRefractaActorSurfaces::ActorInput(vtkActor* actor)
{
  auto* mapper = vtkPolyDataMapper::SafeDownCast(actor->GetMapper());
  if (!mapper)
  {
    return nullptr;
  }
  if (vtkAlgorithm* producer = mapper->GetInputAlgorithm())
  {
    producer->Update();
  }
  vtkPolyData* input = mapper->GetInput();
  return input && input->GetNumberOfPolys() + input->GetNumberOfStrips() > 0 ? input : nullptr;
}

bool vtkRefractaActorSurfaces::IsTaken(vtkActor* actor)
{
  // A wireframe or point representation draws edges or vertices, not the polygons' area: it is
  // VTK's drawing (composited by depth), not a surface that hides and reflects.
  return actor && actor->GetVisibility() && actor->GetProperty()->GetOpacity() >= 1.0 &&
    actor->GetProperty()->GetRepresentation() == VTK_SURFACE && ActorInput(actor) &&
    !actor->HasTranslucentPolygonalGeometry();
}

bool vtkRefractaActorSurfaces::IsForeign(vtkProp* prop)
{
  return prop->GetVisibility() && vtkProp3D::SafeDownCast(prop) && prop->HasOpaqueGeometry();
}

//------------------------------------------------------------------------------
std::vector<double> vtkRefractaActorSurfaces::Signature() const
{
  std::vector<double> signature;
  for (const auto& actor : this->Taken)
  {
    auto* mapper = vtkPolyDataMapper::SafeDownCast(actor->GetMapper());
    signature.push_back(static_cast<double>(reinterpret_cast<std::uintptr_t>(actor.Get())));
    signature.push_back(static_cast<double>(mapper->GetMTime()));
    signature.push_back(static_cast<double>(mapper->GetInput()->GetMTime()));
    signature.push_back(static_cast<double>(actor->GetProperty()->GetMTime()));
    signature.push_back(
      static_cast<double>(mapper->GetLookupTable() ? mapper->GetLookupTable()->GetMTime() : 0));
    vtkTexture* texture = actor->GetTexture();
    signature.push_back(static_cast<double>(texture ? texture->GetMTime() : 0));
    signature.push_back(
      static_cast<double>(texture && texture->GetInput() ? texture->GetInput()->GetMTime() : 0));
  }
  return signature;
}

void vtkRefractaActorSurfaces::Rebuild()
{
  this->Surfaces->RemoveAllSurfaces();
  for (const auto& actor : this->Taken)
  {
    AddActor(this->Surfaces, actor, ActorInput(actor));
  }
  ++this->NumberOfRebuilds;
}

//------------------------------------------------------------------------------
void vtkRefractaActorSurfaces::Update(vtkRenderer* renderer, vtkProp* exclude)
{
  this->Taken.clear();
  this->NumberOfForeignProps = 0;
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (prop == exclude || vtkSkybox::SafeDownCast(prop))
    {
      continue; // a skybox is a vtkActor, but it is the background, not a surface
    }
    auto* actor = vtkActor::SafeDownCast(prop);
    if (actor && IsTaken(actor))
    {
      actor->GetMatrix(); // brings the matrix the set reads up to date with the actor
      this->Taken.emplace_back(actor);
    }
    else if (!vtkVolume::SafeDownCast(prop) && IsForeign(prop) &&
      !(actor && actor->HasTranslucentPolygonalGeometry()))
    {
      ++this->NumberOfForeignProps;
    }
  }
  if (this->Signature() != this->BuiltSignature)
  {
    this->Rebuild();
    // Taken after the rebuild: mapping an actor's scalars may touch its mapper or lookup table
    // (a default table created, its range set), which must not count as a change next time.
    this->BuiltSignature = this->Signature();
  }
}

//------------------------------------------------------------------------------
void vtkRefractaActorSurfaces::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Actors: " << this->Taken.size() << "\n";
  os << indent << "NumberOfForeignProps: " << this->NumberOfForeignProps << "\n";
  os << indent << "NumberOfRebuilds: " << this->NumberOfRebuilds << "\n";
}
