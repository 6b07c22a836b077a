/**
 * @file    RefractaShaftMeasures.h
 * @brief   Widths of lines and of the light shaft in a lighting volume (BenchmarkGlassOptics,
 *          issue 20): the FWHM of a sampled line, and the shaft below the ball as the difference
 *          of two lighting volumes' single scattering S1 = sigma_s phi on the same lattice.
 */
#ifndef RefractaShaftMeasures_h
#define RefractaShaftMeasures_h

#include <vector>

class vtkImageData;

namespace RefractaShaftMeasures
{
/// Width of the run of values >= half of values[peak] around `peak` (ends linear between the
/// last sample above and the first below; a negative sample counts as the line's end).
double Fwhm(const std::vector<double>& values, int peak);

/// FWHM (in units of `h`, the sample spacing) of the largest peak of `values` within `reach`
/// samples of the middle; negative values (noise of a difference) count as 0. 0: no peak.
double ProfileFwhm(std::vector<double> values, double h, int reach);

/// Row `row` of a size x size image of doubles (row 0 first).
std::vector<double> ImageRow(const std::vector<double>& image, int size, int row);

/// The red channel of RGBA image `a` minus that of `b` (empty when their sizes differ).
std::vector<double> RedDifference(const std::vector<float>& a, const std::vector<float>& b);

/// One channel of a lighting volume's S1 (vtkRefractaLightingVolume::RadianceName()) on its
/// lattice (point data: x fastest).
struct ScatteringLattice
{
  std::vector<float> S1;
  double Origin[3] = { 0, 0, 0 }, Spacing[3] = { 1, 1, 1 };
  int Dimensions[3] = { 0, 0, 0 };
};

/// S1 (red) of a lighting volume on a lattice `factor` times finer than its grid: each fine point
/// takes its voxel's Radiance plus, where the voxel has a volume-caustic brick
/// (vtkRefractaLightingVolume::VolumeCaustic*Name()), the brick's fine voxel at that point, so
/// the bricks' light is measured at their resolution. Empty without a Radiance array.
ScatteringLattice FineScatteringLattice(vtkImageData* lighting, int factor);

/// Noise of two renders of one quantity: the RMS of (a - b) / sqrt 2 over the mean of (a + b) / 2
/// (size x size images of doubles, row 0 first), on the pixels of rows firstRow..lastRow where
/// `mask` exceeds 10% of its row's peak. 0 when no pixel qualifies.
double PairNoise(const std::vector<double>& mask, const std::vector<double>& a,
  const std::vector<double>& b, int size, int firstRow, int lastRow);

/// S1 of `r` minus S1 of `reference` along the lattice's x at (y, z = 0), linear in y and z,
/// over |x| < 0.44. Empty when the lattices differ.
std::vector<double> LatticeProfile(
  const ScatteringLattice& r, const ScatteringLattice& reference, double y);

/// The radius about the axis (x = z = 0) within which the layer y of S1(r) - S1(reference)
/// (linear in y) holds half its integral over the points within 0.44 of the axis, each point's
/// value spread over its voxel's square (8 x 8 sub-points in rings of 0.001). 0 when undefined.
double LatticeHalfRadius(const ScatteringLattice& r, const ScatteringLattice& reference, double y);

/// How well the difference isolates the shaft: the mean |S1(r) - S1(reference)| over the directly
/// lit points 0.55 to 0.75 from the axis at y = -0.6 (outside the ball's shadow, inside the
/// spot), over the largest difference in that layer.
double DirectLightResidual(const ScatteringLattice& r, const ScatteringLattice& reference);
}

#endif
