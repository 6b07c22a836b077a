// Tests of vtkReferenceRenderer against analytic answers. Every Monte Carlo comparison uses the
// standard error the renderer reports: the pooled mean over the image must lie within 4 standard
// errors of the analytic value (a false failure rate of 6e-5 per comparison for a Gaussian mean),
// and per-pixel comparisons use the z-scores (mean z^2 close to 1).
#include "ReferenceTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkReferenceRenderer.h"
#include "vtkSMPTools.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace reftest;

namespace
{
double FieldValue(vtkImageData* img, const char* name)
{
  vtkDataArray* a = img->GetFieldData()->GetArray(name);
  return a ? a->GetComponent(0, 0) : std::nan("");
}
} // namespace

// ---------------------------------------------------------------------------------------------
// HG sampling against the HG pdf: chi-square over bins in log(1 - cos theta), expected counts by
// numerical integration of the pdf (independent of the sampler's inverse CDF); also the
// normalisation and mean cosine of the pdf, and the uniformity of the azimuth.
TEST(ReferenceRenderer, HenyeyGreensteinSamplingChiSquare)
{
  for (double g : { -0.7, 0.0, 0.3, 0.9, 0.999, -0.999 })
  {
    // Normalisation and <cos> = g by Simpson integration in cos theta (fine grid near the peak
    // handled by integrating in log(1 - cos) for the forward part).
    // q = 1 - cos theta for g >= 0 and 1 + cos theta for g < 0, so that the peak is at q = 0
    // where the logarithmic bins are finest.
    auto pdfOmc = [g](double q)
    { return 2 * Pi * vtkReferenceRenderer::HenyeyGreensteinPhase(g, g >= 0 ? 1 - q : q - 1); };
    // Integrate over omc in [a, b] with the substitution omc = exp(t).
    auto integrate = [&](double a, double b, bool moment)
    {
      const int m = 400;
      const double ta = std::log(a), tb = std::log(b), h = (tb - ta) / m;
      double s = 0;
      for (int i = 0; i <= m; ++i)
      {
        const double t = ta + i * h, omc = std::exp(t);
        const double f = pdfOmc(omc) * omc * (moment ? (g >= 0 ? 1 - omc : omc - 1) : 1.0);
        s += f * ((i == 0 || i == m) ? 1 : (i % 2 ? 4 : 2));
      }
      return s * h / 3;
    };
    const double lo = 1e-10;
    const int bins = 40;
    std::vector<double> edges(bins + 1);
    edges[0] = 0;
    for (int b = 1; b <= bins; ++b)
    {
      edges[b] = std::exp(std::log(lo) + (std::log(2.0) - std::log(lo)) * (b - 1) / (bins - 1));
    }
    std::vector<double> prob(bins);
    double total = 0, mean = 0;
    prob[0] = pdfOmc(0) * lo; // [0, 1e-10]: the pdf is flat there
    total += prob[0];
    mean += prob[0] * (g >= 0 ? 1 : -1);
    for (int b = 1; b < bins; ++b)
    {
      prob[b] = integrate(edges[b], edges[b + 1], false);
      total += prob[b];
      mean += integrate(edges[b], edges[b + 1], true);
    }
    EXPECT_NEAR(total, 1.0, 1e-6) << "g = " << g;
    EXPECT_NEAR(mean, g, 1e-6) << "g = " << g;

    const int samples = 200000;
    std::mt19937_64 gen(1234);
    std::uniform_real_distribution<double> uni(0, 1);
    std::vector<double> counts(bins, 0);
    const double in[3] = { 0.36, -0.48, 0.8 };
    double azCos = 0, azSin = 0;
    double t1[3], t2[3];
    vtkMath::Perpendiculars(in, t1, t2, 0);
    for (int s = 0; s < samples; ++s)
    {
      double out[3];
      vtkReferenceRenderer::SampleHenyeyGreenstein(g, in, uni(gen), uni(gen), out);
      ASSERT_NEAR(vtkMath::Norm(out), 1.0, 1e-12);
      const double sgn = g >= 0 ? -1 : 1;
      const double d[3] = { in[0] + sgn * out[0], in[1] + sgn * out[1], in[2] + sgn * out[2] };
      const double omc = 0.5 * vtkMath::Dot(d, d);
      const int b =
        static_cast<int>(std::upper_bound(edges.begin(), edges.end(), omc) - edges.begin()) - 1;
      counts[std::min(std::max(b, 0), bins - 1)] += 1;
      const double a = std::atan2(vtkMath::Dot(out, t2), vtkMath::Dot(out, t1));
      azCos += std::cos(a);
      azSin += std::sin(a);
    }
    // Chi-square over bins with expected count >= 5 (the rest merged into one bin).
    double chi2 = 0, restObs = 0, restExp = 0;
    int dof = -1;
    for (int b = 0; b < bins; ++b)
    {
      const double e = prob[b] * samples;
      if (e >= 5)
      {
        chi2 += (counts[b] - e) * (counts[b] - e) / e;
        ++dof;
      }
      else
      {
        restObs += counts[b];
        restExp += e;
      }
    }
    if (restExp >= 5)
    {
      chi2 += (restObs - restExp) * (restObs - restExp) / restExp;
      ++dof;
    }
    else
    {
      EXPECT_LE(restObs, restExp + 5 * std::sqrt(restExp + 1)) << "g = " << g;
    }
    // 99.9% quantile of chi-square (Wilson-Hilferty).
    const double k = dof, z = 3.09;
    const double crit = k * std::pow(1 - 2 / (9 * k) + z * std::sqrt(2 / (9 * k)), 3);
    EXPECT_LT(chi2, crit) << "g = " << g << ", dof = " << dof;
    // Azimuth uniform: |mean of exp(i phi)| ~ 1/sqrt(N) (4.5 sigma).
    EXPECT_LT(std::hypot(azCos, azSin) / samples, 4.5 / std::sqrt(samples)) << "g = " << g;
  }
}

// ---------------------------------------------------------------------------------------------
// A ray through n = n0 + a y against the analytic solution: v_x = C is conserved, and
// n(x) = n_s cosh(k x) + (a tan(alpha) / k) sinh(k x) with k = a / C, y = (n - n0) / a,
// arc length s(x) = [n_s sinh(k x) / k + a tan(alpha) (cosh(k x) - 1) / k^2] / C.
TEST(ReferenceRenderer, CurvedRayLinearGradient)
{
  const double n0 = 1.2, a = 0.08;
  const int dims[3] = { 21, 21, 5 };
  const double spacing[3] = { 0.5, 0.5, 0.5 }, origin[3] = { 0, 0, 0 };
  auto medium = MakeMedium(
    dims, spacing, origin, [&](int, int j, int, Voxel& v) { v.N = n0 + a * j * spacing[1]; });
  vtkNew<vtkReferenceRenderer> r;
  const double alpha = vtkMath::RadiansFromDegrees(25.0);
  const double x0[3] = { 0.5, 1.0, 1.0 };
  const double d0[3] = { std::cos(alpha), std::sin(alpha), 0 };
  const double ns = n0 + a * x0[1];
  const double C = ns * std::cos(alpha), k = a / C;
  auto sOfX = [&](double x)
  {
    return (ns * std::sinh(k * x) / k + a * std::tan(alpha) * (std::cosh(k * x) - 1) / (k * k)) / C;
  };
  auto yOfX = [&](double x)
  { return (ns * std::cosh(k * x) + a * std::tan(alpha) / k * std::sinh(k * x) - n0) / a; };
  // Travel until x has advanced by 8 (stays inside [0, 10] in x and y).
  const double dx = 8.0;
  const double arc = sOfX(dx);
  // Large steps allowed so that the error control (not the step cap) sets the accuracy.
  r->SetMaximumStep(100);
  for (double tol : { 1e-4, 1e-6, 1e-8 })
  {
    r->SetIntegratorTolerance(tol);
    double x1[3], d1[3];
    const int steps = r->TraceRay(medium, x0, d0, arc, x1, d1);
    ASSERT_GT(steps, 0);
    const double y = yOfX(x1[0] - x0[0]) + 0; // y measured from 0 (n = n0 at y = 0)
    const double errY = std::abs(x1[1] - y);
    const double errX = std::abs(x1[0] - x0[0] - dx);
    // Direction: tan(theta) = dy/dx = (dn/dx) / a.
    const double dndx = ns * k * std::sinh(k * dx) + a * std::tan(alpha) * std::cosh(k * dx);
    const double slope = dndx / a;
    const double errSlope = std::abs(d1[1] / d1[0] - slope);
    std::cout << "tol " << tol << ": steps " << steps << ", |dx err| " << errX << ", |y err| "
              << errY << ", |slope err| " << errSlope << ", bend " << std::atan(slope) - alpha
              << " rad\n";
    // Local tolerance tol (relative to the 0.5 spacing) per step: the global error stays within
    // a few tol x steps x spacing.
    EXPECT_LT(errY, 10 * tol * steps * 0.5 + 1e-10);
    EXPECT_LT(errX, 10 * tol * steps * 0.5 + 1e-10);
    EXPECT_LT(errSlope, 10 * tol * steps + 1e-10);
    EXPECT_NEAR(d1[2], 0.0, 1e-12);
  }
  // Leaving the box through the face x = 10.25: from there on a straight line in the exit
  // direction.
  {
    r->SetIntegratorTolerance(1e-9);
    const double dxFace = 10.25 - x0[0];
    ASSERT_LT(yOfX(dxFace), 10.0); // exits through the x face, where n is exactly linear
    const double dndx =
      ns * k * std::sinh(k * dxFace) + a * std::tan(alpha) * std::cosh(k * dxFace);
    const double slope = dndx / a;
    const double ex[3] = { 1 / std::sqrt(1 + slope * slope), slope / std::sqrt(1 + slope * slope),
      0 };
    const double extra = 3.0;
    double x1[3], d1[3];
    r->TraceRay(medium, x0, d0, sOfX(dxFace) + extra, x1, d1);
    const double expected[3] = { 10.25 + extra * ex[0], yOfX(dxFace) + extra * ex[1], x0[2] };
    std::cout << "exit: end point error " << std::abs(x1[0] - expected[0]) << ", "
              << std::abs(x1[1] - expected[1]) << "\n";
    for (int i = 0; i < 3; ++i)
    {
      EXPECT_NEAR(x1[i], expected[i], 2e-4); // exit located within 1e-4 voxel (0.5e-4 here)
      EXPECT_NEAR(d1[i], ex[i], 1e-6);
    }
  }
  // The bend is large enough that a straight line would fail the test above by far.
  EXPECT_GT(std::abs(yOfX(dx) - (x0[1] + dx * std::tan(alpha))), 0.3);

  // Constant index: a straight line, exactly.
  auto flat = Homogeneous(dims, spacing, origin, Voxel{ 1.4 });
  double x1[3], d1[3];
  r->TraceRay(flat, x0, d0, 7.0, x1, d1);
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_NEAR(x1[i], x0[i] + 7.0 * d0[i], 1e-12);
    EXPECT_NEAR(d1[i], d0[i], 1e-15);
  }
}

// ---------------------------------------------------------------------------------------------
// Unscattered transmittance of a slab, non-grey (per-channel paths): with no lights only the
// background seen through the slab remains, exp(-tau) per channel in expectation.
TEST(ReferenceRenderer, SlabUnscatteredTransmittance)
{
  const int dims[3] = { 4, 4, 4 };
  const double spacing[3] = { 10, 10, 0.5 }, origin[3] = { 0, 0, 0 };
  const double thickness = 4 * 0.5;
  const double tau[3] = { 0.3, 1.0, 2.5 };
  Voxel v;
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = tau[c] / thickness;
    v.Albedo[c] = 0.2 * (c + 1);
  }
  v.N = 1.33;
  auto medium = Homogeneous(dims, spacing, origin, v);
  const double focal[3] = { 15, 15, 0.75 }, dop[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(medium);
  r->SetCamera(ParallelCamera(focal, dop, up, 5.0));
  r->SetImageSize(16, 16);
  r->SetSamplesPerPixel(Spp(16));
  r->SetBackgroundColor(1, 1, 1);
  r->SetSeed(7);
  r->Update();
  vtkImageData* out = r->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), 256);
  EXPECT_EQ(FieldValue(out, "SamplesPerPixel"), Spp(16));
  EXPECT_GE(FieldValue(out, "RenderSeconds"), 0);
  auto* hdr = vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("HDR"));
  ASSERT_NE(hdr, nullptr);
  ASSERT_EQ(hdr->GetNumberOfComponents(), 4);
  EXPECT_EQ(hdr->GetComponent(0, 3), 1.0);
  ASSERT_NE(vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetScalars()), nullptr);
  const Pooled p = Pool(out);
  for (int c = 0; c < 3; ++c)
  {
    const double expected = std::exp(-tau[c]);
    std::cout << "channel " << c << ": T = " << p.Mean[c] << " +- " << p.Error[c]
              << ", exp(-tau) = " << expected << "\n";
    EXPECT_GT(p.Error[c], 0);
    EXPECT_NEAR(p.Mean[c], expected, 4 * p.Error[c]);
  }
}

// ---------------------------------------------------------------------------------------------
// A strongly heterogeneous, non-grey, emitting medium (sigma_t jumps by 15x between blocks of the
// per-block majorant grid; emission in one region only, where the majorant is raised) seen along
// +x: L = int eps(x) T(x) dx + L_bg T(end), with sigma and eps piecewise linear between voxel
// centres (constant in the outer half voxels), integrated here by fine quadrature.
TEST(ReferenceRenderer, HeterogeneousEmissionAbsorptionAlongX)
{
  const int dims[3] = { 17, 3, 3 };
  const double spacing[3] = { 0.25, 1.0, 1.0 }, origin[3] = { 0, 0, 0 };
  auto sigmaAt = [](int i, int c)
  {
    return (0.2 + 0.1 * i + (i >= 8 && i <= 10 ? 3.0 : 0.0)) *
      (c == 0 ? 1.0 : (c == 1 ? 0.5 : 2.0));
  };
  auto epsAt = [](int i, int c) { return (i >= 2 && i <= 4) ? 0.5 + 0.2 * c : 0.0; };
  auto medium = MakeMedium(dims, spacing, origin,
    [&](int i, int, int, Voxel& v)
    {
      for (int c = 0; c < 3; ++c)
      {
        v.Sigma[c] = sigmaAt(i, c);
        v.Albedo[c] = 0.5;
        v.Emission[c] = epsAt(i, c);
      }
    });
  const double bg = 0.7;
  const double focal[3] = { 2.0, 1.0, 1.0 }, dop[3] = { 1, 0, 0 }, up[3] = { 0, 0, 1 };
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(medium);
  r->SetCamera(ParallelCamera(focal, dop, up, 0.8));
  r->SetBackgroundColor(bg, bg, bg);
  r->SetImageSize(8, 8);
  r->SetSamplesPerPixel(Spp(64));
  r->SetSeed(4);
  r->Update();
  const Pooled p = Pool(r->GetOutput());
  auto field = [&](const std::function<double(int, int)>& f, double x, int c)
  {
    const double u = std::min(std::max(x / spacing[0], 0.0), 16.0);
    const int i = std::min(static_cast<int>(u), 15);
    const double t = u - i;
    return (1 - t) * f(i, c) + t * f(i + 1, c);
  };
  for (int c = 0; c < 3; ++c)
  {
    const int m = 200000;
    const double x0 = -0.125, x1 = 16.5 * 0.25, h = (x1 - x0) / m;
    double tau = 0, L = 0;
    for (int q = 0; q < m; ++q)
    {
      const double x = x0 + (q + 0.5) * h;
      const double s = field(sigmaAt, x, c);
      // Emission over this piece, attenuated from its middle (second-order accurate).
      L += field(epsAt, x, c) * std::exp(-(tau + 0.5 * s * h)) * h;
      tau += s * h;
    }
    L += bg * std::exp(-tau);
    std::cout << "heterogeneous channel " << c << ": " << p.Mean[c] << " +- " << p.Error[c]
              << ", quadrature " << L << " (tau " << tau << ")\n";
    EXPECT_NEAR(p.Mean[c], L, 4 * p.Error[c]);
    EXPECT_LT(p.Error[c], 0.05 * L);
  }
}

// ---------------------------------------------------------------------------------------------
// Emission-absorption cube with a uniform index (straight rays), rotated and translated, seen in
// perspective: per pixel L = eps / (n^2 sigma) (1 - exp(-sigma l)) + L_bg exp(-sigma l), l the
// chord (emission is physical radiance per length; the camera in n = 1 sees L / n^2).
TEST(ReferenceRenderer, EmissionAbsorptionCubeMatchesStraightLine)
{
  const int dims[3] = { 6, 5, 4 };
  const double spacing[3] = { 0.2, 0.25, 0.3 }, origin[3] = { 10, -5, 3 };
  Voxel v;
  v.N = 1.3;
  const double sigma = 1.5, eps[3] = { 0.6, 0.3, 0.9 }, bg[3] = { 0.2, 0.5, 0.1 };
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = sigma;
    v.Albedo[c] = 0.4;
    v.Emission[c] = eps[c];
  }
  auto medium = Homogeneous(dims, spacing, origin, v);
  vtkNew<vtkMatrix3x3> rot; // 30 degrees about z
  const double ca = std::cos(Pi / 6), sa = std::sin(Pi / 6);
  rot->SetElement(0, 0, ca);
  rot->SetElement(0, 1, -sa);
  rot->SetElement(1, 0, sa);
  rot->SetElement(1, 1, ca);
  medium->SetDirectionMatrix(rot);

  // World-space box corners for the analytic chord: local box [-s/2, (N - 1/2) s].
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = -0.5 * spacing[a];
    hi[a] = (dims[a] - 0.5) * spacing[a];
  }
  auto chord = [&](const double ow[3], const double dw[3])
  {
    // To local: D^T (p - o).
    double o[3], d[3];
    const double po[3] = { ow[0] - origin[0], ow[1] - origin[1], ow[2] - origin[2] };
    for (int i = 0; i < 3; ++i)
    {
      o[i] = rot->GetElement(0, i) * po[0] + rot->GetElement(1, i) * po[1] +
        rot->GetElement(2, i) * po[2];
      d[i] = rot->GetElement(0, i) * dw[0] + rot->GetElement(1, i) * dw[1] +
        rot->GetElement(2, i) * dw[2];
    }
    double t0 = 0, t1 = 1e30;
    for (int a = 0; a < 3; ++a)
    {
      double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
      if (ta > tb)
      {
        std::swap(ta, tb);
      }
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    return std::max(0.0, t1 - t0);
  };

  vtkNew<vtkCamera> cam;
  double centre[3] = { 0, 0, 0 };
  {
    const double lc[3] = { 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]) };
    for (int i = 0; i < 3; ++i)
    {
      centre[i] = origin[i] + rot->GetElement(i, 0) * lc[0] + rot->GetElement(i, 1) * lc[1] +
        rot->GetElement(i, 2) * lc[2];
    }
  }
  cam->SetFocalPoint(centre);
  cam->SetPosition(centre[0] + 2.0, centre[1] - 2.5, centre[2] + 1.5);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(35);
  const int W = 16, H = 12;
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(medium);
  r->SetCamera(cam);
  r->SetImageSize(W, H);
  r->SetSamplesPerPixel(Spp(32));
  r->SetBackgroundColor(bg[0], bg[1], bg[2]);
  r->SetSeed(0);
  r->Update();
  vtkImageData* out = r->GetOutput();
  vtkDataArray* hdr = out->GetPointData()->GetArray("HDR");
  vtkDataArray* se = out->GetPointData()->GetArray("StandardError");

  // The camera basis, as documented (vertical view angle, pixel centres).
  double pos[3], dop[3], vup[3], right[3];
  cam->GetPosition(pos);
  cam->GetDirectionOfProjection(dop);
  cam->GetViewUp(vup);
  vtkMath::Cross(dop, vup, right);
  vtkMath::Normalize(right);
  vtkMath::Cross(right, dop, vup);
  const double th = std::tan(vtkMath::RadiansFromDegrees(35.0) / 2);
  // Pooled per channel (the three channels of a grey medium share their paths, so they are not
  // independent); per-pixel z-scores only where the chord is at least 0.2 (>= 4 expected
  // tentative collisions), since with 32 samples a pixel that a ray barely grazes has a badly
  // estimated standard error.
  double z2 = 0, maxZ = 0, resid[3] = { 0, 0, 0 }, var[3] = { 0, 0, 0 };
  int hitPixels = 0, zPixels = 0;
  for (int j = 0; j < H; ++j)
  {
    for (int i = 0; i < W; ++i)
    {
      const double sx = (2 * (i + 0.5) / W - 1) * th * W / H, sy = (2 * (j + 0.5) / H - 1) * th;
      double d[3];
      for (int a = 0; a < 3; ++a)
      {
        d[a] = dop[a] + sx * right[a] + sy * vup[a];
      }
      vtkMath::Normalize(d);
      const double l = chord(pos, d);
      const vtkIdType id = i + W * j;
      for (int c = 0; c < 3; ++c)
      {
        const double T = std::exp(-sigma * l);
        const double expected = eps[c] / (v.N * v.N * sigma) * (1 - T) + bg[c] * T;
        const double got = hdr->GetComponent(id, c), err = se->GetComponent(id, c);
        if (l == 0)
        {
          EXPECT_EQ(got, static_cast<float>(bg[c])) << "pixel " << i << "," << j;
          EXPECT_EQ(err, 0.0);
          continue;
        }
        ASSERT_GT(err, 0) << "pixel " << i << "," << j;
        resid[c] += got - expected;
        var[c] += err * err;
        hitPixels += c == 0 ? 1 : 0;
        if (l >= 0.2)
        {
          const double zz = (got - expected) / err;
          z2 += zz * zz;
          maxZ = std::max(maxZ, std::abs(zz));
          ++zPixels;
        }
      }
    }
  }
  ASSERT_GT(hitPixels, 50);
  ASSERT_GT(zPixels, 100);
  std::cout << "emission-absorption: " << hitPixels << " pixels hit, mean z^2 " << z2 / zPixels
            << " over " << zPixels << " pixel channels, max |z| " << maxZ << "\n";
  for (int c = 0; c < 3; ++c)
  {
    std::cout << "  channel " << c << ": pooled residual " << resid[c] / hitPixels << " +- "
              << std::sqrt(var[c]) / hitPixels << "\n";
    EXPECT_LT(std::abs(resid[c]), 4 * std::sqrt(var[c]));
  }
  // With 32 samples the per-pixel standard errors are themselves noisy: E[z^2] ~ 1.1.
  EXPECT_LT(z2 / zPixels, 1.6);
  EXPECT_GT(z2 / zPixels, 0.6);
}

// ---------------------------------------------------------------------------------------------
// Single scattering (MaximumScatteringDepth = 1) by a laterally wide slab lit by a directional
// light: reflected radiance w E p(Theta) mu0 / (mu + mu0) (1 - exp(-tau (1/mu + 1/mu0))) and
// transmitted w E p(Theta) mu0 / (mu0 - mu) (exp(-tau/mu0) - exp(-tau/mu)), HG phase g = 0.5,
// per channel.
TEST(ReferenceRenderer, SlabSingleScatteringDirectionalLight)
{
  const int dims[3] = { 3, 3, 4 };
  const double spacing[3] = { 40, 40, 0.25 }, origin[3] = { -40, -40, 0 };
  // Non-grey (one path per channel): optical thickness and albedo differ per channel.
  const double tauC[3] = { 1.0, 0.5, 2.0 }, wC[3] = { 0.8, 0.6, 0.9 }, g = 0.5, E = 3.0;
  Voxel v;
  v.G = g;
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = tauC[c] / 1.0; // thickness 4 * 0.25 = 1
    v.Albedo[c] = wC[c];
  }
  auto medium = Homogeneous(dims, spacing, origin, v);
  const double zc = 0.5 * (-0.125 + 0.875); // slab from z = -0.125 to 0.875
  const double th0 = vtkMath::RadiansFromDegrees(30.0);
  const double towards[3] = { std::sin(th0), 0, std::cos(th0) };
  const double mu0 = std::cos(th0);
  const double travelIn[3] = { -towards[0], -towards[1], -towards[2] };
  for (int reflect = 1; reflect >= 0; --reflect)
  {
    const double thv = vtkMath::RadiansFromDegrees(reflect ? 50.0 : 40.0);
    const double mu = std::cos(thv);
    // Camera direction of projection: looks down (reflection) or up (transmission), azimuth 90.
    const double dop[3] = { 0, std::sin(thv), reflect ? -mu : mu };
    const double focal[3] = { 0, 0, zc }, up[3] = { 1, 0, 0 };
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->AddLight(Directional(towards, E, 1.0, 0.5, 0.25));
    r->SetImageSize(16, 16);
    r->SetSamplesPerPixel(Spp(48));
    r->SetMaximumScatteringDepth(1);
    r->SetSeed(11);
    r->Update();
    // Outgoing travel direction towards the camera is -dop.
    const double out[3] = { -dop[0], -dop[1], -dop[2] };
    const double p = vtkReferenceRenderer::HenyeyGreensteinPhase(g, vtkMath::Dot(travelIn, out));
    const Pooled pl = Pool(r->GetOutput());
    const double colour[3] = { 1.0, 0.5, 0.25 };
    for (int c = 0; c < 3; ++c)
    {
      const double tau = tauC[c], w = wC[c];
      const double expected = reflect
        ? w * E * p * mu0 / (mu + mu0) * (1 - std::exp(-tau * (1 / mu + 1 / mu0)))
        : w * E * p * mu0 / (mu0 - mu) * (std::exp(-tau / mu0) - std::exp(-tau / mu));
      std::cout << (reflect ? "reflected" : "transmitted") << " channel " << c << ": " << pl.Mean[c]
                << " +- " << pl.Error[c] << ", analytic " << expected * colour[c] << "\n";
      EXPECT_NEAR(pl.Mean[c], expected * colour[c], 4 * pl.Error[c]);
      EXPECT_LT(pl.Error[c], 0.05 * expected * colour[c]); // the test has power
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Single scattering from a point light and a spot light inside a thin medium, against quadrature
// along each view ray: L = int T_cam sigma_s p I(w) / r^2 T_light dt (a uniform sphere's
// irradiance is exactly I / r^2, whatever its radius).
TEST(ReferenceRenderer, PointAndSpotLightSingleScattering)
{
  const int dims[3] = { 5, 5, 5 };
  const double spacing[3] = { 0.25, 0.25, 0.25 }, origin[3] = { 0, 0, 0 };
  const double sigma = 0.6, w = 0.9, g = 0.3;
  Voxel v;
  v.G = g;
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = sigma;
    v.Albedo[c] = w;
  }
  auto medium = Homogeneous(dims, spacing, origin, v);
  const double lo = -0.125, hi = 1.125;
  for (int spot = 0; spot <= 1; ++spot)
  {
    const double lp[3] = { 0.5, 1.6, 0.5 }; // outside the box, above in y
    const double lf[3] = { 0.5, 0.0, 0.5 };
    const double I = 2.0, cone = 25.0, expo = 2.0;
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->PositionalOn();
    light->SetPosition(lp[0], lp[1], lp[2]);
    light->SetFocalPoint(lf[0], lf[1], lf[2]);
    light->SetIntensity(I);
    light->SetConeAngle(spot ? cone : 90.0);
    light->SetExponent(expo);
    const double focal[3] = { 0.5, 0.5, 0.5 }, dop[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
    auto cam = ParallelCamera(focal, dop, up, 0.6);
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(cam);
    r->AddLight(light);
    r->SetLightRadius(0.01);
    r->SetImageSize(12, 12);
    r->SetSamplesPerPixel(Spp(96));
    r->SetMaximumScatteringDepth(1);
    r->Update();
    vtkImageData* out = r->GetOutput();
    vtkDataArray* hdr = out->GetPointData()->GetArray("HDR");
    vtkDataArray* se = out->GetPointData()->GetArray("StandardError");
    // Quadrature reference per pixel (the camera ray is along -z through x, y).
    auto boxLen = [&](const double o[3], const double d[3], double tmax)
    {
      double t0 = 0, t1 = tmax;
      for (int a = 0; a < 3; ++a)
      {
        if (d[a] == 0)
        {
          continue;
        }
        double ta = (lo - o[a]) / d[a], tb = (hi - o[a]) / d[a];
        if (ta > tb)
        {
          std::swap(ta, tb);
        }
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
      }
      return std::max(0.0, t1 - t0);
    };
    double resid = 0, var = 0, sumRef = 0;
    for (int j = 0; j < 12; ++j)
    {
      for (int i = 0; i < 12; ++i)
      {
        const double x = 0.5 + (2 * (i + 0.5) / 12 - 1) * 0.6;
        const double y = 0.5 + (2 * (j + 0.5) / 12 - 1) * 0.6;
        double ref = 0;
        const int m = 2000;
        const double h = (hi - lo) / m;
        for (int q = 0; q < m; ++q)
        {
          const double z = hi - (q + 0.5) * h; // distance from the top face: (q + 0.5) h
          const double tcam = std::exp(-sigma * (q + 0.5) * h);
          const double p[3] = { x, y, z };
          double toL[3] = { lp[0] - x, lp[1] - y, lp[2] - z };
          const double r2 = vtkMath::Dot(toL, toL), rl = std::sqrt(r2);
          const double dl[3] = { toL[0] / rl, toL[1] / rl, toL[2] / rl };
          const double tl = std::exp(-sigma * boxLen(p, dl, rl));
          // Scattering: incoming travel direction -dl, outgoing +z (towards the camera).
          const double cosT = -dl[2];
          double Iw = I;
          if (spot)
          {
            double axis[3] = { lf[0] - lp[0], lf[1] - lp[1], lf[2] - lp[2] };
            vtkMath::Normalize(axis);
            const double ca = -vtkMath::Dot(dl, axis);
            Iw = ca >= std::cos(vtkMath::RadiansFromDegrees(cone)) ? I * std::pow(ca, expo) : 0;
          }
          ref += tcam * sigma * w * vtkReferenceRenderer::HenyeyGreensteinPhase(g, cosT) * Iw / r2 *
            tl * h;
        }
        const vtkIdType id = i + 12 * j;
        resid += hdr->GetComponent(id, 0) - ref;
        var += se->GetComponent(id, 0) * se->GetComponent(id, 0);
        sumRef += ref;
      }
    }
    std::cout << (spot ? "spot" : "point") << ": mean " << (sumRef + resid) / 144 << " +- "
              << std::sqrt(var) / 144 << ", quadrature " << sumRef / 144 << "\n";
    EXPECT_LT(std::abs(resid), 4 * std::sqrt(var));
    EXPECT_LT(std::sqrt(var), 0.05 * sumRef);
  }
}

// ---------------------------------------------------------------------------------------------
// Multiple scattering: a thick isotropic slab (tau = 30, albedo 0.9, effectively semi-infinite)
// under a normal directional beam; reflected radiance E w mu0 H(mu) H(mu0) / (4 pi (mu + mu0))
// (Chandrasekhar), H computed here by iteration.
TEST(ReferenceRenderer, SemiInfiniteMultipleScatteringChandrasekhar)
{
  EXPECT_NEAR(HFunction(1.0, 1.0), 2.9078, 5e-3); // tabulated (Chandrasekhar 1950); 64 nodes
  const double w = 0.9, E = 1.0;
  const int dims[3] = { 3, 3, 3 };
  const double spacing[3] = { 100, 100, 10 }, origin[3] = { -100, -100, 0 };
  Voxel v;
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = 1.0;
    v.Albedo[c] = w;
  }
  auto medium = Homogeneous(dims, spacing, origin, v);
  const double top = 25.0;
  const double towards[3] = { 0, 0, 1 };
  for (double thv : { 0.0, 60.0 })
  {
    const double t = vtkMath::RadiansFromDegrees(thv), mu = std::cos(t);
    const double dop[3] = { std::sin(t), 0, -mu }, focal[3] = { 0, 0, top }, up[3] = { 0, 1, 0 };
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->AddLight(Directional(towards, E));
    r->SetImageSize(16, 16);
    r->SetSamplesPerPixel(Spp(24));
    r->SetSeed(3);
    r->Update();
    const Pooled p = Pool(r->GetOutput());
    const double expected =
      E * w * 1.0 * HFunction(w, mu) * HFunction(w, 1.0) / (4 * Pi * (mu + 1.0));
    std::cout << "semi-infinite w = " << w << ", mu = " << mu << ": " << p.Mean[0] << " +- "
              << p.Error[0] << ", Chandrasekhar " << expected << ", seconds "
              << FieldValue(r->GetOutput(), "RenderSeconds") << "\n";
    EXPECT_NEAR(p.Mean[0], expected, 4 * p.Error[0]);
    EXPECT_LT(p.Error[0], 0.05 * expected);
    EXPECT_EQ(p.Mean[0], p.Mean[1]); // grey: one path carries RGB
  }
}

// ---------------------------------------------------------------------------------------------
// Total diffuse reflectance (plane albedo) of the semi-infinite isotropic medium under a normal
// beam: A = 1 - H(1) sqrt(1 - w) (Chandrasekhar 1950; van de Hulst 1980). The reflected flux
// 2 pi int I(mu) mu dmu / E is integrated from renders at 6 Gauss-Legendre view angles; the same
// quadrature applied to the exact I(mu) checks that the quadrature error is negligible.
TEST(ReferenceRenderer, SemiInfinitePlaneAlbedo)
{
  const double w = 0.8;
  const int dims[3] = { 3, 3, 3 };
  const double spacing[3] = { 100, 100, 10 }, origin[3] = { -100, -100, 0 };
  Voxel v;
  for (int c = 0; c < 3; ++c)
  {
    v.Sigma[c] = 1.0;
    v.Albedo[c] = w;
  }
  auto medium = Homogeneous(dims, spacing, origin, v);
  const double towards[3] = { 0, 0, 1 };
  std::vector<double> mu, wt;
  GaussLegendre(6, mu, wt);
  double albedoMC = 0, var = 0, albedoQuad = 0;
  for (size_t q = 0; q < mu.size(); ++q)
  {
    const double t = std::acos(mu[q]);
    const double dop[3] = { std::sin(t), 0, -mu[q] }, focal[3] = { 0, 0, 25 }, up[3] = { 0, 1, 0 };
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->AddLight(Directional(towards, 1.0));
    r->SetImageSize(8, 8);
    r->SetSamplesPerPixel(Spp(64));
    r->SetSeed(static_cast<unsigned int>(q));
    r->Update();
    const Pooled p = Pool(r->GetOutput());
    const double f = 2 * Pi * wt[q] * mu[q];
    albedoMC += f * p.Mean[0];
    var += f * f * p.Error[0] * p.Error[0];
    albedoQuad += f * w * HFunction(w, mu[q]) * HFunction(w, 1.0) / (4 * Pi * (mu[q] + 1));
  }
  const double published = 1 - HFunction(w, 1.0) * std::sqrt(1 - w);
  std::cout << "plane albedo w = " << w << ": Monte Carlo " << albedoMC << " +- " << std::sqrt(var)
            << ", quadrature of exact I " << albedoQuad << ", 1 - H(1) sqrt(1 - w) = " << published
            << "\n";
  EXPECT_NEAR(albedoQuad, published, 1e-3);
  EXPECT_NEAR(albedoMC, albedoQuad, 4 * std::sqrt(var));
  EXPECT_LT(std::sqrt(var), 0.03 * published);
}

// ---------------------------------------------------------------------------------------------
// Rendering along curved rays: an emission-absorption medium with n = n0 + a y seen along +x by a
// parallel camera. A view ray entering horizontally at height y0 bends upwards; its arc length
// to the far face is s = sinh(k dx) / k with k = a / n(y0), and n = n(y0) cosh(k x) along it, so
// per pixel (emission counting 1 / n^2, ds = cosh(k x) dx)
// L = eps / n(y0)^2 int_0^dx exp(-sigma sinh(k x) / k) / cosh(k x) dx + L_bg exp(-sigma s).
// (A straight-line answer is off by up to 30%.)
TEST(ReferenceRenderer, CurvedViewRaysEmissionAbsorption)
{
  const double n0 = 1.0, a = 0.3, sigma = 0.1, eps = 0.5, bg = 0.2;
  const int dims[3] = { 11, 21, 3 };
  const double spacing[3] = { 0.5, 0.5, 0.5 }, origin[3] = { 0, 0, 0 };
  auto medium = MakeMedium(dims, spacing, origin,
    [&](int, int j, int, Voxel& v)
    {
      v.N = n0 + a * j * spacing[1];
      for (int c = 0; c < 3; ++c)
      {
        v.Sigma[c] = sigma;
        v.Emission[c] = eps;
      }
    });
  const int W = 2, H = 16;
  const double focal[3] = { 2.5, 4.5, 0.5 }, dop[3] = { 1, 0, 0 }, up[3] = { 0, 1, 0 };
  const double scale = 3.5;
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(medium);
  r->SetCamera(ParallelCamera(focal, dop, up, scale));
  r->SetImageSize(W, H);
  r->SetSamplesPerPixel(Spp(64));
  r->SetBackgroundColor(bg, bg, bg);
  r->Update();
  vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
  vtkDataArray* se = r->GetOutput()->GetPointData()->GetArray("StandardError");
  ASSERT_NE(hdr, nullptr);
  const double dx = 5.5; // from x = -0.25 to 5.25
  double resid = 0, var = 0, z2 = 0, maxRelStraight = 0;
  int count = 0;
  for (int j = 0; j < H; ++j)
  {
    const double y0 = focal[1] + (2 * (j + 0.5) / H - 1) * scale;
    const double ns = n0 + a * y0, k = a / ns;
    const double yEnd = (ns * std::cosh(k * dx) - n0) / a;
    ASSERT_LT(yEnd, (dims[1] - 1) * spacing[1]); // stays where n is exactly linear
    const double s = std::sinh(k * dx) / k;
    const double T = std::exp(-sigma * s);
    double emitted = 0; // Simpson's rule
    const int q = 2000;
    for (int i = 0; i <= q; ++i)
    {
      const double x = dx * i / q, w = (i == 0 || i == q) ? 1 : (i % 2 ? 4 : 2);
      emitted += w * std::exp(-sigma * std::sinh(k * x) / k) / std::cosh(k * x);
    }
    emitted *= eps / (ns * ns) * dx / (3 * q);
    const double expected = emitted + bg * T;
    const double straight =
      eps / (ns * ns * sigma) * (1 - std::exp(-sigma * dx)) + bg * std::exp(-sigma * dx);
    maxRelStraight = std::max(maxRelStraight, std::abs(straight - expected) / expected);
    for (int i = 0; i < W; ++i)
    {
      const double got = hdr->GetComponent(i + W * j, 0), err = se->GetComponent(i + W * j, 0);
      ASSERT_GT(err, 0);
      resid += got - expected;
      var += err * err;
      z2 += (got - expected) * (got - expected) / (err * err);
      ++count;
    }
  }
  std::cout << "curved view rays: pooled residual " << resid / count << " +- "
            << std::sqrt(var) / count << ", mean z^2 " << z2 / count
            << ", straight-line answer off by up to " << 100 * maxRelStraight << "%\n";
  EXPECT_GT(maxRelStraight, 0.1);
  EXPECT_LT(std::abs(resid), 4 * std::sqrt(var));
  EXPECT_LT(z2 / count, 1.8);
}

// ---------------------------------------------------------------------------------------------
// The curved-ray machinery (RK5(4) view rays, curved light connections with chord-sphere tests
// and exit discs, straight moves through flat blocks) against the straight-line fast path, in a
// multiple-scattering scene with a point light inside the medium and a directional light:
// variant 1, n = 1 + 1e-7 y, takes RK steps everywhere; variant 2, a bump of 1e-7 in one corner
// voxel, takes RK steps near it and crosses the other (flat) blocks in straight moves. Rays bend
// by less than 1e-6, so with the same seed the images must agree with the n = 1 image to far
// better than their standard errors.
TEST(ReferenceRenderer, CurvedMachineryMatchesStraightPathInTheLimit)
{
  const int dims[3] = { 10, 10, 10 };
  const double spacing[3] = { 0.12, 0.12, 0.12 }, origin[3] = { 0, 0, 0 };
  auto build = [&](int variant)
  {
    return MakeMedium(dims, spacing, origin,
      [&](int i, int j, int k, Voxel& v)
      {
        v.N = 1.0 + (variant == 1 ? 1e-7 * j * spacing[1] : 0.0) +
          (variant == 2 && i == 9 && j == 9 && k == 0 ? 1e-7 : 0.0);
        v.G = 0.3;
        for (int c = 0; c < 3; ++c)
        {
          v.Sigma[c] = 1.0 + 0.5 * ((i + k) % 3);
          v.Albedo[c] = 0.8;
        }
      });
  };
  vtkNew<vtkLight> pl;
  pl->PositionalOn();
  pl->SetConeAngle(180);
  pl->SetPosition(0.5, 0.5, 0.5);
  pl->SetIntensity(0.5);
  const double towards[3] = { 0.3, 0.2, 0.93 };
  vtkNew<vtkCamera> cam;
  cam->SetPosition(0.5, -2.0, 1.2);
  cam->SetFocalPoint(0.5, 0.5, 0.5);
  cam->SetViewUp(0, 0, 1);
  cam->SetViewAngle(40);
  Pooled p[3];
  std::vector<double> img[3];
  for (int variant = 0; variant <= 2; ++variant)
  {
    auto medium = build(variant);
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(cam);
    r->AddLight(pl);
    r->AddLight(Directional(towards, 1.0));
    r->SetLightRadius(0.05);
    r->SetImageSize(12, 12);
    r->SetSamplesPerPixel(Spp(16));
    r->SetSeed(9);
    r->Update();
    p[variant] = Pool(r->GetOutput());
    vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
    for (vtkIdType i = 0; i < 144; ++i)
    {
      img[variant].push_back(hdr->GetComponent(i, 0));
    }
  }
  EXPECT_GT(p[0].Mean[0], 0);
  // The flat blocks are really crossed in straight moves: a ray along x at y = z = 0.3 needs one
  // move per block (3) with the bump, one RK step per voxel length without flat blocks, and ends
  // exactly where the straight line does.
  {
    vtkNew<vtkReferenceRenderer> r;
    const double o[3] = { -0.06, 0.3, 0.3 }, d[3] = { 1, 0, 0 };
    double e1[3], ed1[3], e2[3], ed2[3];
    const int stepsRK = r->TraceRay(build(1), o, d, 1.0, e1, ed1);
    const int stepsFlat = r->TraceRay(build(2), o, d, 1.0, e2, ed2);
    std::cout << "ray across the box: " << stepsRK << " RK steps, " << stepsFlat
              << " moves with flat blocks\n";
    EXPECT_GE(stepsRK, 8);
    EXPECT_LE(stepsFlat, 4);
    EXPECT_NEAR(e2[0], 0.94, 1e-12);
    EXPECT_EQ(e2[1], 0.3);
    EXPECT_EQ(e2[2], 0.3);
  }
  for (int variant = 1; variant <= 2; ++variant)
  {
    int identical = 0;
    for (int i = 0; i < 144; ++i)
    {
      identical +=
        std::abs(img[0][i] - img[variant][i]) <= 1e-4 * std::abs(img[0][i]) + 1e-12 ? 1 : 0;
    }
    std::cout << "straight " << p[0].Mean[0] << " +- " << p[0].Error[0]
              << (variant == 1 ? ", RK everywhere " : ", flat blocks + RK near a bump ")
              << p[variant].Mean[0] << " +- " << p[variant].Error[0]
              << ", pixels equal to 1e-4: " << identical << " / 144\n";
    EXPECT_NEAR(p[variant].Mean[0], p[0].Mean[0], 0.1 * p[0].Error[0]);
    EXPECT_GE(identical, 120);
  }
}

// ---------------------------------------------------------------------------------------------
// Determinism: same seed -> identical bits (also with one thread instead of the default); another
// seed -> a different image.
TEST(ReferenceRenderer, DeterministicPerSeed)
{
  const int dims[3] = { 8, 8, 8 };
  const double spacing[3] = { 0.1, 0.1, 0.1 }, origin[3] = { 0, 0, 0 };
  auto medium = MakeMedium(dims, spacing, origin,
    [](int i, int j, int k, Voxel& v)
    {
      v.N = 1.0 + 0.05 * i + 0.02 * j * k / 8.0;
      v.G = 0.4;
      v.Sigma[0] = 2 + i;
      v.Sigma[1] = 3;
      v.Sigma[2] = 1 + k;
      v.Albedo[0] = v.Albedo[1] = v.Albedo[2] = 0.7;
      v.Emission[1] = 0.1 * j;
    });
  const double towards[3] = { 0.3, 0.4, 0.866 };
  vtkNew<vtkCamera> cam;
  cam->SetPosition(0.4, -1.5, 0.9);
  cam->SetFocalPoint(0.35, 0.35, 0.35);
  cam->SetViewUp(0, 0, 1);
  auto render = [&](unsigned int seed)
  {
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(cam);
    r->AddLight(Directional(towards, 2.0));
    r->SetImageSize(8, 8);
    r->SetSamplesPerPixel(Spp(4));
    r->SetSeed(seed);
    r->Update();
    std::vector<float> v;
    vtkDataArray* a = r->GetOutput()->GetPointData()->GetArray("HDR");
    for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
    {
      v.push_back(static_cast<float>(a->GetComponent(i / 4, i % 4)));
    }
    return v;
  };
  const auto a = render(5);
  const auto b = render(5);
  const int threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  vtkSMPTools::Initialize(1);
  const auto c = render(5);
  vtkSMPTools::Initialize(threads);
  const auto d = render(6);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a, c);
  EXPECT_NE(a, d);
}

// ---------------------------------------------------------------------------------------------
// Hard inputs stay finite: albedo 1 with g = +-0.999 in an optically thick slab, a steep index
// step (n 1 -> 2.5 over one voxel) with a point light inside the medium.
TEST(ReferenceRenderer, HardInputsStayFinite)
{
  const int dims[3] = { 6, 6, 6 };
  const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  const double towards[3] = { 0.2, 0.1, 0.97 };
  vtkNew<vtkCamera> cam;
  cam->SetPosition(2.5, -6, 8);
  cam->SetFocalPoint(2.5, 2.5, 2.5);
  cam->SetViewUp(0, 0, 1);
  for (double g : { 0.999, -0.999 })
  {
    Voxel v;
    v.G = g;
    for (int c = 0; c < 3; ++c)
    {
      v.Sigma[c] = 4.0; // tau = 24 across
      v.Albedo[c] = 1.0;
    }
    auto medium = Homogeneous(dims, spacing, origin, v);
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(cam);
    r->AddLight(Directional(towards, 1.0));
    r->SetImageSize(8, 8);
    r->SetSamplesPerPixel(Spp(4));
    r->Update();
    vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
    vtkDataArray* se = r->GetOutput()->GetPointData()->GetArray("StandardError");
    ASSERT_NE(hdr, nullptr);
    double sum = 0;
    for (vtkIdType i = 0; i < 64; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_TRUE(std::isfinite(hdr->GetComponent(i, c)));
        ASSERT_TRUE(std::isfinite(se->GetComponent(i, c)));
        ASSERT_GE(hdr->GetComponent(i, c), 0.0);
        sum += hdr->GetComponent(i, c);
      }
    }
    EXPECT_GT(sum, 0) << "g = " << g;
    EXPECT_EQ(FieldValue(r->GetOutput(), "NonFiniteSamples"), 0);
    std::cout << "albedo 1, g = " << g << ": mean " << sum / 192 << ", "
              << FieldValue(r->GetOutput(), "RenderSeconds") << " s, truncated "
              << FieldValue(r->GetOutput(), "TruncatedPaths") << "\n";
  }
  // Enormous contrast: sigma_t = 1e5 in a 2^3 core, 0.01 elsewhere (32^3 voxels). Per-block
  // majorants confine the 1e5 majorant to the blocks around the core (a global majorant would
  // take ~3e6 null collisions per ray everywhere); finite, non-negative, bounded time.
  {
    const int bigDims[3] = { 32, 32, 32 };
    auto contrast = MakeMedium(bigDims, spacing, origin,
      [](int i, int j, int k, Voxel& v)
      {
        const bool core = i >= 15 && i <= 16 && j >= 15 && j <= 16 && k >= 15 && k <= 16;
        for (int c = 0; c < 3; ++c)
        {
          v.Sigma[c] = core ? 1e5 : 0.01;
          v.Albedo[c] = 0.9;
        }
      });
    const double focal[3] = { 15.5, 15.5, 15.5 }, dop[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(contrast);
    r->SetCamera(ParallelCamera(focal, dop, up, 8.0));
    r->AddLight(Directional(towards, 1.0));
    r->SetBackgroundColor(1, 1, 1);
    r->SetImageSize(4, 4);
    r->SetSamplesPerPixel(4);
    r->Update();
    const double secs = FieldValue(r->GetOutput(), "RenderSeconds");
    std::cout << "contrast 1e7: " << secs << " s\n";
    EXPECT_LT(secs, 30.0);
    vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
    ASSERT_NE(hdr, nullptr);
    for (vtkIdType i = 0; i < 16; ++i)
    {
      ASSERT_TRUE(std::isfinite(hdr->GetComponent(i, 0)));
      ASSERT_GE(hdr->GetComponent(i, 0), 0.0);
    }
  }
  // Steep index step, point light in the medium, curved rays.
  auto medium = MakeMedium(dims, spacing, origin,
    [](int i, int, int, Voxel& v)
    {
      v.N = i < 3 ? 1.0 : 2.5;
      v.G = 0.9;
      for (int c = 0; c < 3; ++c)
      {
        v.Sigma[c] = 0.3;
        v.Albedo[c] = 0.95;
      }
    });
  vtkNew<vtkLight> pl;
  pl->PositionalOn();
  pl->SetConeAngle(180);
  pl->SetPosition(1, 2.5, 2.5);
  pl->SetIntensity(5);
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(medium);
  r->SetCamera(cam);
  r->AddLight(pl);
  // LightRadius 0 is a delta light, which the reference refuses for point lights: give the
  // radius the renderer used to substitute silently (1% of the voxel box's diagonal).
  r->SetLightRadius(0.01 *
    std::sqrt(std::pow(dims[0] * spacing[0], 2) + std::pow(dims[1] * spacing[1], 2) +
      std::pow(dims[2] * spacing[2], 2)));
  r->SetImageSize(8, 8);
  r->SetSamplesPerPixel(Spp(4));
  r->Update();
  vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
  ASSERT_NE(hdr, nullptr);
  for (vtkIdType i = 0; i < 64; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_TRUE(std::isfinite(hdr->GetComponent(i, c)));
      ASSERT_GE(hdr->GetComponent(i, c), 0.0);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Environment map (vtkRefractaEnvironmentMap, VTK's skybox convention with the default up +y and
// right +x): an empty medium seen along +x shows the map at u = 0.75, v = 0.5 (bilinear between
// the four pixels around that point); 8-bit maps are divided by 255.
TEST(ReferenceRenderer, EnvironmentMapLookup)
{
  const int dims[3] = { 2, 2, 2 };
  const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  auto medium = Homogeneous(dims, spacing, origin, Voxel{});
  vtkNew<vtkImageData> env;
  env->SetDimensions(4, 2, 1);
  vtkNew<vtkFloatArray> s;
  s->SetNumberOfComponents(3);
  s->SetNumberOfTuples(8);
  for (int p = 0; p < 8; ++p)
  {
    s->SetTuple3(p, p, 10 * p, 100 * p);
  }
  env->GetPointData()->SetScalars(s);
  const double focal[3] = { 0.5, 0.5, 0.5 }, dop[3] = { 1, 0, 0 }, up[3] = { 0, 0, 1 };
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(medium);
  r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
  r->SetEnvironmentMap(env);
  r->SetImageSize(2, 2);
  r->SetSamplesPerPixel(Spp(2));
  r->Update();
  // u = 0.75 -> fx = 0.75 * 4 - 0.5 = 2.5 (between columns 2 and 3); v = 0.5 -> fy = 0.5 (rows
  // 0, 1).
  const double expected = 0.25 * (2 + 3 + 6 + 7);
  vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
  ASSERT_NE(hdr, nullptr);
  EXPECT_NEAR(hdr->GetComponent(0, 0), expected, 1e-5);
  EXPECT_NEAR(hdr->GetComponent(0, 1), 10 * expected, 1e-4);
  // Rays travelling -y (the -up pole): v = 0 -> bottom row, constant.
  const double dop2[3] = { 0, -1, 0 }, up2[3] = { 0, 0, 1 };
  r->SetCamera(ParallelCamera(focal, dop2, up2, 1.0));
  r->Update();
  hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
  // Bottom row (0..3) at v = 0 clamps to row 0; u = atan2(0, 0) / 2pi + 1/2 = 0.5: columns 1, 2.
  EXPECT_NEAR(hdr->GetComponent(0, 0), 1.5, 1e-5);
}

// ---------------------------------------------------------------------------------------------
// Bad inputs: a clear error, RequestData fails, the output is empty.
TEST(ReferenceRenderer, BadInputsGiveClearErrors)
{
  const int dims[3] = { 3, 3, 3 };
  const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  Voxel good;
  good.Sigma[0] = good.Sigma[1] = good.Sigma[2] = 1;
  auto medium = Homogeneous(dims, spacing, origin, good);
  const double focal[3] = { 1, 1, 1 }, dop[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
  auto run = [](vtkReferenceRenderer* r, const char* expect)
  {
    vtkNew<vtkTest::ErrorObserver> obs, execObs;
    r->AddObserver(vtkCommand::ErrorEvent, obs);
    r->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, execObs);
    r->Modified();
    r->Update();
    EXPECT_TRUE(obs->GetError()) << expect;
    EXPECT_NE(obs->GetErrorMessage().find(expect), std::string::npos)
      << "message: " << obs->GetErrorMessage();
    EXPECT_EQ(r->GetOutput()->GetNumberOfPoints(), 0);
  };
  {
    vtkNew<vtkReferenceRenderer> r; // no camera
    r->SetInputData(medium);
    r->SetImageSize(4, 4);
    run(r, "SetCamera");
  }
  {
    Voxel bad = good;
    bad.Albedo[1] = 2.0;
    auto badMedium = Homogeneous(dims, spacing, origin, bad);
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(badMedium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->SetImageSize(4, 4);
    run(r, "Albedo");
  }
  {
    vtkNew<vtkImageData> notMedium; // scalars but no medium array
    notMedium->SetDimensions(3, 3, 3);
    notMedium->AllocateScalars(VTK_FLOAT, 1);
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(notMedium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->SetImageSize(4, 4);
    run(r, "not a valid Refracta medium");
  }
  {
    vtkNew<vtkImageData> env;
    env->SetDimensions(4, 2, 1);
    env->AllocateScalars(VTK_FLOAT, 2);
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->SetEnvironmentMap(env);
    r->SetImageSize(4, 4);
    run(r, "EnvironmentMap");
  }
  {
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    const double badUp[3] = { 0, 0, 1 };
    r->SetCamera(ParallelCamera(focal, dop, badUp, 1.0));
    r->SetImageSize(4, 4);
    run(r, "view up");
  }
  {
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->SetBackgroundColor(-1, 0, 0);
    r->SetImageSize(4, 4);
    run(r, "BackgroundColor");
  }
  {
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    vtkNew<vtkLight> degenerate; // directional, position == focal point
    degenerate->PositionalOff();
    degenerate->SetPosition(1, 2, 3);
    degenerate->SetFocalPoint(1, 2, 3);
    r->AddLight(degenerate);
    r->SetImageSize(4, 4);
    run(r, "direction is undefined");
  }
  // TraceRay on an invalid medium.
  {
    vtkNew<vtkReferenceRenderer> r;
    vtkNew<vtkTest::ErrorObserver> obs;
    r->AddObserver(vtkCommand::ErrorEvent, obs);
    vtkNew<vtkImageData> empty;
    const double o[3] = { 0, 0, 0 }, d[3] = { 1, 0, 0 };
    double e[3], ed[3];
    EXPECT_EQ(r->TraceRay(empty, o, d, 1.0, e, ed), -1);
    EXPECT_TRUE(obs->GetError());
  }
  // Clamped settings.
  vtkNew<vtkReferenceRenderer> r;
  r->SetImageSize(0, -3);
  EXPECT_EQ(r->GetImageSize()[0], 1);
  EXPECT_EQ(r->GetImageSize()[1], 1);
  r->SetSamplesPerPixel(0);
  EXPECT_EQ(r->GetSamplesPerPixel(), 1);
}
