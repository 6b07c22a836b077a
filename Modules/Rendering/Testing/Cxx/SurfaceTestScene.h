// Helpers shared by the view pass's surface tests: planes, Lambertian materials, a clear medium
// grid and lighting volumes whose surface irradiance the test prescribes per atlas texel.
#ifndef SurfaceTestScene_h
#define SurfaceTestScene_h

#include "RenderingTestUtilities.h"

#include "vtkFieldData.h"
#include "vtkMath.h"
#include "vtkPlaneSource.h"
#include "vtkPolyData.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRefractaViewPass.h"

#include <gtest/gtest.h>

#include <functional>

namespace refracta_test
{
inline vtkSmartPointer<vtkPolyData> Plane(
  const double origin[3], const double p1[3], const double p2[3], int resolution = 1)
{
  vtkNew<vtkPlaneSource> source;
  source->SetOrigin(origin[0], origin[1], origin[2]);
  source->SetPoint1(p1[0], p1[1], p1[2]);
  source->SetPoint2(p2[0], p2[1], p2[2]);
  source->SetResolution(resolution, resolution);
  source->Update();
  return source->GetOutput();
}

inline vtkSmartPointer<vtkRefractaSurfaceMaterial> Material(double r, double g, double b)
{
  auto material = vtkSmartPointer<vtkRefractaSurfaceMaterial>::New();
  material->SetAlbedo(r, g, b);
  return material;
}

// A lighting volume on the medium's grid with no source in the medium (MultipleScattering 0) and
// the given surface irradiance per texel.
inline vtkSmartPointer<vtkImageData> Lighting(vtkImageData* medium, vtkRefractaSurfaceSet* set,
  const std::function<void(const double centroid[3], double e[3])>& irradiance)
{
  auto light = vtkSmartPointer<vtkImageData>::New();
  light->CopyStructure(medium);
  refracta_test::AddConstant(light, vtkRefractaLightingVolume::MultipleScatteringName(), 3, 0);
  EXPECT_TRUE(set->Build());
  vtkNew<vtkFloatArray> e;
  e->SetName(vtkRefractaLightingVolume::SurfaceIrradianceName());
  e->SetNumberOfComponents(3);
  e->SetNumberOfTuples(set->GetNumberOfTexels());
  const std::vector<int>& info = set->GetTriangleInfo();
  const std::vector<double>& tri = set->GetBVH()->GetTriangles();
  const double* origin = set->GetBVH()->GetFrameOrigin();
  for (vtkIdType t = 0; t < set->GetNumberOfTriangles(); ++t)
  {
    const int first = info[4 * t], n = info[4 * t + 1];
    for (int k = 0; k < n * n; ++k)
    {
      double corners[6];
      EXPECT_TRUE(vtkRefractaSurfaceSet::GetTexelCorners(k, n, corners));
      const double u = (corners[0] + corners[2] + corners[4]) / 3;
      const double v = (corners[1] + corners[3] + corners[5]) / 3;
      double c[3], value[3];
      for (int a = 0; a < 3; ++a)
      {
        c[a] = origin[a] + (1 - u - v) * tri[9 * t + a] + u * tri[9 * t + 3 + a] +
          v * tri[9 * t + 6 + a];
      }
      irradiance(c, value);
      e->SetTuple(first + k, value);
    }
  }
  light->GetFieldData()->AddArray(e);
  return light;
}

inline vtkSmartPointer<vtkImageData> ClearMedium(int n, double spacing, const double origin[3])
{
  auto medium = refracta_test::MakeGrid(n, n, n, spacing, origin);
  refracta_test::AddConstant(medium, "Extinction", 3, 0, 0, 0);
  return medium;
}

// The pixel's ray (world = grid-local here: no direction matrix, origin handled by the frame).
inline void PixelRay(const vtkRefractaViewPass::RayFrame& f, vtkImageData* medium, int i, int j,
  int w, int h, double o[3], double d[3])
{
  const double sx = 2.0 * (i + 0.5) / w - 1.0, sy = 2.0 * (j + 0.5) / h - 1.0;
  double origin[3];
  medium->GetOrigin(origin);
  for (int a = 0; a < 3; ++a)
  {
    // Grid-local -> world: add the origin back (identity direction matrix).
    o[a] = (f.Parallel ? f.Eye[a] + sx * f.U[a] + sy * f.V[a] : f.Eye[a]) + origin[a];
    d[a] = f.Parallel ? f.W[a] : f.W[a] + sx * f.U[a] + sy * f.V[a];
  }
  vtkMath::Normalize(d);
}
}

#endif
