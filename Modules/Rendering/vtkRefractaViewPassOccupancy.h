// Private to vtkRefractaViewPass (not installed): the host side of empty-space skipping. Voxels
// are flagged where something can change a view ray, and macro cells of b^3 voxels take the OR of
// the flags over their voxels dilated by two voxels (the kernel, view_pass.cl with
// REFRACTA_SKIP, jumps over runs of empty cells).
#ifndef vtkRefractaViewPassOccupancy_h
#define vtkRefractaViewPassOccupancy_h

#include <cstdint>
#include <vector>

namespace vtkRefractaViewPassDetail
{
// Per-voxel flags for empty-space skipping (view_pass.cl, REFRACTA_SKIP).
constexpr std::uint8_t SourceFlag = 1; // extinction, emission, Radiance or MultipleScattering != 0
constexpr std::uint8_t GradientFlag = 2; // grad n != 0 (only where rays may bend)

// Sets `flag` in flags[i] for every tuple i of `values` (`comps` per tuple) with a nonzero value.
void MarkNonzero(
  const float* values, int comps, std::uint8_t flag, std::vector<std::uint8_t>& flags);
inline void MarkNonzero(
  const std::vector<float>& values, int comps, std::uint8_t flag, std::vector<std::uint8_t>& flags)
{
  MarkNonzero(values.data(), comps, flag, flags);
}

// The macro-cell occupancy of a grid of `dims` voxels for cells of b^3 voxels, with the active
// cells' counts and bounding boxes for straight rays (mask 0: SourceFlag) and curved rays
// (mask 1: either flag).
struct MacroCellGrid
{
  std::vector<std::uint8_t> Cells; // one byte per cell, x fastest
  int CellDims[3] = { 0, 0, 0 };
  double ActiveFraction[2] = { 1.0, 1.0 };
  int ActiveLo[2][3] = { { 0, 0, 0 }, { 0, 0, 0 } };
  int ActiveHi[2][3] = { { -1, -1, -1 }, { -1, -1, -1 } };
};

// Cell c (per axis) covers continuous voxel coordinates [c b - 1/2, (c + 1) b - 1/2); a trilinear
// sample there reads voxels c b - 1 .. (c + 1) b, and a sample up to one voxel outside it reads
// c b - 2 .. (c + 1) b + 1: the cell takes the OR of the flags over that range, so the kernel's
// eps nudges and rounding stay safe. `lightingFlags` may be empty (no lighting volume).
MacroCellGrid BuildMacroCellGrid(const int dims[3], int b,
  const std::vector<std::uint8_t>& mediumFlags, const std::vector<std::uint8_t>& lightingFlags);
}

#endif
