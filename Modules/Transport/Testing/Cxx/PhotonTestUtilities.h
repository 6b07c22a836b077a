// Helpers shared by the photon tracer tests: media built voxel by voxel, lights, field data.
#ifndef PhotonTestUtilities_h
#define PhotonTestUtilities_h

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>

namespace photontest
{
struct Voxel
{
  double N = 1.0;
  std::array<double, 3> Extinction{ 0, 0, 0 };
  std::array<double, 3> Albedo{ 0, 0, 0 };
};

// A medium whose arrays are given by f(x, y, z) at the voxel centres (grid-local coordinates).
inline vtkSmartPointer<vtkImageData> MakeMedium(int nx, int ny, int nz, double spacing,
  const std::function<Voxel(double, double, double)>& f, bool withN = true)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(spacing, spacing, spacing);
  vtkNew<vtkFloatArray> n, e, a;
  n->SetName("RefractiveIndex");
  e->SetName("Extinction");
  e->SetNumberOfComponents(3);
  a->SetName("Albedo");
  a->SetNumberOfComponents(3);
  const vtkIdType count = static_cast<vtkIdType>(nx) * ny * nz;
  n->SetNumberOfTuples(count);
  e->SetNumberOfTuples(count);
  a->SetNumberOfTuples(count);
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        const vtkIdType id = i + static_cast<vtkIdType>(nx) * (j + static_cast<vtkIdType>(ny) * k);
        const Voxel v = f(i * spacing, j * spacing, k * spacing);
        n->SetValue(id, static_cast<float>(v.N));
        e->SetTuple(id, v.Extinction.data());
        a->SetTuple(id, v.Albedo.data());
      }
    }
  }
  if (withN)
  {
    image->GetPointData()->AddArray(n);
  }
  image->GetPointData()->AddArray(e);
  image->GetPointData()->AddArray(a);
  return image;
}

// A refracting ball (n = 1.3, radius sqrt(0.06) about (0.5, 0.45, 0.4)) in a fog whose sigma_t is
// base + amplitude sin(6x) cos(4z) times `tint` per channel, albedo `albedo` everywhere, on an
// nx x ny x nz grid of spacing 0.05: every stage of the photon pass runs and every trilinear
// gather matters.
inline vtkSmartPointer<vtkImageData> RefractingFog(int nx, int ny, int nz, double base,
  double amplitude, std::array<double, 3> tint, std::array<double, 3> albedo)
{
  return MakeMedium(nx, ny, nz, 0.05,
    [=](double x, double y, double z)
    {
      Voxel v;
      const double r2 = (x - 0.5) * (x - 0.5) + (y - 0.45) * (y - 0.45) + (z - 0.4) * (z - 0.4);
      v.N = r2 < 0.06 ? 1.3 : 1.0;
      const double fog = base + amplitude * std::sin(6 * x) * std::cos(4 * z);
      v.Extinction = { fog * tint[0], fog * tint[1], fog * tint[2] };
      v.Albedo = albedo;
      return v;
    });
}

// A rectangle from `origin` spanned by the edges p1 - origin and p2 - origin (vtkPlaneSource).
inline vtkSmartPointer<vtkPolyData> Rectangle(
  std::array<double, 3> origin, std::array<double, 3> p1, std::array<double, 3> p2)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(origin.data());
  plane->SetPoint1(p1.data());
  plane->SetPoint2(p2.data());
  plane->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(plane->GetOutput());
  return out;
}

// Every array of `a` holds the same bits as `b`'s array of the same name (point data or field
// data: the outputs, the books and counters); arrays named *Seconds* (timings) are skipped.
inline void ExpectSameBits(vtkFieldData* a, vtkFieldData* b, const std::string& where)
{
  ASSERT_EQ(a->GetNumberOfArrays(), b->GetNumberOfArrays()) << where;
  for (int i = 0; i < a->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* x = a->GetArray(i);
    if (!x || std::string(x->GetName()).find("Seconds") != std::string::npos)
    {
      continue;
    }
    vtkDataArray* y = b->GetArray(x->GetName());
    ASSERT_TRUE(y) << x->GetName() << where;
    ASSERT_EQ(x->GetDataType(), y->GetDataType()) << x->GetName() << where;
    ASSERT_EQ(x->GetNumberOfValues(), y->GetNumberOfValues()) << x->GetName() << where;
    EXPECT_EQ(std::memcmp(x->GetVoidPointer(0), y->GetVoidPointer(0),
                static_cast<size_t>(x->GetNumberOfValues()) * x->GetDataTypeSize()),
      0)
      << x->GetName() << where;
  }
}

inline vtkSmartPointer<vtkLight> Directional(std::array<double, 3> from, std::array<double, 3> to,
  double intensity, std::array<double, 3> colour = { 1, 1, 1 })
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetPositional(false);
  light->SetPosition(from.data());
  light->SetFocalPoint(to.data());
  light->SetIntensity(intensity);
  light->SetDiffuseColor(colour.data());
  return light;
}

inline vtkSmartPointer<vtkLight> Positional(std::array<double, 3> at, std::array<double, 3> to,
  double coneAngle, double exponent, double intensity, std::array<double, 3> colour = { 1, 1, 1 })
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetPositional(true);
  light->SetPosition(at.data());
  light->SetFocalPoint(to.data());
  light->SetConeAngle(coneAngle);
  light->SetExponent(exponent);
  light->SetIntensity(intensity);
  light->SetDiffuseColor(colour.data());
  return light;
}

// Channel c of a surface texel's irradiance on one side (vtkRefractaLightingVolume::SurfaceSide).
inline double SideIrradiance(vtkDataArray* e, vtkIdType texel, int side, int c = 0)
{
  return vtkRefractaLightingVolume::GetSurfaceSideValue(e, texel, side, c, 3);
}

// Channel c of a texel's irradiance on both sides together: the flux that arrived on it from
// anywhere, per unit area.
inline double TexelIrradiance(vtkDataArray* e, vtkIdType texel, int c = 0)
{
  return SideIrradiance(e, texel, vtkRefractaLightingVolume::FRONT_SIDE, c) +
    SideIrradiance(e, texel, vtkRefractaLightingVolume::BACK_SIDE, c);
}

inline double Field(vtkImageData* image, const char* name, int component = 0)
{
  vtkDataArray* a = image->GetFieldData()->GetArray(name);
  return a ? a->GetComponent(0, component) : -1e300;
}

inline std::array<double, 3> Energy(vtkImageData* image, const char* name)
{
  return { Field(image, name, 0), Field(image, name, 1), Field(image, name, 2) };
}

// The output's float array `name`. A pass that failed (a kernel that did not build, a rejected
// input) leaves no such array: the test then fails with this message instead of crashing on a
// null pointer (GoogleTest reports the exception as the test's failure).
inline const float* FloatPointer(vtkImageData* image, const char* name)
{
  vtkFloatArray* array =
    image ? vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray(name)) : nullptr;
  if (!array)
  {
    throw std::runtime_error(std::string("the pass's output has no float array '") + name +
      "' (it failed: see the error above)");
  }
  return array->GetPointer(0);
}

inline const float* Radiance(vtkImageData* image)
{
  return FloatPointer(image, vtkRefractaLightingVolume::RadianceName());
}

inline const float* Direction(vtkImageData* image)
{
  return FloatPointer(image, vtkRefractaLightingVolume::RadianceDirectionName());
}
}

#endif
// VTK-HeaderTest-Exclude: PhotonTestUtilities.h
