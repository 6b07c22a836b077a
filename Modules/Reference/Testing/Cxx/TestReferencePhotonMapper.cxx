// The reference photon mapper (stochastic progressive photon mapping in the medium) against the
// unbiased path tracer where the latter converges, against analytic answers (emission, the
// ball-lens focus, the bending of a ray in a linear index gradient), its error against the number
// of passes, its error estimate, determinism and bad input.
#include "ReferenceTestUtilities.h"

#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkReferencePhotonMapper.h"
#include "vtkSMPTools.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
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

// Where view rays gather: at every tentative collision with ratio-tracking weights (the default,
// GatherSpacing 2) or at the first real collision (0). Both estimate, pass by pass, the same
// kernel-blurred in-scattered light, so with the same photons their images must agree within
// their noise (the difference over its expected size from the two stream estimates); and summing
// along the whole ray must leave less noise after the same passes: at least 2x less variance in
// this dense cube (3.2x measured; the gain in efficiency, time included, is 2.5x here and 4-14x
// on the accuracy benchmark's thinner scenes, measured by BenchmarkReferencePhotonMapper:
// Documentation/Benchmarks.md). A gather that ignored the collision's probability of being real,
// or weights that did not fall with the ratio-tracked transmittance, would fail the first.
TEST(ReferencePhotonMapper, GatheringAlongTheRayAgreesWithOneGatherAndIsLessNoisy)
{
  CubeScene scene;
  const int size = 8;
  auto render = [&](double spacing)
  {
    vtkNew<vtkReferencePhotonMapper> pm;
    scene.SetUp(pm, size);
    pm->SetPasses(32);
    pm->SetPhotonsPerPass(4000);
    pm->SetSamplesPerPixel(4);
    pm->SetGatherSpacing(spacing);
    return Render(pm);
  };
  auto first = render(0.0);
  auto along = render(1.0);
  double d2 = 0, var = 0;
  for (int p = 0; p < size * size; ++p)
  {
    const double d = Hdr(along, p) - Hdr(first, p);
    d2 += d * d;
    var += Se(along, p) * Se(along, p) + Se(first, p) * Se(first, p);
  }
  auto noise = [](vtkImageData* out)
  {
    vtkDataArray* e = out->GetFieldData()->GetArray("CheckpointError");
    return e->GetComponent(e->GetNumberOfTuples() - 1, 0); // at the end
  };
  const double varianceRatio = std::pow(noise(first) / noise(along), 2);
  std::printf("gathering along the ray: difference / its noise %.3f; noise %.4f against %.4f at "
              "one gather per path (variance / %.2f) in %.2f s against %.2f s\n",
    std::sqrt(d2 / var), noise(along), noise(first), varianceRatio,
    FieldValue(along, "RenderSeconds"), FieldValue(first, "RenderSeconds"));
  vtkNew<vtkReferencePhotonMapper> defaults;
  EXPECT_EQ(defaults->GetGatherSpacing(), 2.0);
  EXPECT_EQ(FieldValue(along, "GatherSpacing"), 1.0);
  EXPECT_LT(std::sqrt(d2 / var), 2.0);
  EXPECT_GT(varianceRatio, 2.0);
}

namespace
{
// Least-squares slope of log(y) against log(x).
double LogLogSlope(const std::vector<double>& x, const std::vector<double>& y)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (size_t i = 0; i < x.size(); ++i)
  {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}
} // namespace

// The error falls with the number of passes N as the theory says. With r_i^3 ~ i^(Alpha - 1) the
// variance of a point estimate of pass i grows like 1 / r_i^3 ~ i^(1 - Alpha), so the mean of N
// passes has variance ~ N^-Alpha: noise slope -Alpha / 2 = -1/3 in log-log. A pixel averages its
// view points along the ray (64 a pass here), which smooths the kernel into a beam (variance ~
// 1 / r_i^2, slope -(1 + 2 Alpha) / 6 = -0.39), and noise that does not depend on the radius
// (the view paths' own) falls with slope -1/2; so the stream spread (noise alone) must fall with
// a slope in [-0.5, -0.3]. The error against the converged path tracer (its variance taken out)
// adds the kernel's bias, falling like N^(-2 (1 - Alpha) / 3) = N^(-2/9): its slope must lie in
// [-0.6, -0.15] and the error must fall by at least 2x from 2 to 64 passes.
TEST(ReferencePhotonMapper, ErrorFallsWithPassesAtTheTheoreticalRate)
{
  CubeScene scene;
  const int size = 6;
  vtkNew<vtkReferenceRenderer> pt;
  scene.SetUp(pt, size);
  pt->SetSamplesPerPixel(Spp(4096));
  auto truth = Render(pt);
  std::vector<double> passes, errors;
  vtkSmartPointer<vtkImageData> last;
  for (int n : { 2, 8, 32, 64 })
  {
    vtkNew<vtkReferencePhotonMapper> pm;
    scene.SetUp(pm, size);
    pm->SetPasses(n);
    // Few photons and many view rays a pass: the kernel's counting noise (variance ~ 1 / r^3,
    // the part the schedule trades against bias) dominates the view paths' own noise (variance
    // independent of r, which alone would fall with slope -1/2).
    pm->SetPhotonsPerPass(250);
    pm->SetSamplesPerPixel(32);
    pm->SetStreams(4);
    pm->SetInitialRadius(2.0);
    auto out = Render(pm);
    double d2 = 0, var = 0, norm = 0;
    for (int p = 0; p < size * size; ++p)
    {
      d2 += (Hdr(out, p) - Hdr(truth, p)) * (Hdr(out, p) - Hdr(truth, p));
      var += Se(truth, p) * Se(truth, p);
      norm += Hdr(truth, p) * Hdr(truth, p);
    }
    passes.push_back(n);
    errors.push_back(std::sqrt(std::max(d2 - var, 1e-30) / norm));
    std::printf("%2d passes: relative RMSE against the path tracer %.4f\n", n, errors.back());
    last = out;
  }
  const double total = LogLogSlope(passes, errors);
  vtkDataArray* cp = last->GetFieldData()->GetArray("CheckpointPasses");
  vtkDataArray* ce = last->GetFieldData()->GetArray("CheckpointError");
  ASSERT_NE(cp, nullptr);
  ASSERT_NE(ce, nullptr);
  std::vector<double> cpasses, cerrors;
  for (vtkIdType i = 0; i < cp->GetNumberOfTuples(); ++i)
  {
    cpasses.push_back(cp->GetComponent(i, 0));
    cerrors.push_back(ce->GetComponent(i, 0));
    std::printf(
      "checkpoint %3.0f passes: stream spread (relative) %.4f\n", cpasses.back(), cerrors.back());
  }
  ASSERT_GE(cpasses.size(), 4u);
  const double noise = LogLogSlope(cpasses, cerrors);
  std::printf("log-log slopes: noise (stream spread) %.3f (theory: -Alpha/2 = -0.333 for a point, "
              "-0.39 for a beam, -0.5 for radius-free noise); error vs the path tracer %.3f\n",
    noise, total);
  EXPECT_GE(noise, -0.5);
  EXPECT_LE(noise, -0.3);
  EXPECT_GE(total, -0.6);
  EXPECT_LE(total, -0.15);
  EXPECT_GT(errors.front() / errors.back(), 2.0);
}

// Emission is collected along the view ray exactly as by the path tracer: a uniform absorbing
// (albedo 0), emitting slab of optical depth 1.5 seen face on shows eps / sigma (1 - e^-tau).
// Every pixel must match within 4 standard errors of the stream estimate, and the normalised
// squared deviations must average to about 1 (the error estimate is neither too small nor far
// too large; the medium is grey, so the three channels of a pixel share their paths and only the
// 16 pixels are independent).
TEST(ReferencePhotonMapper, EmittingSlabMatchesTheAnalyticRadiance)
{
  const int dims[3] = { 4, 4, 8 };
  // The box reaches half a voxel beyond the end points: 8 x 1/8 = 1 thick.
  const double spacing[3] = { 1.0 / 4, 1.0 / 4, 1.0 / 8 }, origin[3] = { 0, 0, 0 };
  Voxel v;
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = 1.5;
    v.Emission[c] = 0.6 + 0.2 * c;
  }
  auto medium = Homogeneous(dims, spacing, origin, v);
  const double focal[3] = { 0.5, 0.5, 0.5 }, dop[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
  vtkNew<vtkReferencePhotonMapper> pm;
  pm->SetInputData(medium);
  pm->SetCamera(ParallelCamera(focal, dop, up, 0.4));
  pm->SetImageSize(4, 4);
  pm->SetPasses(256);
  pm->SetPhotonsPerPass(1);
  pm->SetStreams(16);
  auto out = Render(pm);
  double chi2 = 0, zsum = 0;
  int n = 0;
  for (int p = 0; p < 16; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double expected = v.Emission[c] / 1.5 * (1 - std::exp(-1.5));
      const double z = (Hdr(out, p, c) - expected) / Se(out, p, c);
      EXPECT_LT(std::abs(z), 4.0) << "pixel " << p << " channel " << c;
      chi2 += z * z;
      zsum += z;
      ++n;
    }
  }
  std::printf("emitting slab: mean squared normalised deviation %.2f, mean %.2f, over %d values\n",
    chi2 / n, zsum / n, n);
  EXPECT_GT(chi2 / n, 0.3);
  EXPECT_LT(chi2 / n, 3.0);
}

// Same seed, same image, whatever the number of threads; another seed, another image.
TEST(ReferencePhotonMapper, DeterministicForASeed)
{
  CubeScene scene;
  auto render = [&](unsigned int seed)
  {
    vtkNew<vtkReferencePhotonMapper> pm;
    scene.SetUp(pm, 6);
    pm->SetPasses(3);
    pm->SetPhotonsPerPass(9000); // more than two blocks of photons
    pm->SetSeed(seed);
    return Render(pm);
  };
  vtkSMPTools::Initialize(1);
  auto a = render(5);
  vtkSMPTools::Initialize(2);
  auto b = render(5);
  auto c = render(6);
  int same = 0, differ = 0;
  for (int p = 0; p < 36; ++p)
  {
    same += Hdr(a, p) == Hdr(b, p) ? 1 : 0;
    differ += Hdr(a, p) != Hdr(c, p) ? 1 : 0;
  }
  EXPECT_EQ(same, 36);
  EXPECT_GT(differ, 30);
  EXPECT_EQ(FieldValue(a, "StoredPhotons"), FieldValue(b, "StoredPhotons"));
}

// Settings out of range: a clear error and an empty output.
TEST(ReferencePhotonMapper, BadSettingsGiveClearErrorsAndEmptyOutput)
{
  CubeScene scene;
  auto run = [&](const std::function<void(vtkReferencePhotonMapper*)>& set, const char* expect)
  {
    vtkNew<vtkReferencePhotonMapper> pm;
    scene.SetUp(pm, 4);
    pm->SetPasses(1);
    pm->SetPhotonsPerPass(100);
    set(pm);
    vtkNew<vtkTest::ErrorObserver> obs, execObs;
    pm->AddObserver(vtkCommand::ErrorEvent, obs);
    pm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, execObs);
    pm->Update();
    EXPECT_TRUE(obs->GetError()) << expect;
    EXPECT_NE(obs->GetErrorMessage().find(expect), std::string::npos)
      << "message: " << obs->GetErrorMessage();
    EXPECT_EQ(pm->GetOutput()->GetNumberOfPoints(), 0);
  };
  run([](vtkReferencePhotonMapper* pm) { pm->SetAlpha(0.4); }, "Alpha is 0.4");
  run([](vtkReferencePhotonMapper* pm) { pm->SetAlpha(1.0); }, "[0.5, 1)");
  run([](vtkReferencePhotonMapper* pm) { pm->SetAlpha(std::nan("")); }, "Alpha");
  run([](vtkReferencePhotonMapper* pm) { pm->SetPasses(0); }, "Passes is 0");
  run([](vtkReferencePhotonMapper* pm) { pm->SetPhotonsPerPass(-3); }, "PhotonsPerPass is -3");
  run([](vtkReferencePhotonMapper* pm) { pm->SetStreams(0); }, "Streams is 0");
  run([](vtkReferencePhotonMapper* pm) { pm->SetInitialRadius(0); }, "InitialRadius is 0");
  run([](vtkReferencePhotonMapper* pm) { pm->SetInitialRadius(-1); }, "InitialRadius is -1");
  run([](vtkReferencePhotonMapper* pm) { pm->SetGatherSpacing(-0.5); }, "GatherSpacing is -0.5");
  run([](vtkReferencePhotonMapper* pm) { pm->SetGatherSpacing(std::nan("")); }, "GatherSpacing");
  run([](vtkReferencePhotonMapper* pm) { pm->SetCamera(nullptr); }, "SetCamera");
  // The radius schedule itself.
  EXPECT_DOUBLE_EQ(vtkReferencePhotonMapper::PassRadius(2.0, 0.75, 1), 2.0);
  EXPECT_NEAR(std::pow(vtkReferencePhotonMapper::PassRadius(2.0, 0.75, 3), 3),
    8.0 * (1.75 / 2) * (2.75 / 3), 1e-12);
}

namespace
{
constexpr int LensNx = 80, LensN = 41;
constexpr double LensR = 10, LensC = 20, LensCx = 20, LensIndex = 1.5;

// The photon tracer's ball lens (Modules/Transport/Testing/Cxx/TestPhotonOptics.cxx): n = 1.5,
// radius 10 voxels, tanh boundary 0.7 voxel wide, behind an absorbing screen with a hole of
// radius 0.4 R on the axis, in fog (sigma_t = 0.01 per voxel here, for photons to find).
vtkSmartPointer<vtkImageData> BallLens()
{
  const int dims[3] = { LensNx, LensN, LensN };
  const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  return MakeMedium(dims, spacing, origin,
    [](int i, int j, int k, Voxel& v)
    {
      const double x = i, y = j, z = k;
      const double r = std::sqrt(
        (x - LensCx) * (x - LensCx) + (y - LensC) * (y - LensC) + (z - LensC) * (z - LensC));
      // Exactly 1 beyond R + 5 (where the tanh tail is below 2e-7): blocks there are crossed in
      // one straight move instead of integrator steps as short as the screen's free paths.
      v.N = r > LensR + 5 ? 1.0 : 1 + 0.5 * (LensIndex - 1) * (1 - std::tanh((r - LensR) / 0.7));
      const double rho = std::sqrt((y - LensC) * (y - LensC) + (z - LensC) * (z - LensC));
      const bool screen = x < 0.5 && rho > 0.4 * LensR;
      for (int c = 0; c < 3; ++c)
      {
        v.Sigma[c] = screen ? 100 : 0.01; // the half-voxel screen: optical depth 50
        v.Albedo[c] = x < 0.5 ? 0.0 : 1.0;
      }
    });
}

// Exact axis crossing (from the centre) of a ray at height h through a sharp ball lens.
double CrossingFromCentre(double h)
{
  const double n = LensIndex, R = LensR;
  const double t1 = std::asin(h / R), t2 = std::asin(std::sin(t1) / n);
  const double deviation = 2 * (t1 - t2);
  const double phi = (Pi - t1) - (Pi - 2 * t2);
  const double ex = R * std::cos(phi), ey = R * std::sin(phi);
  return ex + ey / std::tan(deviation);
}
} // namespace

// A parallel beam through the ball lens, seen from the side (parallel camera along -z, one pixel
// a voxel, the middle row on the axis): the light scattered by the fog out of the axis row peaks
// where the beam is narrowest. As in the photon tracer's test, the focus estimated from that row
// (the radiance-weighted mean position of the columns above half the peak, behind the lens) must
// lie between the marginal crossing CrossingFromCentre(0.4 R) = 14.3 and the paraxial focus
// f = n R / (2 (n - 1)) = 15, widened; and the caustic must be much brighter than
// the beam just behind the aperture (4.7 x here). The image integrates along z, which adds the
// bright caustic envelope the marginal rays form before their focus to the axial light, so the
// lower bound is the marginal crossing minus 1.5 voxels here (measured: 15.15 gathering along the
// view rays; 13.4 and 5.7 x with one gather per view path, whose image in this thin fog is far
// noisier after the test's 8 passes). The unbiased path tracer cannot render this
// (its connections from the fog to the light's 0.5 degree disc almost never pass the lens).
TEST(ReferencePhotonMapper, BallLensFocusesNearTheParaxialFocus)
{
  vtkNew<vtkReferencePhotonMapper> pm;
  pm->SetInputData(BallLens());
  const double focal[3] = { 39.5, LensC, LensC }, dop[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
  pm->SetCamera(ParallelCamera(focal, dop, up, 4.5));
  const double towards[3] = { -1, 0, 0 };
  pm->AddLight(Directional(towards, 1.0));
  // A nearly parallel beam: photons of a 0.5 degree disc would drift into the box's side faces
  // past the screen.
  pm->SetDirectionalLightAngularRadius(1e-3);
  pm->SetImageSize(LensNx, 9);
  pm->SetPasses(8);
  pm->SetPhotonsPerPass(100000);
  pm->SetSamplesPerPixel(16);
  pm->SetInitialRadius(1.0);
  auto out = Render(pm);
  std::vector<double> profile(LensNx);
  for (int i = 0; i < LensNx; ++i)
  {
    profile[i] = Hdr(out, i + LensNx * 4);
  }
  const int first = static_cast<int>(LensCx + LensR + 1);
  const double peak = *std::max_element(profile.begin() + first, profile.end());
  double w = 0, wx = 0;
  for (int i = first; i < LensNx; ++i)
  {
    if (profile[i] > 0.5 * peak)
    {
      w += profile[i];
      wx += profile[i] * i;
    }
  }
  const double focus = wx / w - LensCx;
  const double f = LensIndex * LensR / (2 * (LensIndex - 1));
  const double marginal = CrossingFromCentre(0.4 * LensR);
  const double aperture = (profile[4] + profile[5] + profile[6]) / 3;
  std::printf("ball lens: focus at %.2f from the centre; paraxial f %.2f, marginal (h = 0.4 R) "
              "%.2f; caustic / beam at the aperture %.1f; %.1f s\n",
    focus, f, marginal, peak / aperture, FieldValue(out, "RenderSeconds"));
  EXPECT_EQ(FieldValue(out, "TruncatedPaths"), 0);
  EXPECT_GE(focus, marginal - 1.5);
  EXPECT_LE(focus, f + 1.0);
  EXPECT_GT(peak, 4 * aperture);
}

// n = n0 + a y bends a horizontal ray along the catenary n(y) = n(y0) cosh(a (x - xe) / n(y0))
// (the photon tracer's linear-gradient test, 8 voxels deep here): a beam through a 3-voxel slit
// in an absorbing screen, in fog, seen from the side. The radiance-weighted centroid of the image
// in y, averaged over bands of 6 columns, must follow the curve within 0.3 voxel (3% of the
// 9-voxel deflection), and the exit angle
// from a straight-line fit to the centroids of the last 16 columns must match
// atan(sinh(a X / n(y0))) within 10% (the fit's noise).
TEST(ReferencePhotonMapper, LinearGradientBendsAlongTheCatenary)
{
  const int nx = 64, ny = 40, nz = 8, j0 = 13;
  const double s = 1.0 / 64, a = 0.3, n0 = 1.0;
  const int dims[3] = { nx, ny, nz };
  const double spacing[3] = { s, s, s }, origin[3] = { 0, 0, 0 };
  auto medium = MakeMedium(dims, spacing, origin,
    [&](int i, int j, int, Voxel& v)
    {
      v.N = n0 + a * j * s;
      const bool screen = i == 0 && std::abs(j - j0) > 1;
      for (int c = 0; c < 3; ++c)
      {
        v.Sigma[c] = screen ? 1000 : 2.0;
        v.Albedo[c] = i == 0 ? 0.0 : 1.0;
      }
    });
  vtkNew<vtkReferencePhotonMapper> pm;
  pm->SetInputData(medium);
  const double focal[3] = { (nx - 1) * s / 2, (ny - 1) * s / 2, (nz - 1) * s / 2 },
               dop[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
  pm->SetCamera(ParallelCamera(focal, dop, up, ny * s / 2));
  const double towards[3] = { -1, 0, 0 };
  pm->AddLight(Directional(towards, 1.0));
  // A nearly parallel beam: photons of a 0.5 degree disc would drift into the 2-voxel-thick
  // box's z faces past the screen and light the whole fog.
  pm->SetDirectionalLightAngularRadius(1e-3);
  pm->SetImageSize(nx, ny);
  pm->SetPasses(8);
  pm->SetPhotonsPerPass(200000);
  pm->SetSamplesPerPixel(32);
  pm->SetInitialRadius(1.0);
  pm->SetMaximumScatteringDepth(1); // the beam itself, not the glow around it
  auto out = Render(pm);
  const double y0 = j0 * s, n1 = n0 + a * y0, xe = -0.5 * s;
  auto curve = [&](double x) { return y0 + n1 / a * (std::cosh(a * (x - xe) / n1) - 1); };
  std::vector<double> xs, ys;
  double band = 0;
  for (int i = 4; i < nx; ++i)
  {
    double w = 0, wy = 0;
    for (int j = 0; j < ny; ++j)
    {
      const double r = Hdr(out, i + nx * j);
      w += r;
      wy += r * j * s;
    }
    ASSERT_GT(w, 0) << "column " << i;
    // Bands of 6 columns (the mean of their centroids against the mean of the curve there).
    band += (wy / w - curve(i * s)) / 6;
    if (i % 6 == 3)
    {
      EXPECT_NEAR(band, 0.0, 0.3 * s) << "columns " << i - 5 << " to " << i;
      std::printf("columns %d-%d: centroid %.3f voxels from the curve\n", i - 5, i, band / s);
      band = 0;
    }
    if (i >= nx - 16)
    {
      xs.push_back(i * s);
      ys.push_back(wy / w);
    }
  }
  // Least-squares slope of the last 16 centroids.
  double mx = 0, my = 0;
  for (size_t q = 0; q < xs.size(); ++q)
  {
    mx += xs[q] / xs.size();
    my += ys[q] / xs.size();
  }
  double sxy = 0, sxx = 0;
  for (size_t q = 0; q < xs.size(); ++q)
  {
    sxy += (xs[q] - mx) * (ys[q] - my);
    sxx += (xs[q] - mx) * (xs[q] - mx);
  }
  const double measured = std::atan(sxy / sxx);
  const double expected = std::atan(std::sinh(a * (mx - xe) / n1));
  std::printf("GRIN: slope angle over the last 16 columns %.4f rad, analytic %.4f rad; %.1f s\n",
    measured, expected, FieldValue(out, "RenderSeconds"));
  EXPECT_NEAR(measured, expected, 0.1 * expected);
}
