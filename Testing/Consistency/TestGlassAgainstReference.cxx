// The view pass against the reference renderer (vtkReferenceRenderer, a double-precision path
// tracer) on glass: a tessellated ball (n = 1.5, vtkRefractaSurfaceMaterial DIELECTRIC) in front
// of a smooth environment map. The reference meets the same dielectric triangles
// (vtkReferenceSurfaces: the set's corner normals and index pairs, one Fresnel choice per
// interface by vtkRefractaDielectric::Sample); the view pass follows both legs to split depth 8
// (Physics.md, "Glass in the view pass"). The images must agree within the reference's standard
// error: per channel the summed difference within 4 pooled standard errors plus 1e-3 per glass
// pixel, and per pixel within 5 standard errors plus 2e-3 for 99% of the pixel channels.
#include "ReferenceTestUtilities.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkReferenceRenderer.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRefractaViewPass.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace reftest;

namespace
{
// An equirectangular map, smooth in u and v (bilinear lookups of it agree closely wherever the
// two renderers look it up).
vtkSmartPointer<vtkImageData> SmoothEnvironment()
{
  auto env = vtkSmartPointer<vtkImageData>::New();
  const int w = 64, h = 32;
  env->SetDimensions(w, h, 1);
  vtkNew<vtkFloatArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(w * h);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const double u = (i + 0.5) / w, v = (j + 0.5) / h;
      rgb->SetTuple3(
        i + w * j, 0.2 + 0.6 * u, 0.2 + 0.6 * v, 0.5 + 0.3 * std::sin(2 * vtkMath::Pi() * u));
    }
  }
  env->GetPointData()->SetScalars(rgb);
  return env;
}
}

TEST(GlassAgainstReference, BallInFrontOfEnvironment)
{
  const int dims[3] = { 2, 2, 2 };
  const double spacing[3] = { 0.1, 0.1, 0.1 }, origin[3] = { 3, 3, 3 };
  auto medium = Homogeneous(dims, spacing, origin, Voxel());
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(0.5);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  sphere->Update();
  vtkNew<vtkRefractaSurfaceMaterial> glass;
  glass->SetKindToDielectric();
  glass->SetIndexInside(1.5);
  glass->SetIndexOutside(1.0);
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(sphere->GetOutput(), glass);
  auto env = SmoothEnvironment();
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.3, 0.2, 3.0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(24);
  const int n = 40;

  vtkNew<vtkReferenceRenderer> reference;
  reference->SetInputData(medium);
  reference->SetCamera(camera);
  reference->SetSurfaces(set);
  reference->SetEnvironmentMap(env);
  reference->SetImageSize(n, n);
  reference->SetSamplesPerPixel(64);
  reference->SetPixelJitter(false);
  reference->SetSeed(7);
  reference->Update();
  vtkDataArray* hdr = reference->GetOutput()->GetPointData()->GetArray("HDR");
  vtkDataArray* se = reference->GetOutput()->GetPointData()->GetArray("StandardError");
  ASSERT_NE(hdr, nullptr);
  ASSERT_NE(se, nullptr);

  vtkNew<vtkRefractaViewPass> pass;
  ASSERT_TRUE(pass->SetMedium(medium));
  pass->SetSurfaces(set);
  pass->SetEnvironmentMap(env);
  pass->SetDielectricSplitDepth(8);
  pass->SetDielectricSupersampling(1); // pixel centres, as the reference without pixel jitter
  std::vector<float> view;
  ASSERT_TRUE(pass->Render(camera, n, n, nullptr, nullptr, view));

  int outliers = 0, glassPixels = 0;
  for (int c = 0; c < 3; ++c)
  {
    double diff = 0, var = 0, diffOutside = 0;
    for (vtkIdType p = 0; p < n * n; ++p)
    {
      const double l = hdr->GetComponent(p, c), s = se->GetComponent(p, c), e = view[4 * p + c];
      ASSERT_TRUE(std::isfinite(e));
      diff += l - e;
      diffOutside += s > 0 ? 0 : l - e;
      var += s * s;
      outliers += std::abs(l - e) > 5 * s + 2e-3 ? 1 : 0;
      glassPixels += (c == 0 && s > 0) ? 1 : 0; // noise only where a path met glass
    }
    std::printf("channel %d: summed difference %.3g (%.3g where no path met glass), pooled "
                "standard error %.3g\n",
      c, diff, diffOutside, std::sqrt(var));
    // Allowance: 1e-3 per glass pixel (0.2% of its radiance) for the float arithmetic of the view
    // pass; measured: the reference is brighter by 3e-4 .. 8e-4 per glass pixel (1.2 .. 3.7
    // standard errors), a small bias not yet explained (Physics.md).
    EXPECT_LT(std::abs(diff), 4 * std::sqrt(var) + 1e-3 * glassPixels) << "channel " << c;
  }
  std::printf("%d pixels see the glass; %d of %d pixel channels differ by > 5 SE + 2e-3\n",
    glassPixels, outliers, 3 * n * n);
  EXPECT_GT(glassPixels, n * n / 4) << "the ball fills a good part of the image";
  EXPECT_LT(outliers, 3 * n * n / 100);
}
