// Fuzz target: the mesh path of vtkMeshVoxelizer (mesh validation and repair, the exact inside
// test, the materials) on hostile meshes decoded from the bytes, on a grid of at most 6^3 voxels.
//
// Layout of the bytes (FuzzBytes; reads past the end give zeros):
//   header: meshes (1-2), grid dimensions (3 x 1-6), supersampling (1-3), smoothing window
//           (1-5), self-intersection check (bit), explicit bounds (bit, then 6 doubles), padding
//   per mesh: points (0-40), then each point's x, y, z (FuzzBytes::Double: mostly a 1/16
//           lattice, so coincident, coplanar and collinear points are common; also NaN, Inf,
//           denormals, 1e300, DBL_MAX); cells (0-60), then per cell a kind (triangle, polygon of
//           1-6 vertices, strip, line, vertex) and its point ids (mostly in range, sometimes -1,
//           the point count, or a large id); a material (index, extinction, albedo, g)
//
// Contract checked: the voxelizer either produces a medium on the requested grid that passes
// vtkMediumValidator, or reports an error through VTK and produces an empty image. A crash, a
// hang, a sanitizer report, or a failure without a message is a bug.
#include "FuzzSupport.h"

#include "vtkCellArray.h"
#include "vtkImageData.h"
#include "vtkMediumMaterial.h"
#include "vtkMeshVoxelizer.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <vector>

namespace
{
using refracta_fuzz::FuzzBytes;

// A point id: mostly a valid one, sometimes just outside the range or far outside it.
vtkIdType PointId(FuzzBytes& in, vtkIdType numPoints)
{
  const uint8_t b = in.Byte();
  if (b < 240 || numPoints == 0)
  {
    return numPoints > 0 ? b % numPoints : b % 4;
  }
  switch (b % 4)
  {
    case 0:
      return -1;
    case 1:
      return numPoints;
    case 2:
      return numPoints + in.Byte();
    default:
      return -static_cast<vtkIdType>(in.Byte()) * 1000003;
  }
}

vtkSmartPointer<vtkPolyData> DecodeMesh(FuzzBytes& in)
{
  const int numPoints = in.Int(0, 40);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (int p = 0; p < numPoints; ++p)
  {
    const double x = in.Double(), y = in.Double(), z = in.Double();
    points->InsertNextPoint(x, y, z);
  }
  vtkNew<vtkCellArray> polys, strips, lines, verts;
  const int numCells = in.Int(0, 60);
  std::vector<vtkIdType> ids;
  for (int c = 0; c < numCells; ++c)
  {
    const uint8_t kind = in.Byte();
    int n = 3;
    vtkCellArray* target = polys;
    if (kind >= 200)
    {
      switch (kind % 4)
      {
        case 0:
          n = in.Int(1, 6); // polygon of any size, also 1 or 2 vertices
          break;
        case 1:
          n = in.Int(3, 6);
          target = strips;
          break;
        case 2:
          n = 2;
          target = lines;
          break;
        default:
          n = 1;
          target = verts;
      }
    }
    ids.resize(n);
    for (int v = 0; v < n; ++v)
    {
      ids[v] = PointId(in, numPoints);
    }
    target->InsertNextCell(n, ids.data());
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  if (strips->GetNumberOfCells())
  {
    mesh->SetStrips(strips);
  }
  if (lines->GetNumberOfCells())
  {
    mesh->SetLines(lines);
  }
  if (verts->GetNumberOfCells())
  {
    mesh->SetVerts(verts);
  }
  return mesh;
}

vtkSmartPointer<vtkMediumMaterial> DecodeMaterial(FuzzBytes& in)
{
  auto material = vtkSmartPointer<vtkMediumMaterial>::New();
  material->SetRefractiveIndex(1.0 + in.Int(0, 8) * 0.125);
  const double e = in.Int(0, 4) * 2.5, a = in.Int(0, 4) * 0.25;
  material->SetExtinction(e, e, e);
  material->SetAlbedo(a, a, a);
  material->SetAnisotropy(in.Int(-4, 4) * 0.2);
  return material;
}
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  refracta_fuzz::InstallQuietOutput();
  FuzzBytes in(data, size);
  vtkNew<vtkMeshVoxelizer> voxelizer;
  const int meshes = in.Int(1, 2);
  int dims[3];
  for (int& d : dims)
  {
    d = in.Int(1, 6);
  }
  voxelizer->SetDimensions(dims);
  voxelizer->SetSupersampling(in.Int(1, 3));
  voxelizer->SetSmoothingWindow(in.Int(1, 5));
  voxelizer->SetCheckSelfIntersections(in.Byte() < 224);
  if (in.Bool())
  {
    double bounds[6];
    for (double& b : bounds)
    {
      b = in.Double();
    }
    voxelizer->SetBounds(bounds);
  }
  voxelizer->SetPadding(in.Int(0, 3) * 0.25);
  for (int m = 0; m < meshes; ++m)
  {
    voxelizer->AddInputData(DecodeMesh(in));
    voxelizer->SetMaterial(m, DecodeMaterial(in));
  }

  refracta_fuzz::ResetErrorCount();
  voxelizer->Update();
  vtkImageData* out = voxelizer->GetOutput();
  if (out->GetNumberOfPoints() == 0)
  {
    refracta_fuzz::Require(
      refracta_fuzz::GetErrorCount() > 0, "a mesh the voxelizer rejects gets an error message");
    return 0;
  }
  int outDims[3];
  out->GetDimensions(outDims);
  refracta_fuzz::Require(outDims[0] == dims[0] && outDims[1] == dims[1] && outDims[2] == dims[2],
    "the voxelized grid has the requested dimensions");
  refracta_fuzz::Require(refracta_fuzz::IsValidMedium(out), "the voxelized medium is valid");
  return 0;
}
