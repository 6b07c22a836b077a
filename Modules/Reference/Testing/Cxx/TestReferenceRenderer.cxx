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
