// Placement invariance (issue 12, "one set of conventions"): the same medium, camera and light
// expressed through three placements of the grid must give the same view-pass image, photon
// lighting volume, reference image and scene analysis:
//   (a) extent starting at 0, identity direction matrix;
//   (b) extent starting at (10, -3, 5) with the origin shifted so that every voxel is at the same
//       world position as in (a);
//   (c) the (b) grid rotated by R (direction matrix R, origin R o_b), with the camera and the light
//       rotated by R as well.
// (a) vs (b) must agree to float rounding (1e-5 relative); (c) to the rounding of a rotated frame:
// view pass and reference 1e-4 and 1e-5 relative, the photon lighting volume 5e-2 per voxel (a
// photon whose float decisions flip moves its whole deposit). Measured on PoCL (CPU) at the
// time of writing: 0 everywhere except the reference's (c), 7e-8. Before the frames were
// unified the view pass differed by 0.998 relative (b and c), the reference by 0.4, the scene
// analysis' optical thickness toward the light 2.30 vs 2.75.
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkReferenceRenderer.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaViewPass.h"
#include "vtkSceneAnalysis.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

namespace
{
constexpr int N[3] = { 12, 10, 8 };
constexpr double S[3] = { 0.1, 0.11, 0.09 };
constexpr double OriginA[3] = { 0.3, -0.2, 0.5 };
constexpr int ExtentMinB[3] = { 10, -3, 5 };

// Rotation by 40 degrees about (1, 2, 3).
void Rotation(double r[9])
{
  double axis[3] = { 1, 2, 3 };
  vtkMath::Normalize(axis);
  const double a = vtkMath::RadiansFromDegrees(40.0), c = std::cos(a), s = std::sin(a);
  const double x = axis[0], y = axis[1], z = axis[2];
  const double m[9] = { c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s,
    y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s, z * x * (1 - c) - y * s,
    z * y * (1 - c) + x * s, c + z * z * (1 - c) };
  std::copy(m, m + 9, r);
}

void Rotate(const double r[9], const double in[3], double out[3])
{
  for (int i = 0; i < 3; ++i)
  {
    out[i] = r[3 * i] * in[0] + r[3 * i + 1] * in[1] + r[3 * i + 2] * in[2];
  }
}

// The medium in placement p (0: a, 1: b, 2: c). Values depend only on the stored index.
vtkSmartPointer<vtkImageData> MakeMedium(int placement)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  int lo[3] = { 0, 0, 0 };
  double origin[3] = { OriginA[0], OriginA[1], OriginA[2] };
  if (placement > 0)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = ExtentMinB[a];
      origin[a] = OriginA[a] - S[a] * ExtentMinB[a];
    }
  }
  image->SetExtent(lo[0], lo[0] + N[0] - 1, lo[1], lo[1] + N[1] - 1, lo[2], lo[2] + N[2] - 1);
  image->SetSpacing(S[0], S[1], S[2]);
  if (placement == 2)
  {
    double r[9], o[3];
    Rotation(r);
    Rotate(r, origin, o);
    std::copy(o, o + 3, origin);
    image->SetDirectionMatrix(r);
  }
  image->SetOrigin(origin);
  const vtkIdType n = image->GetNumberOfPoints();
  auto make = [&](int id)
  {
    vtkNew<vtkFloatArray> array;
    array->SetName(vtkRefractaMedium::GetArrayName(id));
    array->SetNumberOfComponents(vtkRefractaMedium::GetNumberOfComponents(id));
    array->SetNumberOfTuples(n);
    image->GetPointData()->AddArray(array);
    return array.GetPointer();
  };
  vtkFloatArray* index = make(vtkRefractaMedium::REFRACTIVE_INDEX);
  vtkFloatArray* sigma = make(vtkRefractaMedium::EXTINCTION);
  vtkFloatArray* albedo = make(vtkRefractaMedium::ALBEDO);
  vtkFloatArray* g = make(vtkRefractaMedium::ANISOTROPY);
  for (int k = 0; k < N[2]; ++k)
  {
    for (int j = 0; j < N[1]; ++j)
    {
      for (int i = 0; i < N[0]; ++i)
      {
        const vtkIdType id = i + N[0] * (j + static_cast<vtkIdType>(N[1]) * k);
        const double x = i * S[0], y = j * S[1], z = k * S[2]; // grid-local
        const double dx = x - 0.6, dy = y - 0.45, dz = z - 0.3;
        const double blob = std::exp(-(dx * dx + dy * dy + dz * dz) / (0.3 * 0.3));
        index->SetValue(id, static_cast<float>(1.0 + 0.3 * blob));
        const double s = 1.5 + 1.2 * std::sin(4 * x + 2) * std::cos(3 * y - 1) + 0.5 * z;
        sigma->SetTuple3(id, s, 0.8 * s, 1.2 * s);
        albedo->SetTuple3(id, 0.8, 0.7, 0.6);
        g->SetValue(id, 0.3f);
      }
    }
  }
  return image;
}

// Camera and light of placement a, rotated by R for placement c.
struct Scene
{
  vtkSmartPointer<vtkCamera> Camera = vtkSmartPointer<vtkCamera>::New();
  vtkSmartPointer<vtkLight> Light = vtkSmartPointer<vtkLight>::New();
};

Scene MakeScene(int placement)
{
  double pos[3] = { OriginA[0] + 0.5, OriginA[1] + 0.3, OriginA[2] + 2.5 };
  double focal[3] = { OriginA[0] + 0.55, OriginA[1] + 0.5, OriginA[2] + 0.3 };
  double up[3] = { 0.1, 1, 0 };
  double light[3] = { OriginA[0] - 0.8, OriginA[1] + 1.6, OriginA[2] + 0.9 };
  double lightFocal[3] = { OriginA[0] + 0.55, OriginA[1] + 0.5, OriginA[2] + 0.3 };
  if (placement == 2)
  {
    double r[9], t[3];
    Rotation(r);
    for (double* v : { pos, focal, up, light, lightFocal })
    {
      Rotate(r, v, t);
      std::copy(t, t + 3, v);
    }
  }
  Scene s;
  s.Camera->SetPosition(pos);
  s.Camera->SetFocalPoint(focal);
  s.Camera->SetViewUp(up);
  s.Camera->SetViewAngle(35);
  s.Light->SetPositional(true);
  s.Light->SetConeAngle(180);
  s.Light->SetPosition(light);
  s.Light->SetFocalPoint(lightFocal);
  s.Light->SetIntensity(3.0);
  s.Light->SetLightTypeToSceneLight();
  return s;
}

struct Difference
{
  double MaxAbs = 0;
  double MaxRel = 0; // max |x - y| / max(|y|)
};

// The i-th value of an array, components of a tuple adjacent.
double Value(vtkDataArray* a, vtkIdType i)
{
  const int n = a->GetNumberOfComponents();
  return a->GetComponent(i / n, static_cast<int>(i % n));
}

Difference Compare(vtkDataArray* x, vtkDataArray* y)
{
  Difference d;
  if (!x || !y || x->GetNumberOfValues() != y->GetNumberOfValues())
  {
    d.MaxAbs = d.MaxRel = 1e30;
    return d;
  }
  double scale = 0;
  for (vtkIdType i = 0; i < y->GetNumberOfValues(); ++i)
  {
    const double a = Value(x, i), b = Value(y, i);
    scale = std::max(scale, std::abs(b));
    d.MaxAbs = std::max(d.MaxAbs, std::abs(a - b));
  }
  d.MaxRel = scale > 0 ? d.MaxAbs / scale : d.MaxAbs;
  return d;
}

const char* const Names[3] = { "a (extent 0)", "b (extent (10,-3,5), shifted origin)",
  "c (rotated direction matrix, camera and light)" };

constexpr double LightRadius = 0.05; // world units, explicit for both tracer and reference
} // namespace

TEST(GridInvariance, PhotonTracerAndViewPass)
{
  vtkSmartPointer<vtkImageData> lighting[3], image[3];
  for (int p = 0; p < 3; ++p)
  {
    auto medium = MakeMedium(p);
    Scene s = MakeScene(p);
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetInputData(medium);
    tracer->AddLight(s.Light);
    tracer->SetNumberOfPhotons(20000);
    tracer->SetSeed(7);
    tracer->SetLightRadius(LightRadius);
    tracer->Update();
    lighting[p] = tracer->GetOutput();
    ASSERT_GT(lighting[p]->GetNumberOfPoints(), 0) << Names[p];

    vtkNew<vtkRefractaImageRenderer> renderer;
    renderer->SetInputData(medium);
    renderer->SetLightingData(lighting[p]);
    renderer->SetCamera(s.Camera);
    renderer->SetImageSize(32, 24);
    renderer->SetBackgroundColor(0.2, 0.3, 0.4);
    renderer->Update();
    image[p] = renderer->GetOutput();
    ASSERT_GT(image[p]->GetNumberOfPoints(), 0) << Names[p];
    EXPECT_TRUE(renderer->GetViewPass()->GetLastCurved()) << "the blob must bend the view rays";
  }
  // The scene is not trivial: the light deposits, and the image is not uniform.
  double deposited = 0, lo = 1e30, hi = -1e30;
  vtkDataArray* s1 =
    lighting[0]->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName());
  vtkDataArray* hdr0 = image[0]->GetPointData()->GetArray("HDR");
  ASSERT_NE(s1, nullptr);
  ASSERT_NE(hdr0, nullptr);
  for (vtkIdType i = 0; i < s1->GetNumberOfValues(); ++i)
  {
    deposited += Value(s1, i);
  }
  for (vtkIdType i = 0; i < hdr0->GetNumberOfTuples(); ++i)
  {
    lo = std::min(lo, hdr0->GetComponent(i, 0));
    hi = std::max(hi, hdr0->GetComponent(i, 0));
  }
  EXPECT_GT(deposited, 0.0);
  EXPECT_GT(hi - lo, 0.05);
  const char* radiance = vtkRefractaLightingVolume::RadianceName();
  for (int p = 1; p < 3; ++p)
  {
    const Difference l = Compare(lighting[p]->GetPointData()->GetArray(radiance),
      lighting[0]->GetPointData()->GetArray(radiance));
    const Difference v =
      Compare(image[p]->GetPointData()->GetArray("HDR"), image[0]->GetPointData()->GetArray("HDR"));
    std::cout << Names[p] << " vs a: photon Radiance max rel diff " << l.MaxRel
              << ", view pass HDR max abs diff " << v.MaxAbs << " (max rel " << v.MaxRel << ")\n";
    // (a) vs (b): identical grid-local scene, differences are float rounding of the frame.
    // (c): the rotated frame rounds differently in the float kernels; a photon path whose
    // decisions flip moves its deposit, hence the looser photon tolerance (per-voxel maximum).
    EXPECT_LE(v.MaxRel, p == 1 ? 1e-5 : 1e-4) << Names[p];
    EXPECT_LE(l.MaxRel, p == 1 ? 1e-5 : 5e-2) << Names[p];
  }
}

TEST(GridInvariance, ReferenceRenderer)
{
  vtkSmartPointer<vtkImageData> image[3];
  for (int p = 0; p < 3; ++p)
  {
    auto medium = MakeMedium(p);
    Scene s = MakeScene(p);
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(s.Camera);
    r->AddLight(s.Light);
    r->SetImageSize(12, 9);
    r->SetSamplesPerPixel(2);
    r->SetSeed(3);
    r->SetLightRadius(LightRadius);
    r->SetBackgroundColor(0.2, 0.3, 0.4);
    r->Update();
    image[p] = r->GetOutput();
    ASSERT_GT(image[p]->GetNumberOfPoints(), 0) << Names[p];
  }
  for (int p = 1; p < 3; ++p)
  {
    const Difference v =
      Compare(image[p]->GetPointData()->GetArray("HDR"), image[0]->GetPointData()->GetArray("HDR"));
    std::cout << Names[p] << " vs a: reference HDR max abs diff " << v.MaxAbs << " (max rel "
              << v.MaxRel << ")\n";
    EXPECT_LE(v.MaxRel, 1e-5) << Names[p];
  }
}

TEST(GridInvariance, SceneAnalysis)
{
  double thickness[3] = { 0, 0, 0 };
  for (int p = 0; p < 3; ++p)
  {
    auto medium = MakeMedium(p);
    Scene s = MakeScene(p);
    vtkNew<vtkSceneAnalysis> analysis;
    analysis->SetMedium(medium);
    analysis->AddLight(s.Light);
    ASSERT_TRUE(analysis->Analyze()) << Names[p];
    thickness[p] = analysis->GetOpticalThicknessTowardLight(0);
  }
  std::cout << "optical thickness toward the light: " << thickness[0] << ", " << thickness[1]
            << ", " << thickness[2] << "\n";
  EXPECT_NEAR(thickness[1], thickness[0], 1e-9 * thickness[0]);
  EXPECT_NEAR(thickness[2], thickness[0], 1e-6 * thickness[0]);
}
