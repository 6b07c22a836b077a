// BenchmarkGlassEdges: what vtkRefractaViewPass::DielectricSupersampling costs and what it fixes
// at the edges of glass (issue 20: "no rim speckle"), on refracta-render's default scene (the
// glass ball in fog over the floor), in one run.
//
// The ground truth is each pixel's mean over its footprint: the same scene and lighting volume
// rendered at R x the image size with one ray per pixel (DielectricSupersampling 1), box-filtered
// back by R x R. The photon pass runs once (the lighting volume does not depend on the image). Each
// setting n renders the image at its size with DielectricSupersampling n; the runs of one setting
// give the view pass's median time.
//
// Measured per band of the pixels' centre rays, by rho = the ray's closest approach to the ball's
// centre over its radius: inside (rho < 0.85), the rim (0.85 to 1, the grazing hits), the
// silhouette (1 to 1.1: pixels the ball's edge crosses) and the rest of the image:
// - error: the mean |luminance - truth| over the band's mean truth (a mean of absolute values: the
//   caustic's few pixels, hundreds of times brighter than the rest, would rule an RMS);
// - speckle: the mean |discrete Laplacian| of the luminance over its mean, for the render and the
//   truth (a smooth image has a small one; aliasing raises it).
//
// Usage: BenchmarkGlassEdges [--quick] [--samples LIST] [--reference R] [--runs N]
// [--grazing-cosine C]
// --quick: 128 x 128, 2^16 photons, R = 4 (about a minute); default 256 x 256, 2^18 photons,
// R = 8. --samples: the settings n (default 1,2,3,4). --runs: view-pass runs per setting
// (default 3). The truth's rays must not coincide with a setting's: R = 8 shares none with
// n = 2, 3 or 4 (R = 4 holds all of n = 4's rays, so --quick's n = 4 row is not a measurement).
// --grazing-cosine: vtkRefractaViewPass::DielectricGrazingCosine (default 0.5; 1: every pixel of
// glass).

#include "RefractaBenchmark.h"
#include "RefractaScene.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaViewPass.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace
{
using refracta::bench::Median;
using refracta::bench::ParseIntList;
using RefractaRender::json;

// The default scene's ball (medium.meshes[0] of RefractaRender::DefaultSceneJson).
struct Ball
{
  double Centre[3];
  double Radius;
};

struct Settings
{
  int Size = 256;
  int Photons = 1 << 18;
  int Reference = 8;
  int Runs = 3;
  double GrazingCosine = 0.5;
  std::vector<int> Samples = { 1, 2, 3, 4 };
};

// The band of each pixel by its centre ray (camera as the view pass builds it: perspective,
// square image, row 0 at the bottom): 0 inside, 1 rim, 2 silhouette, 3 the rest.
enum Band
{
  Inside,
  Rim,
  Silhouette,
  Rest,
  NumberOfBands
};
const char* const BandNames[NumberOfBands] = { "inside (rho < 0.85)", "rim (0.85-1)",
  "silhouette (1-1.1)", "rest of the image" };

std::vector<int> PixelBands(vtkCamera* camera, vtkImageData* medium, int size, const Ball& ball)
{
  // The view pass's own rays (grid-local frame), so the bands follow the pixels it renders.
  vtkRefractaViewPass::RayFrame f;
  std::vector<int> bands(static_cast<size_t>(size) * size, Rest);
  if (!vtkRefractaViewPass::ComputeRayFrame(camera, medium, nullptr, size, size, f))
  {
    return bands;
  }
  double centre[3];
  for (int r = 0; r < 3; ++r)
  {
    centre[r] = f.WorldToLocal[r][0] * ball.Centre[0] + f.WorldToLocal[r][1] * ball.Centre[1] +
      f.WorldToLocal[r][2] * ball.Centre[2] + f.WorldToLocal[r][3];
  }
  for (int j = 0; j < size; ++j)
  {
    for (int i = 0; i < size; ++i)
    {
      const double sx = 2.0 * (i + 0.5) / size - 1.0, sy = 2.0 * (j + 0.5) / size - 1.0;
      double d[3], toCentre[3];
      for (int c = 0; c < 3; ++c)
      {
        d[c] = f.W[c] + sx * f.U[c] + sy * f.V[c];
        toCentre[c] = centre[c] - f.Eye[c];
      }
      vtkMath::Normalize(d);
      const double along = vtkMath::Dot(toCentre, d);
      const double rho =
        std::sqrt(std::max(vtkMath::Dot(toCentre, toCentre) - along * along, 0.0)) / ball.Radius;
      bands[i + static_cast<size_t>(size) * j] = rho < 0.85 ? Inside
        : rho < 1.0                                         ? Rim
        : rho < 1.1                                         ? Silhouette
                                                            : Rest;
    }
  }
  return bands;
}

// The renderer's HDR luminance (mean of RGB), size x size.
std::vector<double> Luminance(vtkRefractaImageRenderer* renderer)
{
  vtkDataArray* hdr = renderer->GetOutput()->GetPointData()->GetArray("HDR");
  std::vector<double> out(hdr ? hdr->GetNumberOfTuples() : 0);
  for (size_t p = 0; p < out.size(); ++p)
  {
    const double* t = hdr->GetTuple4(static_cast<vtkIdType>(p));
    out[p] = (t[0] + t[1] + t[2]) / 3.0;
  }
  return out;
}

// Box filter of a (size R) x (size R) image by R x R.
std::vector<double> Downsample(const std::vector<double>& fine, int size, int r)
{
  std::vector<double> out(static_cast<size_t>(size) * size, 0.0);
  const int fineSize = size * r;
  for (int j = 0; j < fineSize; ++j)
  {
    for (int i = 0; i < fineSize; ++i)
    {
      out[i / r + static_cast<size_t>(size) * (j / r)] +=
        fine[i + static_cast<size_t>(fineSize) * j] / (r * r);
    }
  }
  return out;
}

struct BandFigures
{
  double Error = 0.0;
  double Speckle = 0.0;
  int Pixels = 0;
};

// Error against the truth and speckle per band (pixels on the image border have no Laplacian).
std::vector<BandFigures> Measure(const std::vector<double>& image, const std::vector<double>& truth,
  const std::vector<int>& bands, int size)
{
  std::vector<double> absolute(NumberOfBands), mean(NumberOfBands), lap(NumberOfBands),
    own(NumberOfBands);
  std::vector<BandFigures> out(NumberOfBands);
  for (int j = 1; j + 1 < size; ++j)
  {
    for (int i = 1; i + 1 < size; ++i)
    {
      const size_t p = i + static_cast<size_t>(size) * j;
      const int b = bands[p];
      absolute[b] += std::abs(image[p] - truth[p]);
      mean[b] += truth[p];
      own[b] += image[p];
      lap[b] +=
        std::abs(image[p - 1] + image[p + 1] + image[p - size] + image[p + size] - 4.0 * image[p]);
      ++out[b].Pixels;
    }
  }
  for (int b = 0; b < NumberOfBands; ++b)
  {
    out[b].Error = absolute[b] / std::max(mean[b], 1e-30);
    out[b].Speckle = lap[b] / std::max(own[b], 1e-30);
  }
  return out;
}

bool ParseArguments(int argc, char* argv[], Settings& s)
{
  for (int a = 1; a < argc; ++a)
  {
    const bool more = a + 1 < argc;
    if (!std::strcmp(argv[a], "--quick"))
    {
      s.Size = 128;
      s.Photons = 1 << 16;
      s.Reference = 4;
    }
    else if (!std::strcmp(argv[a], "--samples") && more)
    {
      s.Samples = ParseIntList(argv[++a]);
    }
    else if (!std::strcmp(argv[a], "--reference") && more)
    {
      s.Reference = std::atoi(argv[++a]);
    }
    else if (!std::strcmp(argv[a], "--runs") && more)
    {
      s.Runs = std::atoi(argv[++a]);
    }
    else if (!std::strcmp(argv[a], "--grazing-cosine") && more)
    {
      s.GrazingCosine = std::atof(argv[++a]);
    }
    else
    {
      std::fprintf(stderr,
        "usage: BenchmarkGlassEdges [--quick] [--samples LIST] [--reference R] [--runs N] "
        "[--grazing-cosine C]\n");
      return false;
    }
  }
  const bool samplesValid = !s.Samples.empty() &&
    std::all_of(s.Samples.begin(), s.Samples.end(), [](int n) { return n >= 1 && n <= 8; });
  if (!samplesValid || s.Reference < 2 || s.Reference > 16 || s.Runs < 1 ||
    !(s.GrazingCosine >= 0.0 && s.GrazingCosine <= 1.0))
  {
    std::fprintf(stderr,
      "BenchmarkGlassEdges: --samples takes 1..8, --reference 2..16, --runs "
      ">= 1, --grazing-cosine 0..1\n");
    return false;
  }
  return true;
}

// Renders the current settings at size x size with DielectricSupersampling n.
void RenderView(vtkRefractaImageRenderer* renderer, int size, int n)
{
  renderer->SetImageSize(size, size);
  renderer->GetViewPass()->SetDielectricSupersampling(n);
  renderer->Modified();
  renderer->Update();
}
}

int main(int argc, char* argv[])
{
  Settings s;
  if (!ParseArguments(argc, argv, s))
  {
    return 2;
  }
  json scene = json::parse(RefractaRender::DefaultSceneJson);
  scene["image"]["width"] = scene["image"]["height"] = s.Size;
  scene["quality"]["photons"] = s.Photons;
  vtkNew<vtkRefractaImageRenderer> renderer;
  const RefractaRender::Scene read = RefractaRender::ReadScene(scene, ".", renderer, true);
  vtkRefractaViewPass* view = renderer->GetViewPass();
  view->SetDielectricGrazingCosine(s.GrazingCosine);

  // The lighting (once), then the truth: R x the size, one ray per pixel.
  RenderView(renderer, s.Size, 1);
  RenderView(renderer, s.Size * s.Reference, 1);
  const double truthSeconds = view->GetLastSeconds();
  const std::vector<double> truth = Downsample(Luminance(renderer), s.Size, s.Reference);
  if (truth.empty())
  {
    std::fprintf(stderr, "BenchmarkGlassEdges: the reference render failed\n");
    return 1;
  }
  const json& sphere = scene["medium"]["meshes"][0]["sphere"];
  Ball ball;
  for (int c = 0; c < 3; ++c)
  {
    ball.Centre[c] = sphere["center"][c].get<double>();
  }
  ball.Radius = sphere["radius"].get<double>();
  const std::vector<int> bands = PixelBands(read.Camera, read.Medium.Image, s.Size, ball);
  const std::vector<BandFigures> truthFigures = Measure(truth, truth, bands, s.Size);

  std::printf("Glass edges on the default scene, %d x %d, %d photons, grazing cosine %g. Truth: "
              "each pixel's footprint mean, %d x %d rays per pixel (%d x %d image, %.2f s of view "
              "pass).\n\n",
    s.Size, s.Size, s.Photons, s.GrazingCosine, s.Reference, s.Reference, s.Size * s.Reference,
    s.Size * s.Reference, truthSeconds);
  std::printf("| n | supersampled pixels | view pass (median of %d) | time / n = 1 |", s.Runs);
  for (int b = 0; b < NumberOfBands; ++b)
  {
    std::printf(" error %s |", BandNames[b]);
  }
  std::printf(" speckle inside / truth's | speckle rim / truth's | speckle silhouette / truth's "
              "|\n|---|---|---|---|");
  for (int b = 0; b < NumberOfBands + 3; ++b)
  {
    std::printf("---|");
  }
  std::printf("\n");
  double baseSeconds = 0.0;
  for (int n : s.Samples)
  {
    std::vector<double> seconds;
    std::vector<double> image;
    for (int r = 0; r < s.Runs; ++r)
    {
      RenderView(renderer, s.Size, n);
      seconds.push_back(view->GetLastSeconds());
      image = Luminance(renderer);
    }
    const double median = Median(seconds);
    if (baseSeconds == 0.0)
    {
      baseSeconds = median;
    }
    const std::vector<BandFigures> f = Measure(image, truth, bands, s.Size);
    std::printf("| %d | %lld | %.3f s | %.2f |", n,
      static_cast<long long>(view->GetLastNumberOfSupersampledPixels()), median,
      median / baseSeconds);
    for (int b = 0; b < NumberOfBands; ++b)
    {
      std::printf(" %.2f%% |", 100.0 * f[b].Error);
    }
    std::printf(" %.3f / %.3f | %.3f / %.3f | %.3f / %.3f |\n", f[Inside].Speckle,
      truthFigures[Inside].Speckle, f[Rim].Speckle, truthFigures[Rim].Speckle,
      f[Silhouette].Speckle, truthFigures[Silhouette].Speckle);
  }
  std::printf("\nPixels per band:");
  for (int b = 0; b < NumberOfBands; ++b)
  {
    std::printf(" %s %d;", BandNames[b], truthFigures[b].Pixels);
  }
  std::printf("\n");
  return 0;
}
