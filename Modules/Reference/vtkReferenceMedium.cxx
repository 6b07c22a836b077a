#include "vtkReferenceMedium.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"

namespace refracta
{
namespace reference
{
void Medium::BuildBlockMajorants()
{
  BlockMajorant.assign(3 * static_cast<size_t>(NB[0]) * NB[1] * NB[2], 0.0);
  auto at = [this](const std::vector<double>& v, int64_t id)
  { return &v[v.size() == 3 ? 0 : 3 * id]; };
  for (int bz = 0; bz < NB[2]; ++bz)
  {
    for (int by = 0; by < NB[1]; ++by)
    {
      for (int bx = 0; bx < NB[0]; ++bx)
      {
        const int b[3] = { bx, by, bz };
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a)
        {
          // Points within one voxel of the block region [bB, (b+1)B] interpolate voxels
          // bB - 1 .. (b+1)B + 2.
          lo[a] = std::max(b[a] * BlockSize - 1, 0);
          hi[a] = std::min((b[a] + 1) * BlockSize + 2, N[a] - 1);
        }
        double m[3] = { 0, 0, 0 };
        bool emission = false;
        for (int k = lo[2]; k <= hi[2]; ++k)
        {
          for (int j = lo[1]; j <= hi[1]; ++j)
          {
            for (int i = lo[0]; i <= hi[0]; ++i)
            {
              const int64_t id = i + N[0] * (j + static_cast<int64_t>(N[1]) * k);
              const double* sg = at(Sigma, id);
              const double* e = at(Emission, id);
              for (int c = 0; c < 3; ++c)
              {
                m[c] = std::max(m[c], sg[c]);
                emission = emission || e[c] > 0;
              }
            }
          }
        }
        if (emission)
        {
          // Emission is estimated at tentative collisions: at least 4 per smallest spacing.
          for (int c = 0; c < 3; ++c)
          {
            m[c] = std::max(m[c], 4.0 / MinSpacing);
          }
        }
        if (Grey)
        {
          m[0] = m[1] = m[2] = std::max(m[0], std::max(m[1], m[2]));
        }
        double* out = &BlockMajorant[3 * (bx + NB[0] * (by + static_cast<size_t>(NB[1]) * bz))];
        out[0] = m[0];
        out[1] = m[1];
        out[2] = m[2];
      }
    }
  }
}

void Medium::BuildFlatBlocks()
{
  Flat.clear();
  if (StraightRays || (Index.size() == 1 && Gradient.size() == 3))
  {
    return; // everything straight, or a uniform non-zero gradient: nothing flat to skip
  }
  Flat.assign(static_cast<size_t>(NB[0]) * NB[1] * NB[2], 0);
  auto nAt = [this](int64_t id) { return Index.size() == 1 ? Index[0] : Index[id]; };
  auto gAt = [this](int64_t id) { return &Gradient[Gradient.size() == 3 ? 0 : 3 * id]; };
  for (int bz = 0; bz < NB[2]; ++bz)
  {
    for (int by = 0; by < NB[1]; ++by)
    {
      for (int bx = 0; bx < NB[0]; ++bx)
      {
        const int b[3] = { bx, by, bz };
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a)
        {
          lo[a] = b[a] * BlockSize;
          hi[a] = std::min((b[a] + 1) * BlockSize, N[a] - 1);
        }
        const double n0 = nAt(lo[0] + N[0] * (lo[1] + static_cast<int64_t>(N[1]) * lo[2]));
        bool flat = true;
        for (int k = lo[2]; k <= hi[2] && flat; ++k)
        {
          for (int j = lo[1]; j <= hi[1] && flat; ++j)
          {
            for (int i = lo[0]; i <= hi[0] && flat; ++i)
            {
              const int64_t id = i + N[0] * (j + static_cast<int64_t>(N[1]) * k);
              const double* g = gAt(id);
              flat = nAt(id) == n0 && g[0] == 0 && g[1] == 0 && g[2] == 0;
            }
          }
        }
        Flat[bx + NB[0] * (by + static_cast<size_t>(NB[1]) * bz)] = flat ? 1 : 0;
      }
    }
  }
}

Vec3 Medium::ToLocalPoint(const double p[3]) const
{
  double r[3];
  Grid->WorldToLocalPoint(p, r);
  return ToVec3(r);
}

Vec3 Medium::ToLocalVector(const double v[3]) const
{
  double r[3];
  Grid->WorldToLocalVector(v, r);
  return ToVec3(r);
}

Vec3 Medium::ToWorldVector(const Vec3& v) const
{
  const double in[3] = { v.x, v.y, v.z };
  double r[3];
  Grid->LocalToWorldVector(in, r);
  return ToVec3(r);
}

Vec3 Medium::ToWorldPoint(const Vec3& v) const
{
  const double in[3] = { v.x, v.y, v.z };
  double r[3];
  Grid->LocalToWorldPoint(in, r);
  return ToVec3(r);
}

// Copies the arrays (defaults where missing) and derives the flags. `medium` was validated.
void Medium::Load(vtkImageData* medium)
{
  int dims[3];
  medium->GetDimensions(dims);
  medium->GetSpacing(S);
  Grid->SetImage(medium);
  for (int a = 0; a < 3; ++a)
  {
    N[a] = dims[a];
    Lo[a] = -0.5 * S[a];
    Hi[a] = (N[a] - 0.5) * S[a];
  }
  MinSpacing = std::min(S[0], std::min(S[1], S[2]));
  Diagonal = glm::length(Hi - Lo);
  const int64_t n = static_cast<int64_t>(N[0]) * N[1] * N[2];
  vtkPointData* pd = medium->GetPointData();
  // A missing array, or one whose tuples are all equal, is kept as a single tuple: memory
  // (8 bytes per component per voxel otherwise) and a faster lookup.
  auto shrinkIfUniform = [n](std::vector<double>& out, int nc)
  {
    for (int64_t i = 1; i < n; ++i)
    {
      for (int c = 0; c < nc; ++c)
      {
        if (out[i * nc + c] != out[c])
        {
          return;
        }
      }
    }
    out.resize(nc);
    out.shrink_to_fit();
  };
  auto load = [&](int id, std::vector<double>& out) -> bool
  {
    const int nc = vtkRefractaMedium::GetNumberOfComponents(id);
    vtkDataArray* arr = pd->GetArray(vtkRefractaMedium::GetArrayName(id));
    if (!arr)
    {
      out.assign(nc, vtkRefractaMedium::GetDefaultValue(id));
      return false;
    }
    out.resize(static_cast<size_t>(n * nc));
    for (int64_t i = 0; i < n; ++i)
    {
      for (int c = 0; c < nc; ++c)
      {
        out[i * nc + c] = arr->GetComponent(i, c);
      }
    }
    shrinkIfUniform(out, nc);
    return true;
  };
  load(vtkRefractaMedium::REFRACTIVE_INDEX, Index);
  const bool hasGradient = load(vtkRefractaMedium::REFRACTIVE_INDEX_GRADIENT, Gradient);
  load(vtkRefractaMedium::EXTINCTION, Sigma);
  load(vtkRefractaMedium::ALBEDO, Albedo);
  load(vtkRefractaMedium::ANISOTROPY, G);
  load(vtkRefractaMedium::EMISSION, Emission);

  if (!hasGradient && Index.size() == 1)
  {
    Gradient.assign(3, 0.0);
  }
  else if (!hasGradient)
  {
    // Per-voxel central differences of n (one-sided at the edge voxels, 0 along an axis with a
    // single voxel), interpolated trilinearly afterwards like any other array.
    Gradient.assign(static_cast<size_t>(3 * n), 0.0);
    for (int k = 0; k < N[2]; ++k)
    {
      for (int j = 0; j < N[1]; ++j)
      {
        for (int i = 0; i < N[0]; ++i)
        {
          const int ijk[3] = { i, j, k };
          const int64_t id = i + N[0] * (j + static_cast<int64_t>(N[1]) * k);
          for (int a = 0; a < 3; ++a)
          {
            if (N[a] < 2)
            {
              continue;
            }
            int lo[3] = { i, j, k }, hi[3] = { i, j, k };
            lo[a] = std::max(ijk[a] - 1, 0);
            hi[a] = std::min(ijk[a] + 1, N[a] - 1);
            const int64_t il = lo[0] + N[0] * (lo[1] + static_cast<int64_t>(N[1]) * lo[2]);
            const int64_t ih = hi[0] + N[0] * (hi[1] + static_cast<int64_t>(N[1]) * hi[2]);
            Gradient[3 * id + a] = (Index[ih] - Index[il]) / ((hi[a] - lo[a]) * S[a]);
          }
        }
      }
    }
    shrinkIfUniform(Gradient, 3);
  }
  auto at = [](const std::vector<double>& v, int nc, int64_t i)
  { return &v[v.size() == static_cast<size_t>(nc) ? 0 : i * nc]; };
  const int64_t nIndex = static_cast<int64_t>(Index.size());
  const int64_t nGrad = static_cast<int64_t>(Gradient.size()) / 3;
  StraightRays = true;
  NMax = 1;
  for (int64_t i = 0; i < nIndex; ++i)
  {
    NMax = std::max(NMax, Index[i]);
    StraightRays = StraightRays && Index[i] == Index[0];
  }
  for (int64_t i = 0; i < nGrad; ++i)
  {
    const double* g = at(Gradient, 3, i);
    StraightRays = StraightRays && g[0] == 0 && g[1] == 0 && g[2] == 0;
  }
  Grey = true;
  HasEmission = false;
  for (int64_t i = 0; i < n; ++i)
  {
    const double* s = at(Sigma, 3, i);
    const double* a = at(Albedo, 3, i);
    const double* e = at(Emission, 3, i);
    if (s[0] != s[1] || s[0] != s[2] || a[0] != a[1] || a[0] != a[2])
    {
      Grey = false;
    }
    for (int c = 0; c < 3; ++c)
    {
      HasEmission = HasEmission || e[c] > 0;
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    NB[a] = std::max(1, (N[a] - 1 + BlockSize - 1) / BlockSize);
  }
  BuildFlatBlocks();
  BuildBlockMajorants();
}
} // namespace reference
} // namespace refracta
