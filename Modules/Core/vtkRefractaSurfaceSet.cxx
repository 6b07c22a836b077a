#include "vtkRefractaSurfaceSet.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkIdList.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolygon.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaSettings.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSetInternals.h"
#include "vtkUnsignedCharArray.h"

#include "refracta_surfaces.cl" // the flattened layout, shared with the kernels

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

vtkStandardNewMacro(vtkRefractaSurfaceSet);
vtkRefractaCxxSetClampMacro(vtkRefractaSurfaceSet, TexelSize, 0.0, 1e300);

using namespace vtkRefractaSurfaceSetDetail;

namespace
{
// The automatic texel size is the diagonal of the surfaces' bounds over this.
constexpr double AutomaticTexelsPerDiagonal = 128.0;
// A triangle is degenerate when |e1 x e2| <= this x (longest edge)^2.
constexpr double DegenerateRatio = 1e-12;
// How one surface's texels get their colour.
struct ColorSource
{
  enum Kind
  {
    ALBEDO,
    CHECKER,
    TEXTURE,
    POINT_SCALARS,
    CELL_SCALARS
  };
  Kind Type = ALBEDO;
  vtkDataArray* Scalars = nullptr;
  double ScalarScale = 1.0;          // 1/255 for unsigned char colours
  std::vector<double> TextureCoords; // per point (u, v) for the texture or the checker
  vtkRefractaSurfaceMaterial* Material = nullptr;
};

bool IsColorArray(vtkDataArray* a)
{
  if (!a || (a->GetNumberOfComponents() != 3 && a->GetNumberOfComponents() != 4))
  {
    return false;
  }
  const int type = a->GetDataType();
  return type == VTK_UNSIGNED_CHAR || type == VTK_FLOAT || type == VTK_DOUBLE;
}

double Length(const double a[3], const double b[3])
{
  return std::sqrt(
    (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

double LongestEdge(const double* v)
{
  return std::max({ Length(v, v + 3), Length(v + 3, v + 6), Length(v + 6, v) });
}

}

//------------------------------------------------------------------------------
vtkRefractaSurfaceSet::vtkRefractaSurfaceSet()
  : Impl(new Internals)
{
}

//------------------------------------------------------------------------------
vtkRefractaSurfaceSet::~vtkRefractaSurfaceSet()
{
  delete this->Impl;
}

//------------------------------------------------------------------------------
int vtkRefractaSurfaceSet::AddSurface(
  vtkPolyData* mesh, vtkRefractaSurfaceMaterial* material, vtkMatrix4x4* matrix)
{
  if (!mesh)
  {
    vtkErrorMacro("AddSurface: the mesh is null; a surface needs a vtkPolyData with polygons or "
                  "triangle strips.");
    return -1;
  }
  Internals::Entry entry;
  entry.Mesh = mesh;
  entry.Material = material;
  if (!material)
  {
    entry.Material = vtkSmartPointer<vtkRefractaSurfaceMaterial>::New();
  }
  entry.Matrix = matrix;
  this->Impl->Surfaces.push_back(entry);
  this->Modified();
  return static_cast<int>(this->Impl->Surfaces.size()) - 1;
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceSet::RemoveAllSurfaces()
{
  if (!this->Impl->Surfaces.empty())
  {
    this->Impl->Surfaces.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkRefractaSurfaceSet::GetNumberOfSurfaces() const
{
  return static_cast<int>(this->Impl->Surfaces.size());
}

int vtkRefractaSurfaceSet::GetNumberOfNonEmptySurfaces() const
{
  int count = 0;
  for (const auto& s : this->Impl->Surfaces)
  {
    count += (s.Mesh->GetNumberOfPolys() + s.Mesh->GetNumberOfStrips() > 0) ? 1 : 0;
  }
  return count;
}

int vtkRefractaSurfaceSet::GetNumberOfNonEmptyDielectricSurfaces() const
{
  int count = 0;
  for (int s = 0; s < this->GetNumberOfSurfaces(); ++s)
  {
    vtkPolyData* mesh = this->Impl->Surfaces[s].Mesh;
    const bool empty = mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips() == 0;
    count += (this->IsDielectric(s) && !empty) ? 1 : 0;
  }
  return count;
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceSet::CopySurfaces(vtkRefractaSurfaceSet* source)
{
  this->RemoveAllSurfaces();
  vtkNew<vtkRefractaSurfaceSet> defaults;
  vtkRefractaSurfaceSet* settings = source ? source : defaults.GetPointer();
  this->SetTexelSize(settings->GetTexelSize());
  this->SetMaximumTexelSubdivision(settings->GetMaximumTexelSubdivision());
  this->SetMaximumNumberOfTexels(settings->GetMaximumNumberOfTexels());
  for (int s = 0; source && s < source->GetNumberOfSurfaces(); ++s)
  {
    this->AddSurface(source->GetSurface(s), source->GetMaterial(s), source->GetMatrix(s));
  }
}

vtkPolyData* vtkRefractaSurfaceSet::GetSurface(int index) const
{
  return index >= 0 && index < this->GetNumberOfSurfaces() ? this->Impl->Surfaces[index].Mesh
                                                           : nullptr;
}

vtkRefractaSurfaceMaterial* vtkRefractaSurfaceSet::GetMaterial(int index) const
{
  return index >= 0 && index < this->GetNumberOfSurfaces() ? this->Impl->Surfaces[index].Material
                                                           : nullptr;
}

vtkMatrix4x4* vtkRefractaSurfaceSet::GetMatrix(int index) const
{
  return index >= 0 && index < this->GetNumberOfSurfaces() ? this->Impl->Surfaces[index].Matrix
                                                           : nullptr;
}

vtkRefractaBVH* vtkRefractaSurfaceSet::GetBVH() const
{
  return this->Impl->BVH;
}

vtkIdType vtkRefractaSurfaceSet::GetNumberOfTriangles() const
{
  return this->Impl->BVH->GetNumberOfTriangles();
}

void vtkRefractaSurfaceSet::GetBounds(double bounds[6]) const
{
  this->Impl->BVH->GetBounds(bounds);
}

//------------------------------------------------------------------------------
vtkMTimeType vtkRefractaSurfaceSet::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  for (const auto& s : this->Impl->Surfaces)
  {
    t = std::max(t, s.Mesh->GetMTime());
    t = std::max(t, s.Material->GetMTime());
    if (s.Matrix)
    {
      t = std::max(t, s.Matrix->GetMTime());
    }
  }
  return t;
}

//------------------------------------------------------------------------------
int vtkRefractaSurfaceSet::TexelIndex(float u, float v, int n)
{
  // Step for step refracta_texel_index (Kernels/refracta_surfaces.cl); each product and sum is
  // its own statement so that no compiler fuses them differently from the device.
  const float fn = static_cast<float>(n);
  const float ua = u * fn;
  const float vb = v * fn;
  const float a = std::min(std::max(ua, 0.0f), fn);
  const float b = std::min(std::max(vb, 0.0f), fn);
  const int j = std::min(static_cast<int>(std::floor(b)), n - 1);
  int i = std::min(static_cast<int>(std::floor(a)), n - 1);
  if (i + j > n - 1)
  {
    i = n - 1 - j;
    return j * (2 * n - j) + 2 * i;
  }
  const float s = a + b;
  const int inverted = (i + j <= n - 2 && s > static_cast<float>(i + j + 1)) ? 1 : 0;
  return j * (2 * n - j) + 2 * i + inverted;
}

//------------------------------------------------------------------------------
bool vtkRefractaSurfaceSet::GetTexelCorners(int texel, int n, double corners[6])
{
  if (n < 1 || texel < 0 || texel >= n * n)
  {
    return false;
  }
  int j = 0;
  while ((j + 1) * (2 * n - j - 1) <= texel)
  {
    ++j;
  }
  const int r = texel - j * (2 * n - j);
  const int i = r / 2;
  const double h = 1.0 / n;
  if (r % 2 == 0)
  {
    const double c[6] = { i * h, j * h, (i + 1) * h, j * h, i * h, (j + 1) * h };
    std::copy(c, c + 6, corners);
  }
  else
  {
    const double c[6] = { (i + 1) * h, j * h, i * h, (j + 1) * h, (i + 1) * h, (j + 1) * h };
    std::copy(c, c + 6, corners);
  }
  return true;
}

bool vtkRefractaSurfaceSet::GetTexelSamplePoints(int texel, int n, double points[8])
{
  double c[6];
  if (!GetTexelCorners(texel, n, c))
  {
    return false;
  }
  // The centroid and the centroids of the three corner sub-triangles.
  const double weights[4][3] = { { 1 / 3., 1 / 3., 1 / 3. }, { 4 / 6., 1 / 6., 1 / 6. },
    { 1 / 6., 4 / 6., 1 / 6. }, { 1 / 6., 1 / 6., 4 / 6. } };
  for (int q = 0; q < 4; ++q)
  {
    const double* w = weights[q];
    points[2 * q] = w[0] * c[0] + w[1] * c[2] + w[2] * c[4];
    points[2 * q + 1] = w[0] * c[1] + w[1] * c[3] + w[2] * c[5];
  }
  return true;
}

namespace
{
// World points of a surface (model points through its matrix); false if any is not finite.
bool TransformPoints(vtkPolyData* mesh, vtkMatrix4x4* matrix, std::vector<double>& world)
{
  const vtkIdType n = mesh->GetNumberOfPoints();
  world.resize(3 * n);
  for (vtkIdType p = 0; p < n; ++p)
  {
    double x[4] = { 0, 0, 0, 1 };
    mesh->GetPoint(p, x);
    if (matrix)
    {
      double y[4];
      matrix->MultiplyPoint(x, y);
      for (int a = 0; a < 3; ++a)
      {
        x[a] = y[a] / y[3];
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      if (!std::isfinite(x[a]))
      {
        return false;
      }
      world[3 * p + a] = x[a];
    }
  }
  return true;
}

// Appends the triangle (a, b, c) of `cell` unless degenerate (then counts it).
void AddTriangle(const std::vector<double>& points, int surface, vtkIdType cell, vtkIdType a,
  vtkIdType b, vtkIdType c, std::vector<double>& world, std::vector<SourceTriangle>& sources,
  vtkIdType& dropped)
{
  double v[9];
  const vtkIdType ids[3] = { a, b, c };
  for (int k = 0; k < 3; ++k)
  {
    for (int d = 0; d < 3; ++d)
    {
      v[3 * k + d] = points[3 * ids[k] + d];
    }
  }
  const double edge = LongestEdge(v);
  if (!(DoubledArea(v) > DegenerateRatio * edge * edge))
  {
    ++dropped;
    return;
  }
  world.insert(world.end(), v, v + 9);
  sources.push_back({ surface, cell, { a, b, c } });
}

// Triangles of the polygons (fan for quads, ear cutting beyond) and strips of one surface.
void Triangulate(vtkPolyData* mesh, const std::vector<double>& points, int surface,
  std::vector<double>& world, std::vector<SourceTriangle>& sources, vtkIdType& dropped)
{
  const vtkIdType npts = mesh->GetNumberOfPoints();
  vtkIdType cell = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
  vtkNew<vtkPolygon> polygon;
  vtkNew<vtkIdList> local;
  vtkIdType n;
  const vtkIdType* ids;
  auto valid = [&](vtkIdType count, const vtkIdType* list)
  { return std::all_of(list, list + count, [&](vtkIdType id) { return id >= 0 && id < npts; }); };
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(n, ids); ++cell)
  {
    if (n < 3 || !valid(n, ids))
    {
      dropped += std::max<vtkIdType>(n - 2, 0);
      continue;
    }
    if (n <= 4)
    {
      for (vtkIdType k = 1; k + 1 < n; ++k)
      {
        AddTriangle(points, surface, cell, ids[0], ids[k], ids[k + 1], world, sources, dropped);
      }
      continue;
    }
    polygon->GetPointIds()->SetNumberOfIds(n);
    polygon->GetPoints()->SetNumberOfPoints(n);
    for (vtkIdType k = 0; k < n; ++k)
    {
      polygon->GetPointIds()->SetId(k, k);
      polygon->GetPoints()->SetPoint(k, &points[3 * ids[k]]);
    }
    if (polygon->Triangulate(local) && local->GetNumberOfIds() == 3 * (n - 2))
    {
      for (vtkIdType k = 0; k + 2 < local->GetNumberOfIds(); k += 3)
      {
        AddTriangle(points, surface, cell, ids[local->GetId(k)], ids[local->GetId(k + 1)],
          ids[local->GetId(k + 2)], world, sources, dropped);
      }
    }
    else
    {
      for (vtkIdType k = 1; k + 1 < n; ++k)
      {
        AddTriangle(points, surface, cell, ids[0], ids[k], ids[k + 1], world, sources, dropped);
      }
    }
  }
  vtkCellArray* strips = mesh->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(n, ids); ++cell)
  {
    if (!valid(n, ids))
    {
      dropped += std::max<vtkIdType>(n - 2, 0);
      continue;
    }
    for (vtkIdType k = 0; k + 2 < n; ++k)
    {
      // Every other triangle of a strip is reversed to keep one winding.
      const vtkIdType a = ids[k], b = ids[k + 1], c = ids[k + 2];
      if (k % 2 == 0)
      {
        AddTriangle(points, surface, cell, a, b, c, world, sources, dropped);
      }
      else
      {
        AddTriangle(points, surface, cell, b, a, c, world, sources, dropped);
      }
    }
  }
}

// Per-point (u, v) for the checker: TCoords, or planar over the two largest model extents.
std::vector<double> TextureCoordinates(vtkPolyData* mesh)
{
  const vtkIdType n = mesh->GetNumberOfPoints();
  std::vector<double> uv(2 * n);
  vtkDataArray* tcoords = mesh->GetPointData()->GetTCoords();
  if (tcoords && tcoords->GetNumberOfComponents() >= 2 && tcoords->GetNumberOfTuples() == n)
  {
    for (vtkIdType p = 0; p < n; ++p)
    {
      uv[2 * p] = tcoords->GetComponent(p, 0);
      uv[2 * p + 1] = tcoords->GetComponent(p, 1);
    }
    return uv;
  }
  double b[6];
  mesh->GetPoints()->GetBounds(b);
  std::array<int, 3> axes = { 0, 1, 2 };
  std::stable_sort(axes.begin(), axes.end(),
    [&](int x, int y) { return b[2 * x + 1] - b[2 * x] > b[2 * y + 1] - b[2 * y]; });
  for (vtkIdType p = 0; p < n; ++p)
  {
    double x[3];
    mesh->GetPoint(p, x);
    for (int k = 0; k < 2; ++k)
    {
      const int a = axes[k];
      const double extent = b[2 * a + 1] - b[2 * a];
      uv[2 * p + k] = extent > 0 ? (x[a] - b[2 * a]) / extent : 0.0;
    }
  }
  return uv;
}
}

//------------------------------------------------------------------------------
bool vtkRefractaSurfaceSet::Build()
{
  const vtkMTimeType mtime = this->GetMTime();
  if (this->Built && mtime <= this->BuiltMTime)
  {
    return true;
  }
  const auto start = std::chrono::steady_clock::now();
  Internals& impl = *this->Impl;
  impl.World.clear();
  impl.Sources.clear();
  this->DroppedTriangles = 0;
  this->RejectedSurfaces = 0;
  std::vector<double> points;
  for (int s = 0; s < this->GetNumberOfSurfaces(); ++s)
  {
    const auto& entry = impl.Surfaces[s];
    if (!entry.Mesh->GetPoints() || entry.Mesh->GetNumberOfPoints() == 0)
    {
      continue; // an empty mesh has nothing to draw
    }
    if (!TransformPoints(entry.Mesh, entry.Matrix, points))
    {
      vtkErrorMacro("Surface " << s << " (" << entry.Mesh->GetNumberOfPoints()
                               << " points) has a non-finite (NaN or Inf) vertex"
                               << (entry.Matrix ? " after its matrix" : "")
                               << "; every point of a surface must be finite. It is skipped.");
      ++this->RejectedSurfaces;
      continue;
    }
    Triangulate(entry.Mesh, points, s, impl.World, impl.Sources, this->DroppedTriangles);
  }
  const vtkIdType triangles = static_cast<vtkIdType>(impl.Sources.size());
  if (triangles > std::numeric_limits<int>::max())
  {
    vtkErrorMacro("The surfaces have " << triangles << " triangles; at most 2^31 - 1 are "
                                       << "supported. Nothing was built.");
    impl.BVH->Build(nullptr, 0);
    this->TriangleInfo.clear();
    this->TexelAlbedo.clear();
    this->TexelAreas.clear();
    this->TriangleNormals.clear();
    this->SurfaceInterfaces.clear();
    this->SurfaceBodies.clear();
    this->CornerOffsets.assign(1, 0);
    this->CornerTexels.clear();
    this->DielectricTriangles = 0;
    return false;
  }
  impl.BVH->Build(impl.World.data(), triangles);
  this->LayOutAtlas();
  this->BakeAlbedo();
  impl.Shared.Build(this, impl.BVH, impl.Sources);
  this->DescribeInterfaces();
  this->LinkCorners();
  impl.Shared.Clear();
  impl.World.clear();
  impl.World.shrink_to_fit();
  this->Built = true;
  this->BuiltMTime = mtime;
  ++this->NumberOfBuilds;
  this->BuildSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceSet::LayOutAtlas()
{
  const vtkRefractaBVH* bvh = this->Impl->BVH;
  const vtkIdType triangles = bvh->GetNumberOfTriangles();
  const std::vector<double>& tri = bvh->GetTriangles();
  const std::vector<vtkIdType>& order = bvh->GetTriangleOrder();
  // A dielectric triangle receives no deposits: longest edge 0 gives it one texel. The automatic
  // size follows the bounds of the triangles that do receive them, so adding glass to a scene
  // does not coarsen its floor's texels.
  std::vector<double> longest(triangles);
  double b[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX,
    -VTK_DOUBLE_MAX };
  for (vtkIdType k = 0; k < triangles; ++k)
  {
    const bool glass = this->IsDielectric(this->Impl->Sources[order[k]].Surface);
    longest[k] = glass ? 0.0 : LongestEdge(&tri[9 * k]);
    for (int c = 0; !glass && c < 9; ++c)
    {
      b[2 * (c % 3)] = std::min(b[2 * (c % 3)], tri[9 * k + c]);
      b[2 * (c % 3) + 1] = std::max(b[2 * (c % 3) + 1], tri[9 * k + c]);
    }
  }
  const double diagonal = b[1] >= b[0]
    ? std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
        (b[5] - b[4]) * (b[5] - b[4]))
    : 1.0;
  double size = this->TexelSize > 0 ? this->TexelSize : diagonal / AutomaticTexelsPerDiagonal;
  if (!(size > 0))
  {
    size = 1.0;
  }
  const vtkIdType budget = std::max<vtkIdType>(
    triangles, std::min<vtkIdType>(this->MaximumNumberOfTexels, std::numeric_limits<int>::max()));
  std::vector<int> subdivision(triangles, 1);
  for (int attempt = 0; attempt < 200; ++attempt)
  {
    vtkIdType total = 0;
    for (vtkIdType k = 0; k < triangles; ++k)
    {
      const double n = std::ceil(longest[k] / size);
      subdivision[k] =
        static_cast<int>(std::max(1.0, std::min(n, double(this->MaximumTexelSubdivision))));
      total += vtkIdType(subdivision[k]) * subdivision[k];
    }
    if (total <= budget)
    {
      break;
    }
    // Texel count goes as 1 / size^2: grow the size by the square root of the excess (and at
    // least 1%, so the loop always advances).
    size *= std::max(1.01, std::sqrt(double(total) / double(budget)));
  }
  this->EffectiveTexelSize = size;
  this->TriangleInfo.assign(REFRACTA_TRIANGLE_INFO_INTS * triangles, 0);
  this->TexelAreas.clear();
  vtkIdType offset = 0;
  for (vtkIdType k = 0; k < triangles; ++k)
  {
    const int n = subdivision[k];
    int* info = &this->TriangleInfo[REFRACTA_TRIANGLE_INFO_INTS * k];
    info[REFRACTA_TRIANGLE_INFO_TEXEL] = static_cast<int>(offset);
    info[REFRACTA_TRIANGLE_INFO_SUBDIVISION] = n;
    info[REFRACTA_TRIANGLE_INFO_SURFACE] = this->Impl->Sources[order[k]].Surface;
    const double area = 0.5 * DoubledArea(&tri[9 * k]);
    this->TexelAreas.insert(this->TexelAreas.end(), size_t(n) * n, area / (double(n) * n));
    offset += vtkIdType(n) * n;
  }
}

namespace
{
// The colour source of each surface, prepared once per build.
std::vector<ColorSource> PrepareColorSources(
  vtkRefractaSurfaceSet* self, std::vector<int>& missingScalars, std::vector<int>& unusableTextures)
{
  std::vector<ColorSource> sources(self->GetNumberOfSurfaces());
  for (int s = 0; s < self->GetNumberOfSurfaces(); ++s)
  {
    ColorSource& c = sources[s];
    vtkPolyData* mesh = self->GetSurface(s);
    c.Material = self->GetMaterial(s);
    if (c.Material->GetUseScalarColors())
    {
      vtkDataArray* point = mesh->GetPointData()->GetScalars();
      vtkDataArray* cell = mesh->GetCellData()->GetScalars();
      if (IsColorArray(point) && point->GetNumberOfTuples() == mesh->GetNumberOfPoints())
      {
        c.Type = ColorSource::POINT_SCALARS;
        c.Scalars = point;
      }
      else if (IsColorArray(cell) && cell->GetNumberOfTuples() == mesh->GetNumberOfCells())
      {
        c.Type = ColorSource::CELL_SCALARS;
        c.Scalars = cell;
      }
      else
      {
        missingScalars.push_back(s);
      }
      if (c.Scalars)
      {
        c.ScalarScale = c.Scalars->GetDataType() == VTK_UNSIGNED_CHAR ? 1.0 / 255.0 : 1.0;
        continue;
      }
    }
    if (c.Material->GetTexture() && !c.Material->HasUsableTexture())
    {
      unusableTextures.push_back(s);
    }
    if (c.Material->HasUsableTexture())
    {
      c.Type = ColorSource::TEXTURE;
      c.TextureCoords = TextureCoordinates(mesh);
    }
    else if (c.Material->GetUseChecker())
    {
      c.Type = ColorSource::CHECKER;
      c.TextureCoords = TextureCoordinates(mesh);
    }
  }
  return sources;
}

// Albedo at barycentric (u, v) of a triangle.
void EvaluateColor(const ColorSource& c, const SourceTriangle& t, double u, double v, double rgb[3])
{
  const double w[3] = { 1.0 - u - v, u, v };
  switch (c.Type)
  {
    case ColorSource::POINT_SCALARS:
      for (int ch = 0; ch < 3; ++ch)
      {
        double sum = 0;
        for (int k = 0; k < 3; ++k)
        {
          sum += w[k] * c.Scalars->GetComponent(t.Points[k], ch);
        }
        rgb[ch] = sum * c.ScalarScale;
      }
      break;
    case ColorSource::CELL_SCALARS:
      for (int ch = 0; ch < 3; ++ch)
      {
        rgb[ch] = c.Scalars->GetComponent(t.Cell, ch) * c.ScalarScale;
      }
      break;
    case ColorSource::CHECKER:
    case ColorSource::TEXTURE:
    {
      double tu = 0, tv = 0;
      for (int k = 0; k < 3; ++k)
      {
        tu += w[k] * c.TextureCoords[2 * t.Points[k]];
        tv += w[k] * c.TextureCoords[2 * t.Points[k] + 1];
      }
      if (c.Type == ColorSource::CHECKER)
      {
        c.Material->EvaluateChecker(tu, tv, rgb);
        break;
      }
      // Modulated by the albedo, as VTK modulates an actor's texture by its colour.
      double albedo[3];
      c.Material->GetAlbedo(albedo);
      c.Material->EvaluateTexture(tu, tv, rgb);
      for (int ch = 0; ch < 3; ++ch)
      {
        rgb[ch] *= albedo[ch];
      }
      break;
    }
    default:
      c.Material->GetAlbedo(rgb);
  }
  for (int ch = 0; ch < 3; ++ch)
  {
    rgb[ch] = rgb[ch] >= 0.0 ? std::min(rgb[ch], 1.0) : 0.0;
  }
}
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceSet::BakeAlbedo()
{
  std::vector<int> missing, unusable;
  const std::vector<ColorSource> colors = PrepareColorSources(this, missing, unusable);
  for (int s : unusable)
  {
    vtkWarningMacro("Surface " << s << " has a texture that cannot be sampled (a 2D image, one "
                               << "slice thick, with one colour tuple of 1 to 4 components per "
                               << "pixel is needed); its checker or albedo is used instead.");
  }
  for (int s : missing)
  {
    vtkWarningMacro("Surface " << s << " asks for scalar colours (UseScalarColors) but has no "
                               << "colour scalars (3 or 4 components, unsigned char 0-255 or "
                               << "float in [0, 1]); its checker or albedo is used instead.");
  }
  const vtkRefractaBVH* bvh = this->Impl->BVH;
  const std::vector<vtkIdType>& order = bvh->GetTriangleOrder();
  this->TexelAlbedo.assign(3 * this->TexelAreas.size(), 0.0f);
  for (vtkIdType k = 0; k < bvh->GetNumberOfTriangles(); ++k)
  {
    const int* info = &this->TriangleInfo[REFRACTA_TRIANGLE_INFO_INTS * k];
    const int n = info[REFRACTA_TRIANGLE_INFO_SUBDIVISION];
    const SourceTriangle& source = this->Impl->Sources[order[k]];
    const ColorSource& color = colors[source.Surface];
    for (int texel = 0; texel < n * n; ++texel)
    {
      double uv[8];
      GetTexelSamplePoints(texel, n, uv);
      double mean[3] = { 0, 0, 0 };
      for (int q = 0; q < 4; ++q)
      {
        double rgb[3];
        EvaluateColor(color, source, uv[2 * q], uv[2 * q + 1], rgb);
        for (int ch = 0; ch < 3; ++ch)
        {
          mean[ch] += 0.25 * rgb[ch];
        }
      }
      float* out = &this->TexelAlbedo[3 * (size_t(info[REFRACTA_TRIANGLE_INFO_TEXEL]) + texel)];
      for (int ch = 0; ch < 3; ++ch)
      {
        out[ch] = static_cast<float>(mean[ch]);
      }
    }
  }
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceSet::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfSurfaces: " << this->GetNumberOfSurfaces() << "\n";
  os << indent << "TexelSize: " << this->TexelSize << "\n";
  os << indent << "MaximumTexelSubdivision: " << this->MaximumTexelSubdivision << "\n";
  os << indent << "MaximumNumberOfTexels: " << this->MaximumNumberOfTexels << "\n";
  os << indent << "NumberOfTriangles: " << this->GetNumberOfTriangles() << "\n";
  os << indent << "NumberOfTexels: " << this->GetNumberOfTexels() << "\n";
  os << indent << "EffectiveTexelSize: " << this->EffectiveTexelSize << "\n";
  os << indent << "NumberOfDroppedTriangles: " << this->DroppedTriangles << "\n";
  os << indent << "NumberOfDielectricTriangles: " << this->DielectricTriangles << "\n";
  os << indent << "NumberOfRejectedSurfaces: " << this->RejectedSurfaces << "\n";
  os << indent << "NumberOfBuilds: " << this->NumberOfBuilds << "\n";
}
