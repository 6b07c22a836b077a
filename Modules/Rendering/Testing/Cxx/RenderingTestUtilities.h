// Helpers shared by the Rendering tests: homogeneous media and lighting volumes, constant arrays,
// and image regression against Testing/Baselines/<name>.png (vtkTesting, as
// vtkRegressionTestImage does). REFRACTA_UPDATE_BASELINES=1 in the environment (re)writes the
// baselines instead of comparing.
#ifndef RenderingTestUtilities_h
#define RenderingTestUtilities_h

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkTesting.h"
#include "vtkTrivialProducer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace refracta_test
{
inline vtkSmartPointer<vtkImageData> MakeGrid(
  int nx, int ny, int nz, double spacing, const double origin[3] = nullptr)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(spacing, spacing, spacing);
  if (origin)
  {
    image->SetOrigin(origin[0], origin[1], origin[2]);
  }
  return image;
}

inline vtkFloatArray* AddConstant(
  vtkImageData* image, const char* name, int comps, double a, double b = 0, double c = 0)
{
  vtkNew<vtkFloatArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(comps);
  array->SetNumberOfTuples(image->GetNumberOfPoints());
  const double v[3] = { a, b, c };
  for (int k = 0; k < comps; ++k)
  {
    array->FillComponent(k, v[k]);
  }
  image->GetPointData()->AddArray(array);
  return array;
}

// The largest absolute value of an image, and the largest absolute difference of two of the same
// size.
inline double MaxAbs(const std::vector<float>& v)
{
  double m = 0;
  for (float x : v)
  {
    m = std::max(m, std::abs(static_cast<double>(x)));
  }
  return m;
}

inline double MaxDiff(const std::vector<float>& a, const std::vector<float>& b)
{
  double m = 0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    m = std::max(m, std::abs(static_cast<double>(a[i]) - b[i]));
  }
  return m;
}

// Per-pixel depth limits (path lengths from 0 to `longest`) scattered by a pixel hash, so that
// some rays stop before the medium, some in front of or behind an object, some inside one.
inline std::vector<float> HashedDepthLimits(int width, int height, double longest)
{
  std::vector<float> depth(static_cast<size_t>(width) * height);
  for (size_t p = 0; p < depth.size(); ++p)
  {
    depth[p] = static_cast<float>(longest * ((p * 2654435761u) % 1000) / 1000.0);
  }
  return depth;
}

inline std::string EnvOr(const char* name, const char* fallback)
{
  const char* v = std::getenv(name);
  return v ? v : fallback;
}

// Compares the RGB scalars of `image` with Testing/Baselines/<name>.png. Returns true when they
// agree within `threshold` (vtkTesting's image-difference metric, as vtkRegressionTestImage).
inline bool MatchesBaseline(vtkImageData* image, const std::string& name, double threshold = 10)
{
  const std::string baseline = EnvOr("REFRACTA_BASELINE_DIR", ".") + "/" + name + ".png";
  const std::string temp = EnvOr("REFRACTA_TEST_OUTPUT_DIR", ".");
  vtkNew<vtkImageData> rgb;
  rgb->CopyStructure(image);
  rgb->GetPointData()->SetScalars(image->GetPointData()->GetScalars());
  if (std::getenv("REFRACTA_UPDATE_BASELINES"))
  {
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputData(rgb);
    writer->SetFileName(baseline.c_str());
    writer->Write();
    std::cout << "wrote baseline " << baseline << "\n";
    return true;
  }
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(rgb);
  vtkNew<vtkTesting> testing;
  testing->AddArgument("-V");
  testing->AddArgument(baseline.c_str());
  testing->AddArgument("-T");
  testing->AddArgument(temp.c_str());
  std::ostringstream log;
  const int result = testing->RegressionTest(producer, threshold, log);
  if (result != vtkTesting::PASSED)
  {
    std::cerr << log.str() << "\n";
    return false;
  }
  // vtkTesting ignores per-pixel differences below its threshold (vtkImageDifference's default
  // 105), so also require a close match: mean absolute difference <= 1.5 / 255 per channel and
  // at most 1% of the pixels off by more than 16 / 255 in some channel.
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(baseline.c_str());
  reader->Update();
  vtkDataArray* want = reader->GetOutput()->GetPointData()->GetScalars();
  vtkDataArray* got = rgb->GetPointData()->GetScalars();
  if (!want || !got || want->GetNumberOfTuples() != got->GetNumberOfTuples() ||
    want->GetNumberOfComponents() < 3 || got->GetNumberOfComponents() < 3)
  {
    std::cerr << "baseline " << baseline << " has another size or format\n";
    return false;
  }
  double sum = 0;
  vtkIdType off = 0;
  for (vtkIdType i = 0; i < got->GetNumberOfTuples(); ++i)
  {
    double worst = 0;
    for (int c = 0; c < 3; ++c)
    {
      const double d = std::abs(got->GetComponent(i, c) - want->GetComponent(i, c));
      sum += d;
      worst = std::max(worst, d);
    }
    off += worst > 16 ? 1 : 0;
  }
  const double mean = sum / (3.0 * got->GetNumberOfTuples());
  const double fraction = static_cast<double>(off) / got->GetNumberOfTuples();
  if (mean > 1.5 || fraction > 0.01)
  {
    std::cerr << name << ": mean difference " << mean << " / 255, " << 100 * fraction
              << "% of pixels off by more than 16 / 255 (baseline " << baseline << ")\n";
    return false;
  }
  return true;
}
}

#endif
