// BenchmarkGlassOpticsShaft.cxx: BenchmarkGlassOptics --shaft, the light shaft below the ball in
// the default scene's fog against ideal optics (what it measures: BenchmarkGlassOptics.cxx).
#include "BenchmarkGlassOptics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace glass_optics
{
namespace
{
// The heights of the table's rows.
const double TableHeights[] = { -0.40, -0.45, -0.50, -0.55, -0.60, -0.65, -0.70, -0.75 };

// Fluence planes every 0.01 from just below the ball (y = -0.38) to just above the floor.
std::vector<double> PlaneHeights()
{
  std::vector<double> heights;
  for (int k = 0; k < 42; ++k)
  {
    heights.push_back(-0.38 - 0.01 * k);
  }
  return heights;
}

// The image row through the axis point (0, y, 0) and its pixels per world unit there; -1 when
// the ball hides that point.
int AxisRow(const View& view, double y, double& pixelsPerUnit)
{
  double x0, y0, x1, y1;
  view.Project({ -0.05, y, 0.0 }, x0, y0);
  view.Project({ 0.05, y, 0.0 }, x1, y1);
  pixelsPerUnit = (x1 - x0) / 0.1;
  const int row = static_cast<int>(0.5 * (y0 + y1));
  return view.SeesBall(view.Size / 2, row) ? -1 : row;
}

} // namespace

// Measures and prints the shaft; returns whether every render ran. `narrowMet[m]` (m = 0 exact,
// 1 smoothed): whether every visible row's image FWHM from y = -0.45 down is within 1.5x of
// ideal (the shaft narrows to the focus as the optics say). `lightMet[m]` (m = 0 exact,
// 1 smoothed): whether the render's shaft holds the ideal single-scattered light, every visible
// row from y = -0.45 down summing to within 20% of ideal (meaningful without multiple
// scattering, --single: the lattice adds about 30% there).
bool MeasureShaft(const Settings& s, const View& view, bool lightMet[2], bool narrowMet[2])
{
  const std::vector<double> heights = PlaneHeights();
  IdealShaft ideal(view, Fog(), heights, 0.002, 0.45, 0.11);
  TraceThroughBall(s.ShaftRays, 6, Fog().Extinction, [&](const Beam& b) { ideal.AddToPlanes(b); });
  TraceThroughBall(
    s.ShaftImageRays, 6, Fog().Extinction, [&](const Beam& b) { ideal.AddToImage(b); });
  ideal.Finish();

  Scene scene{ true, true, true, true, true };
  const Render opaque = RenderScene(s, scene);
  scene.OpaqueBall = false;
  const Render exact = RenderScene(s, scene);
  scene.Exact = false;
  const Render smoothed = RenderScene(s, scene);
  if (opaque.Image.empty() || exact.Image.empty() || smoothed.Image.empty())
  {
    return false;
  }
  scene.Exact = true;
  scene.Seed = 2;
  const Render reseeded = RenderScene(s, scene);
  const std::vector<double> images[3] = { ideal.Image, RedDifference(exact.Image, opaque.Image),
    RedDifference(smoothed.Image, opaque.Image) };
  double x, top, bottom; // the noise's rows: y = -0.45 to -0.75 on the axis
  view.Project({ 0.0, -0.45, 0.0 }, x, top);
  view.Project({ 0.0, -0.75, 0.0 }, x, bottom);
  const double noise =
    PairNoise(ideal.Image, images[1], RedDifference(reseeded.Image, opaque.Image), view.Size,
      static_cast<int>(std::ceil(bottom)), static_cast<int>(top));
  const double h = exact.Lighting.Spacing[0];
  std::printf("\nThe light shaft below the ball: the default scene with its fog and a black floor; "
              "rendered = glass ball - black opaque ball (S1 by photons in both), %.0f s + %.0f s "
              "+ %.0f s. Ideal: %d^2 light rays (fluence, 0.002 cells), %d^2 (image).\n\n",
    opaque.Seconds, exact.Seconds, smoothed.Seconds, s.ShaftRays, s.ShaftImageRays);
  std::printf("Image rows through the axis point (0, y, 0): FWHM across the row, pixels (world "
              "units at the axis); the row's sum over its middle half, rendered / %g over ideal\n\n"
              "| y | row | ideal | exact | smoothed | sum exact / ideal | sum smoothed / ideal "
              "|\n|---|---|---|---|---|---|---|\n",
    LightIntensity);
  int rowsChecked = 0;
  for (double y : TableHeights)
  {
    double ppu;
    const int row = AxisRow(view, y, ppu);
    if (row < 0)
    {
      std::printf("| %.2f | behind the ball | | | | | |\n", y);
      continue;
    }
    std::printf("| %.2f | %d |", y, row);
    double sums[3] = { 0, 0, 0 }, widths[3] = { 0, 0, 0 };
    for (int m = 0; m < 3; ++m)
    {
      const std::vector<double> line = ImageRow(images[m], view.Size, row);
      const double w = ProfileFwhm(line, 1.0, view.Size / 4);
      std::printf(" %.1f (%.3f) |", w, w / ppu);
      widths[m] = w;
      for (int i = view.Size / 4; i < 3 * view.Size / 4; ++i)
      {
        sums[m] += line[i] / (m ? LightIntensity : 1.0);
      }
    }
    std::printf(" %.2f | %.2f |\n", sums[1] / sums[0], sums[2] / sums[0]);
    rowsChecked += y < -0.44;
    for (int m = 0; m < 2 && y < -0.44; ++m)
    {
      lightMet[m] = lightMet[m] && std::abs(sums[m + 1] / sums[0] - 1.0) <= 0.2;
      narrowMet[m] = narrowMet[m] && widths[m + 1] <= 1.5 * widths[0];
    }
  }
  for (int m = 0; m < 2; ++m)
  {
    lightMet[m] = lightMet[m] && rowsChecked > 0;
    narrowMet[m] = narrowMet[m] && rowsChecked > 0;
  }
  std::printf("\nFluence below the ball (S1 = sigma_s phi of the lighting grid, spacing h = %.4f): "
              "r50 = radius holding half of phi's integral over the plane y within 0.44 of the "
              "axis; FWHM of phi along x at z = 0 (ideal: on a lattice of spacing h, h / 2, h / 4, "
              "voxel means and (1, 2, 1) smoothing)\n\n| y | r50 ideal | r50 exact | r50 smoothed "
              "| FWHM ideal, h | h / 2 | h / 4 | FWHM exact | FWHM smoothed |\n"
              "|---|---|---|---|---|---|---|---|---|\n",
    h);
  double narrowest[3] = { 1e9, 1e9, 1e9 }, at[3] = { 0, 0, 0 };
  for (int k = 0; k < static_cast<int>(heights.size()); ++k)
  {
    const double y = heights[k];
    const double r50[3] = { ideal.EncircledRadius(k, 0.5),
      LatticeHalfRadius(exact.Lighting, opaque.Lighting, y),
      LatticeHalfRadius(smoothed.Lighting, opaque.Lighting, y) };
    for (int m = 0; m < 3; ++m)
    {
      if (r50[m] < narrowest[m])
      {
        narrowest[m] = r50[m];
        at[m] = y;
      }
    }
    if (k == 0 || k % 5 == 2)
    {
      std::printf("| %.2f | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f |\n", y, r50[0],
        r50[1], r50[2], ProfileFwhm(ideal.ProfileOnLattice(k, h), h, 100),
        ProfileFwhm(ideal.ProfileOnLattice(k, h / 2), h / 2, 200),
        ProfileFwhm(ideal.ProfileOnLattice(k, h / 4), h / 4, 400),
        ProfileFwhm(LatticeProfile(exact.Lighting, opaque.Lighting, y), h, 100),
        ProfileFwhm(LatticeProfile(smoothed.Lighting, opaque.Lighting, y), h, 100));
    }
  }
  std::printf("\nNoise of the exact interfaces' shaft (two photon seeds; RMS of their difference "
              "/ sqrt 2 over the mean, pixels of the rows y = -0.45 to -0.75 where the ideal "
              "image exceeds 10%% of its row's peak): %.1f%%; photon pass %.1f s (volume caustic "
              "%d^3)\n",
    100 * noise, exact.LightSeconds, exact.VolumeCaustic);
  std::printf("\nNarrowest r50 (planes every 0.01): ideal %.4f at y = %.2f, exact %.4f at %.2f, "
              "smoothed %.4f at %.2f\n",
    narrowest[0], at[0], narrowest[1], at[1], narrowest[2], at[2]);
  std::printf("Direct light left in the difference (mean |S1 glass - S1 opaque| 0.55 to 0.75 from "
              "the axis at y = -0.6, over its peak there): exact %.4f, smoothed %.4f\n",
    DirectLightResidual(exact.Lighting, opaque.Lighting),
    DirectLightResidual(smoothed.Lighting, opaque.Lighting));
  return true;
}
}
