#include "vtkRefractaViewPassOccupancy.h"

#include <algorithm>
#include <cstddef>

namespace vtkRefractaViewPassDetail
{
namespace
{
int FloorDiv(int a, int b)
{
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}
}

// Sets `flag` in flags[i] for every tuple i of `values` (`comps` per tuple) with a nonzero value.
void MarkNonzero(
  const float* values, int comps, std::uint8_t flag, std::vector<std::uint8_t>& flags)
{
  const std::size_t n = flags.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int c = 0; c < comps; ++c)
    {
      if (values[i * comps + c] != 0.0f)
      {
        flags[i] |= flag;
        break;
      }
    }
  }
}

MacroCellGrid BuildMacroCellGrid(const int dims[3], int b,
  const std::vector<std::uint8_t>& mediumFlags, const std::vector<std::uint8_t>& lightingFlags)
{
  MacroCellGrid grid;
  int cells[3];
  for (int a = 0; a < 3; ++a)
  {
    cells[a] = (dims[a] + b - 1) / b;
    grid.CellDims[a] = cells[a];
  }
  const std::size_t numberOfCells = static_cast<std::size_t>(cells[0]) * cells[1] * cells[2];
  std::vector<std::uint8_t>& occupancy = grid.Cells;
  occupancy.assign(numberOfCells, 0);
  const bool lit = !lightingFlags.empty();
  // Per axis, the range of cells whose dilated voxel range [c b - 2, (c + 1) b + 1] holds v.
  auto cellRange = [&](int v, int a, int& lo, int& hi)
  {
    lo = std::max(0, -FloorDiv(-(v - b - 1), b)); // ceil((v - b - 1) / b)
    hi = std::min(cells[a] - 1, FloorDiv(v + 2, b));
  };
  for (int k = 0; k < dims[2]; ++k)
  {
    int k0, k1;
    cellRange(k, 2, k0, k1);
    for (int j = 0; j < dims[1]; ++j)
    {
      int j0, j1;
      cellRange(j, 1, j0, j1);
      const std::size_t row =
        static_cast<std::size_t>(dims[0]) * (j + static_cast<std::size_t>(dims[1]) * k);
      for (int i = 0; i < dims[0]; ++i)
      {
        const std::uint8_t f =
          mediumFlags[row + i] | (lit ? lightingFlags[row + i] : std::uint8_t(0));
        if (!f)
        {
          continue;
        }
        int i0, i1;
        cellRange(i, 0, i0, i1);
        for (int ck = k0; ck <= k1; ++ck)
        {
          for (int cj = j0; cj <= j1; ++cj)
          {
            for (int ci = i0; ci <= i1; ++ci)
            {
              occupancy[ci +
                static_cast<std::size_t>(cells[0]) *
                  (cj + static_cast<std::size_t>(cells[1]) * ck)] |= f;
            }
          }
        }
      }
    }
  }
  // Counts and bounding boxes (in cells) of the active cells, for straight rays (SourceFlag)
  // and curved ones (either flag).
  std::size_t source = 0, either = 0;
  for (int m = 0; m < 2; ++m)
  {
    for (int a = 0; a < 3; ++a)
    {
      grid.ActiveLo[m][a] = cells[a];
      grid.ActiveHi[m][a] = -1;
    }
  }
  for (int ck = 0; ck < cells[2]; ++ck)
  {
    for (int cj = 0; cj < cells[1]; ++cj)
    {
      for (int ci = 0; ci < cells[0]; ++ci)
      {
        const std::uint8_t c = occupancy[ci +
          static_cast<std::size_t>(cells[0]) * (cj + static_cast<std::size_t>(cells[1]) * ck)];
        const int ijk[3] = { ci, cj, ck };
        for (int m = 0; m < 2; ++m)
        {
          if (c & (m == 0 ? SourceFlag : (SourceFlag | GradientFlag)))
          {
            (m == 0 ? source : either) += 1;
            for (int a = 0; a < 3; ++a)
            {
              grid.ActiveLo[m][a] = std::min(grid.ActiveLo[m][a], ijk[a]);
              grid.ActiveHi[m][a] = std::max(grid.ActiveHi[m][a], ijk[a]);
            }
          }
        }
      }
    }
  }
  grid.ActiveFraction[0] = static_cast<double>(source) / numberOfCells;
  grid.ActiveFraction[1] = static_cast<double>(either) / numberOfCells;
  return grid;
}
}
