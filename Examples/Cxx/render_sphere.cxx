// README's first script in C++: a glass sphere in fog, lit by a spot light, through the render
// pipeline, built against the installed package (find_package(Refracta)).
//
//   render_sphere [out.png] [voxels per axis]
//
// vtkMeshVoxelizer turns the sphere (n = 1.5) and the fog around it into a medium;
// vtkRefractaImageRenderer runs the render pipeline on it headless (effect plan, photon pass with
// caustics, multiple scattering, view rays refracted at the sphere) at the DRAFT quality preset
// and the PNG is written. Exit code 1 unless the sphere focuses the spot light: the caustic below
// it must be more than twice as bright as the lit fog beside the beam.
#include "vtkEffectPlan.h"
#include "vtkMediumMaterial.h"
#include "vtkMeshVoxelizer.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaRenderPipeline.h"

#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkSphereSource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

int main(int argc, char* argv[])
{
  const char* out = argc > 1 ? argv[1] : "render_sphere.png";
  const int n = argc > 2 ? std::atoi(argv[2]) : 64;

  vtkNew<vtkMediumMaterial> glass;
  glass->SetRefractiveIndex(1.5);
  vtkNew<vtkMediumMaterial> fog;
  fog->SetExtinction(0.35, 0.35, 0.35);
  fog->SetAlbedo(0.9, 0.9, 0.9);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(0.42);
  sphere->SetThetaResolution(64);
  sphere->SetPhiResolution(64);

  vtkNew<vtkMeshVoxelizer> medium; // meshes + materials -> a medium (vtkImageData)
  medium->AddInputConnection(sphere->GetOutputPort());
  medium->SetMaterial(0, glass);
  medium->SetSurroundingMaterial(fog);
  medium->SetDimensions(n, n, n);
  medium->SetBounds(-1, 1, -1, 1, -1, 1);

  vtkNew<vtkLight> light; // a spot light above the sphere
  light->SetPositional(true);
  light->SetConeAngle(12);
  light->SetIntensity(60);
  light->SetPosition(0, 3, 0);
  light->SetFocalPoint(0, 0, 0);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0.55, 3.2);
  camera->SetFocalPoint(0, -0.1, 0);

  const int size = 256;
  vtkNew<vtkRefractaImageRenderer> image; // the render pipeline, headless (no OpenGL)
  image->SetInputConnection(medium->GetOutputPort());
  image->AddLight(light);
  image->SetCamera(camera);
  image->SetImageSize(size, size);
  image->GetPipeline()->SetQuality(vtkEffectPlan::DRAFT); // a measured quality preset
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(image->GetOutputPort());
  writer->SetFileName(out);
  writer->Write();

  vtkDataArray* hdr = image->GetOutput()->GetPointData()->GetArray("HDR");
  if (!hdr || hdr->GetNumberOfTuples() != size * size)
  {
    std::fprintf(stderr, "no image was rendered\n");
    return 1;
  }
  std::printf("%s\n", image->GetPipeline()->GetEffectPlan()->GetSummary().c_str());

  // The focus below the sphere (column 128, rows 30-50 from the bottom) outshines the lit fog
  // beside the beam (column 60).
  auto luminance = [&](int i, int j) {
    double rgba[4];
    hdr->GetTuple(i + size * j, rgba);
    return 0.2126 * rgba[0] + 0.7152 * rgba[1] + 0.0722 * rgba[2];
  };
  double focus = 0.0, beside = 0.0;
  for (int j = 30; j < 50; ++j)
  {
    focus = std::max(focus, luminance(128, j));
    beside = std::max(beside, luminance(60, j));
  }
  std::printf("caustic %.4g, fog beside it %.4g\n", focus, beside);
  if (!(focus > 2.0 * beside))
  {
    std::fprintf(stderr, "the sphere must focus the spot light below it\n");
    return 1;
  }
  return 0;
}
