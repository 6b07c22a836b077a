/**
 * Internal to RefractaReference (a private header: not wrapped, not installed). The background of
 * the reference renderer: a uniform colour or an equirectangular environment map (looked up with
 * vtkRefractaEnvironmentMap, world directions), and, when it illuminates the scene, its sampling
 * for next-event estimation.
 *
 * Sampling, importance by luminance: texel (i, j) of the map (the cell [i, i + 1) / W x
 * [j, j + 1) / H of (u, v)) has the weight Omega_j * Y_ij, where Omega_j is its solid angle
 * (2 pi / W) (sin(lat_j+1) - sin(lat_j)) and Y_ij the largest Rec. 709 luminance over the texel
 * and its eight neighbours (wrapping in u, clamped in v): the bilinear radiance inside a cell is a
 * convex combination of those texels, so the pdf is positive wherever the radiance is. A texel is
 * drawn from its weight (rows, then columns, by binary search of the cumulative sums), then a
 * direction uniformly in its solid angle (u uniform, sin(lat) uniform), so the solid-angle pdf is
 * weight / (total weight * Omega_j), exact also near the poles. A uniform colour is sampled
 * uniformly over the sphere (pdf 1 / (4 pi)).
 */
#ifndef vtkReferenceEnvironment_h
#define vtkReferenceEnvironment_h

#include "vtkReferenceMath.h"

#include <vector>

namespace refracta
{
namespace reference
{
struct Environment
{
  Vec3 Colour = Vec3(0.0); // uniform radiance when there is no map
  // Map: linear RGB, row major, row 0 the v = 0 (-up) pole; W = 0 when there is none.
  std::vector<double> Rgb;
  int W = 0, H = 0;
  double Up[3] = { 0, 1, 0 }, Right[3] = { 1, 0, 0 }; // world vectors orienting the map
  // A procedural checkerboard (vtkRefractaEnvironmentMap::MakeChecker): Radiance evaluates it
  // exactly; the map (its texels' area means) still drives the sampling. Squares 0: none.
  int CheckerSquares[2] = { 0, 0 };
  double Checker1[3] = { 0, 0, 0 }, Checker2[3] = { 0, 0, 0 };

  // Radiance arriving from the world direction d (any length > 0).
  Vec3 Radiance(const Vec3& dWorld) const;

  // Prepares the sampling tables. False when the background is black (nothing to sample).
  bool BuildSampling();

  // A world direction drawn from the sampling distribution with four uniform numbers.
  Vec3 Sample(double u1, double u2, double u3, double u4) const;

  // Solid-angle pdf of Sample at the unit world direction d.
  double Pdf(const Vec3& dWorld) const;

private:
  std::vector<double> RowCdf;                       // H + 1 cumulative row weights, RowCdf[0] = 0
  std::vector<double> CellCdf;                      // H (W + 1): per row, cumulative cell weights
  std::vector<double> Weight;                       // W H cell weights
  std::vector<double> SinLat;                       // H + 1: sin of the latitude of the row edges
  double Basis[9] = { 1, 0, 0, 0, 1, 0, 0, 0, -1 }; // right, up, front (rows)
};
} // namespace reference
} // namespace refracta

#endif
