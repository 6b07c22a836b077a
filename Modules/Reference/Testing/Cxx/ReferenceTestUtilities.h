// Helpers shared by the reference renderer's tests: building media, cameras and lights, reading
// the output, and analytic references (Chandrasekhar's H-function, single scattering by a slab).
#ifndef ReferenceTestUtilities_h
#define ReferenceTestUtilities_h

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkReferenceRenderer.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <vector>

namespace reftest
{
constexpr double Pi = 3.14159265358979323846;

// Value `index` of the renderer's field-data array `name` (NaN when there is none).
inline double FieldValue(vtkImageData* image, const char* name, vtkIdType index = 0)
{
  vtkDataArray* a = image->GetFieldData()->GetArray(name);
  return a && index < a->GetNumberOfTuples() ? a->GetComponent(index, 0) : std::nan("");
}

struct Voxel
{
  double N = 1;
  double Sigma[3] = { 0, 0, 0 };
  double Albedo[3] = { 0, 0, 0 };
  double G = 0;
  double Emission[3] = { 0, 0, 0 };
};

// A medium of dims voxels; `fill(i, j, k, voxel)` sets each voxel. Arrays are always written.
inline vtkSmartPointer<vtkImageData> MakeMedium(const int dims[3], const double spacing[3],
  const double origin[3], const std::function<void(int, int, int, Voxel&)>& fill)
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetDimensions(dims[0], dims[1], dims[2]);
  img->SetSpacing(spacing[0], spacing[1], spacing[2]);
  img->SetOrigin(origin[0], origin[1], origin[2]);
  const vtkIdType n = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  auto make = [&](const char* name, int nc)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(nc);
    a->SetNumberOfTuples(n);
    img->GetPointData()->AddArray(a);
    return a.Get();
  };
  auto* ni = make("RefractiveIndex", 1);
  auto* si = make("Extinction", 3);
  auto* ai = make("Albedo", 3);
  auto* gi = make("Anisotropy", 1);
  auto* ei = make("Emission", 3);
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        Voxel v;
        fill(i, j, k, v);
        const vtkIdType id = i + dims[0] * (j + static_cast<vtkIdType>(dims[1]) * k);
        ni->SetValue(id, v.N);
        gi->SetValue(id, v.G);
        for (int c = 0; c < 3; ++c)
        {
          si->SetComponent(id, c, v.Sigma[c]);
          ai->SetComponent(id, c, v.Albedo[c]);
          ei->SetComponent(id, c, v.Emission[c]);
        }
      }
    }
  }
  return img;
}

// Samples per pixel for a test, multiplied by the environment variable
// REFRACTA_TEST_SAMPLE_SCALE (default 1) to rerun the same comparisons at higher precision.
inline int Spp(int n)
{
  const char* s = std::getenv("REFRACTA_TEST_SAMPLE_SCALE");
  const double f = s ? std::atof(s) : 1.0;
  return std::max(1, static_cast<int>(n * (f > 0 ? f : 1.0)));
}

inline vtkSmartPointer<vtkImageData> Homogeneous(
  const int dims[3], const double spacing[3], const double origin[3], const Voxel& v)
{
  return MakeMedium(dims, spacing, origin, [&](int, int, int, Voxel& out) { out = v; });
}

// A grey isotropic slab with sigma_t = 1 and the given albedo: 3 x 3 x 3 nodes spanning
// [-width, width]^2 laterally and [0, 2 depth] in z (effectively semi-infinite when depth >> 1).
inline vtkSmartPointer<vtkImageData> IsotropicSlab(double albedo, double width, double depth)
{
  const int dims[3] = { 3, 3, 3 };
  const double spacing[3] = { width, width, depth }, origin[3] = { -width, -width, 0 };
  Voxel v;
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = 1.0;
    v.Albedo[c] = albedo;
  }
  return Homogeneous(dims, spacing, origin, v);
}

inline vtkSmartPointer<vtkCamera> ParallelCamera(
  const double focal[3], const double dirOfProjection[3], const double up[3], double scale)
{
  auto cam = vtkSmartPointer<vtkCamera>::New();
  cam->ParallelProjectionOn();
  cam->SetFocalPoint(focal[0], focal[1], focal[2]);
  cam->SetPosition(focal[0] - 100 * dirOfProjection[0], focal[1] - 100 * dirOfProjection[1],
    focal[2] - 100 * dirOfProjection[2]);
  cam->SetViewUp(up[0], up[1], up[2]);
  cam->SetParallelScale(scale);
  return cam;
}

// Directional light coming FROM direction `towards` (unit, pointing at the light).
inline vtkSmartPointer<vtkLight> Directional(
  const double towards[3], double e, double r = 1, double g = 1, double b = 1)
{
  auto l = vtkSmartPointer<vtkLight>::New();
  l->SetLightTypeToSceneLight();
  l->PositionalOff();
  l->SetPosition(towards[0], towards[1], towards[2]);
  l->SetFocalPoint(0, 0, 0);
  l->SetIntensity(e);
  l->SetDiffuseColor(r, g, b);
  return l;
}

// Mean of HDR channel c over the image and the standard error of that mean (pixels independent).
struct Pooled
{
  double Mean[3] = { 0, 0, 0 };
  double Error[3] = { 0, 0, 0 };
};
inline Pooled Pool(vtkImageData* out)
{
  Pooled p;
  vtkDataArray* hdr = out->GetPointData()->GetArray("HDR");
  vtkDataArray* se = out->GetPointData()->GetArray("StandardError");
  const vtkIdType n = hdr->GetNumberOfTuples();
  for (int c = 0; c < 3; ++c)
  {
    double s = 0, v = 0;
    for (vtkIdType i = 0; i < n; ++i)
    {
      s += hdr->GetComponent(i, c);
      v += se->GetComponent(i, c) * se->GetComponent(i, c);
    }
    p.Mean[c] = s / n;
    p.Error[c] = std::sqrt(v) / n;
  }
  return p;
}

// Chandrasekhar's H-function for isotropic scattering with albedo w, by iterating
// H(mu) = 1 / (1 - (w / 2) mu int_0^1 H(mu') / (mu + mu') dmu') on a 64-point Gauss-Legendre grid;
// H at `mu` by the same relation. (The equivalent form with sqrt(1 - w) converges to a spurious
// solution at w = 1 under this iteration.)
inline double HFunction(double w, double mu);

// Gauss-Legendre nodes and weights on [0, 1].
inline void GaussLegendre(int n, std::vector<double>& x, std::vector<double>& wt)
{
  x.assign(n, 0);
  wt.assign(n, 0);
  for (int i = 0; i < n; ++i)
  {
    double z = std::cos(Pi * (i + 0.75) / (n + 0.5));
    auto legendre = [n](double zz, double& pn, double& dpn)
    {
      double p0 = 1, p1 = zz;
      for (int k = 2; k <= n; ++k)
      {
        const double p2 = ((2 * k - 1) * zz * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      pn = p1;
      dpn = n * (zz * p1 - p0) / (zz * zz - 1);
    };
    double pn, dpn;
    for (int it = 0; it < 100; ++it)
    {
      legendre(z, pn, dpn);
      const double dz = pn / dpn;
      z -= dz;
      if (std::abs(dz) < 1e-14)
      {
        break;
      }
    }
    legendre(z, pn, dpn);
    wt[i] = 1.0 / ((1 - z * z) * dpn * dpn); // half of 2 / ((1 - z^2) P'^2)
    x[i] = 0.5 * (1 - z);
  }
}

inline double HFunction(double w, double mu)
{
  const int n = 64;
  std::vector<double> x, wt, h(n, 1.0);
  GaussLegendre(n, x, wt);
  auto inv = [&](double m)
  {
    double s = 0;
    for (int j = 0; j < n; ++j)
    {
      s += wt[j] * h[j] / (m + x[j]);
    }
    return 1 - 0.5 * w * m * s;
  };
  for (int it = 0; it < 2000; ++it)
  {
    std::vector<double> hn(n);
    for (int i = 0; i < n; ++i)
    {
      hn[i] = 1.0 / inv(x[i]);
    }
    h = hn;
  }
  return 1.0 / inv(mu);
}
} // namespace reftest

#endif
