#include "vtkRefractaPluginMeshVoxelizer.h"

#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMediumMaterial.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>

vtkStandardNewMacro(vtkRefractaPluginMeshVoxelizer);

//------------------------------------------------------------------------------
vtkRefractaPluginMeshVoxelizer::vtkRefractaPluginMeshVoxelizer() = default;

//------------------------------------------------------------------------------
vtkRefractaPluginMeshVoxelizer::~vtkRefractaPluginMeshVoxelizer() = default;

namespace
{
// A homogeneous material from one row of numbers. vtkMediumMaterial clamps each value to its
// valid range (documented there).
vtkSmartPointer<vtkMediumMaterial> MakeMaterial(double n, double er, double eg, double eb,
  double ar, double ag, double ab, double g, double mr, double mg, double mb)
{
  auto material = vtkSmartPointer<vtkMediumMaterial>::New();
  material->SetRefractiveIndex(n);
  material->SetExtinction(er, eg, eb);
  material->SetAlbedo(ar, ag, ab);
  material->SetAnisotropy(g);
  material->SetEmission(mr, mg, mb);
  return material;
}
}

//------------------------------------------------------------------------------
void vtkRefractaPluginMeshVoxelizer::SetMaterialParameters(int connection, double n, double er,
  double eg, double eb, double ar, double ag, double ab, double g, double mr, double mg, double mb)
{
  this->SetMaterial(connection, MakeMaterial(n, er, eg, eb, ar, ag, ab, g, mr, mg, mb));
}

//------------------------------------------------------------------------------
void vtkRefractaPluginMeshVoxelizer::RemoveAllMaterials()
{
  if (!this->Materials.empty())
  {
    this->Materials.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkRefractaPluginMeshVoxelizer::SetSurroundingMaterialParameters(double n, double er,
  double eg, double eb, double ar, double ag, double ab, double g, double mr, double mg, double mb)
{
  this->SetSurroundingMaterial(MakeMaterial(n, er, eg, eb, ar, ag, ab, g, mr, mg, mb));
}

//------------------------------------------------------------------------------
void vtkRefractaPluginMeshVoxelizer::SetGridDimensions(int nx, int ny, int nz)
{
  const int n[3] = { std::max(1, nx), std::max(1, ny), std::max(1, nz) };
  if (!std::equal(n, n + 3, this->Dimensions))
  {
    std::copy(n, n + 3, this->Dimensions);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkRefractaPluginMeshVoxelizer::SetGridSpacing(double sx, double sy, double sz)
{
  const double s[3] = { sx, sy, sz };
  if (!std::equal(s, s + 3, this->Spacing))
  {
    std::copy(s, s + 3, this->Spacing);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkRefractaPluginMeshVoxelizer::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestData(request, inputVector, outputVector))
  {
    // Reported by vtkMeshVoxelizer. The output keeps no arrays but spans the requested extent
    // (the one-voxel grid RequestInformation advertised), so the pipeline sees the request
    // satisfied and does not run the filter (and repeat the message) again until something
    // changes; an image with no points would never satisfy it.
    vtkImageData* output = vtkImageData::GetData(outputVector, 0);
    output->Initialize();
    output->SetExtent(outputVector->GetInformationObject(0)->Get(
      vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()));
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkRefractaPluginMeshVoxelizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
