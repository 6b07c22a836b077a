// Private to vtkLatticeBoltzmannSolver*.cxx: the lattice's direction table and work-group shape,
// shared by the solver's setup and iteration (vtkLatticeBoltzmannSolver.cxx) and its books and
// analytic lengths (vtkLatticeBoltzmannSolverBooks.cxx).
#ifndef vtkLatticeBoltzmannSolverInternals_h
#define vtkLatticeBoltzmannSolverInternals_h

#include <cstddef>

namespace refracta_lbm
{
// Lattice directions in opposite pairs, the same table as Kernels/lbl.cl.
constexpr int Cx[18] = { 1, -1, 0, 0, 0, 0, 1, -1, 1, -1, 1, -1, 1, -1, 0, 0, 0, 0 };
constexpr int Cy[18] = { 0, 0, 1, -1, 0, 0, 1, -1, -1, 1, 0, 0, 0, 0, 1, -1, 1, -1 };
constexpr int Cz[18] = { 0, 0, 0, 0, 1, -1, 0, 0, 0, 0, 1, -1, -1, 1, 1, -1, -1, 1 };

// One x-row per work-group (measured 2.5x faster than PoCL's default shape on the CPU).
inline size_t LocalRow(int nx)
{
  size_t l = 1;
  while (l < static_cast<size_t>(nx) && l < 128)
  {
    l <<= 1;
  }
  return l;
}
}

#endif
