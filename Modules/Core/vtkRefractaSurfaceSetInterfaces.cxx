// vtkRefractaSurfaceSet, part 2: the exact dielectric interfaces a voxelized medium carries in its
// field data (vtkMeshVoxelizer::EXACT_INTERFACES), as dielectric surfaces with their inside media
// (Documentation/Physics.md "From the voxelizer to the surface set", "Glass bodies"), and the
// flattened description of every dielectric surface the kernels read (DescribeInterfaces).
#include "vtkRefractaSurfaceSet.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSetInternals.h"
#include "vtkSmartPointer.h"

#include "refracta_surfaces.cl" // the flattened layout, shared with the kernels

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>
//------------------------------------------------------------------------------
int vtkRefractaSurfaceSet::AddMediumInterfaces(vtkDataObject* medium, vtkMatrix4x4* matrix)
{
  vtkFieldData* fd = medium ? medium->GetFieldData() : nullptr;
  vtkDataArray* points = fd ? fd->GetArray(vtkRefractaMedium::InterfacePointsName()) : nullptr;
  vtkDataArray* triangles =
    fd ? fd->GetArray(vtkRefractaMedium::InterfaceTrianglesName()) : nullptr;
  vtkDataArray* indices = fd ? fd->GetArray(vtkRefractaMedium::InterfaceIndicesName()) : nullptr;
  if (!points && !triangles && !indices)
  {
    return 0;
  }
  if (!points || !triangles || !indices || points->GetNumberOfComponents() != 3 ||
    triangles->GetNumberOfComponents() != 3 || indices->GetNumberOfComponents() != 2 ||
    indices->GetNumberOfTuples() != triangles->GetNumberOfTuples())
  {
    vtkErrorMacro("AddMediumInterfaces: the medium's interface arrays are inconsistent; valid are "
      << vtkRefractaMedium::InterfacePointsName() << " (3 components), "
      << vtkRefractaMedium::InterfaceTrianglesName() << " (3 point ids) and "
      << vtkRefractaMedium::InterfaceIndicesName()
      << " (2 components, one tuple per triangle), all three present. Nothing was added.");
    return -1;
  }
  vtkDataArray* bodies = fd->GetArray(vtkRefractaMedium::InterfaceMaterialsName());
  if (bodies && !this->CheckInterfaceMaterials(bodies, triangles->GetNumberOfTuples()))
  {
    return -1;
  }
  const vtkIdType numPoints = points->GetNumberOfTuples();
  vtkNew<vtkPoints> shared;
  shared->SetDataTypeToDouble();
  shared->SetNumberOfPoints(numPoints);
  for (vtkIdType p = 0; p < numPoints; ++p)
  {
    shared->SetPoint(p, points->GetTuple3(p));
  }
  // One surface per (inside, outside) pair and inside medium, sharing the points (unused ones
  // are harmless).
  using Key = std::vector<double>;
  std::map<Key, vtkSmartPointer<vtkCellArray>> groups;
  for (vtkIdType t = 0; t < triangles->GetNumberOfTuples(); ++t)
  {
    const double* ids = triangles->GetTuple3(t);
    vtkIdType cell[3];
    for (int c = 0; c < 3; ++c)
    {
      cell[c] = static_cast<vtkIdType>(ids[c]);
      if (!(ids[c] >= 0 && ids[c] < numPoints))
      {
        vtkErrorMacro("AddMediumInterfaces: interface triangle "
          << t << " refers to point " << ids[c] << "; valid ids are 0 to " << numPoints - 1
          << ". Nothing was added.");
        return -1;
      }
    }
    const double* pair = indices->GetTuple2(t);
    Key key{ pair[0], pair[1] };
    if (bodies)
    {
      const double* body = bodies->GetTuple(t);
      key.insert(key.end(), body, body + vtkRefractaMedium::InterfaceMaterialComponents);
    }
    auto& cells = groups[key];
    if (!cells)
    {
      cells = vtkSmartPointer<vtkCellArray>::New();
    }
    cells->InsertNextCell(3, cell);
  }
  for (const auto& group : groups)
  {
    vtkNew<vtkPolyData> mesh;
    mesh->SetPoints(shared);
    mesh->SetPolys(group.second);
    vtkNew<vtkRefractaSurfaceMaterial> glass;
    glass->SetKindToDielectric();
    const Key& key = group.first;
    glass->SetIndexInside(key[0]);
    glass->SetIndexOutside(key[1]);
    if (key.size() == 2 + vtkRefractaMedium::InterfaceMaterialComponents && key[12] > 0.5)
    {
      glass->SetUseInsideMedium(true);
      glass->SetInsideExtinction(&key[2]);
      glass->SetInsideAlbedo(&key[5]);
      glass->SetInsideAnisotropy(key[8]);
      glass->SetInsideEmission(&key[9]);
    }
    this->AddSurface(mesh, glass, matrix);
  }
  return static_cast<int>(groups.size());
}

//------------------------------------------------------------------------------
bool vtkRefractaSurfaceSet::CheckInterfaceMaterials(vtkDataArray* bodies, vtkIdType triangles)
{
  const int nc = vtkRefractaMedium::InterfaceMaterialComponents;
  if (bodies->GetNumberOfComponents() != nc || bodies->GetNumberOfTuples() != triangles)
  {
    vtkErrorMacro("AddMediumInterfaces: "
      << vtkRefractaMedium::InterfaceMaterialsName() << " has " << bodies->GetNumberOfTuples()
      << " tuples of " << bodies->GetNumberOfComponents()
      << " components; valid is one tuple per interface triangle (" << triangles << ") of " << nc
      << " components. Nothing was added.");
    return false;
  }
  for (vtkIdType t = 0; t < triangles; ++t)
  {
    const double* b = bodies->GetTuple(t);
    bool valid = true;
    for (int c = 0; c < nc; ++c)
    {
      valid = valid && std::isfinite(b[c]) && (c == 6 || b[c] >= 0.0);
    }
    valid = valid && b[3] <= 1.0 && b[4] <= 1.0 && b[5] <= 1.0 && std::fabs(b[6]) < 1.0 &&
      (b[10] == 0.0 || b[10] == 1.0);
    if (!valid)
    {
      vtkErrorMacro("AddMediumInterfaces: "
        << vtkRefractaMedium::InterfaceMaterialsName() << " tuple " << t
        << " is invalid; valid are finite values: extinction >= 0, albedo in "
           "[0, 1], anisotropy in (-1, 1), emission >= 0, and a last component of 0 or 1. "
           "Nothing was added.");
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaSurfaceSet::IsDielectric(int surface) const
{
  vtkRefractaSurfaceMaterial* m = this->GetMaterial(surface);
  return m && m->GetKind() == vtkRefractaSurfaceMaterial::DIELECTRIC;
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceSet::DescribeInterfaces()
{
  using namespace vtkRefractaSurfaceSetDetail;
  const int surfaces = this->GetNumberOfSurfaces();
  this->SurfaceInterfaces.assign(REFRACTA_SURFACE_INTERFACE_FLOATS * size_t(surfaces), 1.0f);
  this->SurfaceBodies.assign(REFRACTA_SURFACE_BODY_FLOATS * size_t(surfaces), 0.0f);
  std::vector<bool> smooth(surfaces, false);
  for (int s = 0; s < surfaces; ++s)
  {
    if (this->IsDielectric(s))
    {
      vtkRefractaSurfaceMaterial* m = this->GetMaterial(s);
      this->SurfaceInterfaces[REFRACTA_SURFACE_INTERFACE_FLOATS * s] =
        static_cast<float>(m->GetIndexInside());
      this->SurfaceInterfaces[REFRACTA_SURFACE_INTERFACE_FLOATS * s + 1] =
        static_cast<float>(m->GetIndexOutside());
      smooth[s] = m->GetSmoothNormals();
      if (m->GetUseInsideMedium())
      {
        float* body = &this->SurfaceBodies[REFRACTA_SURFACE_BODY_FLOATS * s];
        for (int c = 0; c < 3; ++c)
        {
          body[c] = static_cast<float>(m->GetInsideExtinction()[c]);
          body[4 + c] = static_cast<float>(m->GetInsideAlbedo()[c]);
          body[8 + c] = static_cast<float>(m->GetInsideEmission()[c]);
        }
        body[3] = 1.0f;
        body[7] = static_cast<float>(m->GetInsideAnisotropy());
      }
    }
  }
  const vtkRefractaBVH* bvh = this->Impl->BVH;
  const vtkIdType triangles = bvh->GetNumberOfTriangles();
  const std::vector<vtkIdType>& order = bvh->GetTriangleOrder();
  const SharedPoints& shared = this->Impl->Shared;
  this->DielectricTriangles = 0;
  this->TriangleNormals.assign(REFRACTA_TRIANGLE_NORMAL_FLOATS * size_t(triangles), 0.0f);
  for (vtkIdType k = 0; k < triangles; ++k)
  {
    const SourceTriangle& source = this->Impl->Sources[order[k]];
    const bool dielectric = this->IsDielectric(source.Surface);
    this->TriangleInfo[REFRACTA_TRIANGLE_INFO_INTS * k + REFRACTA_TRIANGLE_INFO_KIND] =
      dielectric ? REFRACTA_SURFACE_DIELECTRIC : REFRACTA_SURFACE_LAMBERTIAN;
    this->DielectricTriangles += dielectric ? 1 : 0;
    const double* face = &shared.Faces[3 * k];
    for (int corner = 0; corner < 3; ++corner)
    {
      double n[3] = { face[0], face[1], face[2] };
      if (smooth[source.Surface])
      {
        // The area-weighted mean over the point's faces within the feature angle of this face:
        // a 45-degree edge of a prism stays sharp on both sides.
        double mean[3] = { 0, 0, 0 };
        shared.ForSmoothNeighbours(source.Surface, source.Points[corner], k,
          [&](vtkIdType j)
          {
            for (int a = 0; a < 3; ++a)
            {
              mean[a] += shared.Areas[j] * shared.Faces[3 * j + a];
            }
          });
        Normalize(mean);
        std::copy(mean, mean + 3, n);
      }
      float* out = &this->TriangleNormals[REFRACTA_TRIANGLE_NORMAL_FLOATS * k + 4 * corner];
      for (int a = 0; a < 3; ++a)
      {
        out[a] = static_cast<float>(n[a]);
      }
    }
  }
}
