// The reference photon mapper (stochastic progressive photon mapping in the medium) against the
// unbiased path tracer where the latter converges, against analytic answers (emission, the
// ball-lens focus, the bending of a ray in a linear index gradient), its error against the number
// of passes, its error estimate, determinism and bad input.
#include "ReferenceTestUtilities.h"

#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkReferencePhotonMapper.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace reftest;

namespace
{
vtkSmartPointer<vtkImageData> Render(vtkReferenceRenderer* r)
{
  r->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(r->GetOutput());
  return out;
}

double FieldValue(vtkImageData* out, const char* name, vtkIdType i = 0)
{
  vtkDataArray* a = out->GetFieldData()->GetArray(name);
  return a && i < a->GetNumberOfTuples() ? a->GetComponent(i, 0) : -1;
}

double Hdr(vtkImageData* out, vtkIdType p, int c = 0)
{
  return out->GetPointData()->GetArray("HDR")->GetComponent(p, c);
}

double Se(vtkImageData* out, vtkIdType p, int c = 0)
{
  return out->GetPointData()->GetArray("StandardError")->GetComponent(p, c);
}

// A 16^3 cube of unit side, sigma_t = 2, albedo 0.8, g = 0.3, lit from the side and above by a
// directional light, seen by a parallel camera along -z: the path tracer converges here.
struct CubeScene
{
  vtkSmartPointer<vtkImageData> Medium;
  vtkSmartPointer<vtkCamera> Camera;
  vtkSmartPointer<vtkLight> Light;
  CubeScene()
  {
    const int dims[3] = { 16, 16, 16 };
    const double s = 1.0 / 15, spacing[3] = { s, s, s }, origin[3] = { 0, 0, 0 };
    Voxel v;
    for (int c = 0; c < 3; ++c)
    {
      v.Sigma[c] = 2;
      v.Albedo[c] = 0.8;
    }
    v.G = 0.3;
    Medium = Homogeneous(dims, spacing, origin, v);
    const double focal[3] = { 0.5, 0.5, 0.5 }, dop[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
    Camera = ParallelCamera(focal, dop, up, 0.5);
    const double towards[3] = { 0.6, 0.5, 0.62 };
    Light = Directional(towards, 1.0);
  }
  void SetUp(vtkReferenceRenderer* r, int size) const
  {
    r->SetInputData(Medium);
    r->SetCamera(Camera);
    r->AddLight(Light);
    r->SetImageSize(size, size);
  }
};
} // namespace

// The two estimators see the same medium, lights and camera; on a scene where both converge the
// photon mapper's image (64 passes) must match the path tracer's within the combined noise plus
// the kernel's bias, pixel by pixel (RMS of the normalised differences) and over the image.
TEST(ReferencePhotonMapper, AgreesWithThePathTracerOnADenseCube)
{
  CubeScene scene;
  const int size = 8;
  vtkNew<vtkReferenceRenderer> pt;
  scene.SetUp(pt, size);
  pt->SetSamplesPerPixel(Spp(1024));
  auto truth = Render(pt);
  vtkNew<vtkReferencePhotonMapper> pm;
  scene.SetUp(pm, size);
  pm->SetPasses(64);
  pm->SetPhotonsPerPass(20000);
  pm->SetInitialRadius(1.0);
  auto out = Render(pm);
  double sumA = 0, sumB = 0, chi2 = 0;
  for (int p = 0; p < size * size; ++p)
  {
    sumA += Hdr(out, p);
    sumB += Hdr(truth, p);
    const double e2 = Se(out, p) * Se(out, p) + Se(truth, p) * Se(truth, p);
    chi2 += (Hdr(out, p) - Hdr(truth, p)) * (Hdr(out, p) - Hdr(truth, p)) / e2;
  }
  std::printf("cube: photon mapper mean %.5f, path tracer %.5f (ratio %.4f); pixel chi2/n %.2f; "
              "photon mapper %.1f s, %g photons stored\n",
    sumA / (size * size), sumB / (size * size), sumA / sumB, chi2 / (size * size),
    FieldValue(out, "RenderSeconds"), FieldValue(out, "StoredPhotons"));
  EXPECT_NEAR(sumA / sumB, 1.0, 0.03);
  EXPECT_LT(chi2 / (size * size), 3.0);
}
