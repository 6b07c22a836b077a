/**
 * Internal to RefractaReference (a private header: not wrapped, not installed). The pieces of
 * the volumetric photon mapper (vtkReferencePhotonMapper) on top of the path tracer's Scene:
 * photons emitted by the same lights (and the background when it illuminates) and traced through
 * the same curved-ray integrator, delta tracking, surfaces and Russian roulette; the photons of a
 * pass stored at their real collisions in the medium and sorted into a hashed uniform grid; and
 * the view sample, which follows the path tracer's view path up to its first real collision in
 * the medium and there estimates the in-scattered radiance from the photons within a sphere of
 * radius r (point-point 3D kernel, Jarosz et al. 2011).
 */
#ifndef vtkReferencePhotonMap_h
#define vtkReferencePhotonMap_h

#include "vtkReferencePathTracer.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace refracta
{
namespace reference
{
// A photon at a real collision in the medium.
struct Photon
{
  Vec3 X = Vec3(0.0);       // position, grid-local
  Vec3 Dir = Vec3(0.0);     // unit travel direction on arrival
  Vec3 Fluence = Vec3(0.0); // power / sigma_t(X) per channel: its share of the fluence x volume
  int Depth = 0;            // scattering and reflection events before this collision
};

// The photons of one pass in a hashed uniform grid of cells 2 r wide (a sphere of radius r meets
// at most 2 x 2 x 2 cells), sorted by bucket (counting sort); buckets that two queried cells share
// are visited once.
class PhotonGrid
{
public:
  void Build(std::vector<Photon>&& photons, const Vec3& lo, double radius);

  // Calls f(photon) for every photon within the radius of x.
  template <class F>
  void ForEachWithin(const Vec3& x, F&& f) const
  {
    if (Sorted.empty())
    {
      return;
    }
    int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = Cell(x[a] - Radius, a);
      hi[a] = Cell(x[a] + Radius, a);
    }
    size_t buckets[8];
    int n = 0;
    for (int64_t k = lo[2]; k <= hi[2]; ++k)
    {
      for (int64_t j = lo[1]; j <= hi[1]; ++j)
      {
        for (int64_t i = lo[0]; i <= hi[0]; ++i)
        {
          const size_t b = Bucket(i, j, k);
          bool seen = false;
          for (int q = 0; q < n; ++q)
          {
            seen = seen || buckets[q] == b;
          }
          if (!seen && n < 8)
          {
            buckets[n++] = b;
          }
        }
      }
    }
    const double r2 = Radius * Radius;
    for (int q = 0; q < n; ++q)
    {
      for (uint32_t p = Start[buckets[q]]; p < Start[buckets[q] + 1]; ++p)
      {
        const Vec3 d = Sorted[p].X - x;
        if (glm::dot(d, d) <= r2)
        {
          f(Sorted[p]);
        }
      }
    }
  }

  size_t Size() const { return Sorted.size(); }

private:
  int64_t Cell(double v, int axis) const
  {
    return static_cast<int64_t>(std::floor((v - Lo[axis]) * InvCell));
  }
  size_t Bucket(int64_t i, int64_t j, int64_t k) const
  {
    // Teschner et al. 2003, on the cell coordinates.
    const uint64_t h = (static_cast<uint64_t>(i) * 73856093ULL) ^
      (static_cast<uint64_t>(j) * 19349663ULL) ^ (static_cast<uint64_t>(k) * 83492791ULL);
    return static_cast<size_t>(Mix64(h) & Mask);
  }

  std::vector<Photon> Sorted;
  std::vector<uint32_t> Start; // Mask + 2 entries: bucket b holds Sorted[Start[b], Start[b + 1])
  Vec3 Lo = Vec3(0.0);
  double Radius = 0, InvCell = 0;
  uint64_t Mask = 0;
};

// The photon mapper's estimator on a path tracer Scene.
struct PhotonScene
{
  const Scene* S = nullptr;
  // Sphere (grid-local) holding the medium's box and the surfaces: photons from directional
  // lights and the background are launched on a disc of this radius, outside it.
  Vec3 BoundCentre = Vec3(0.0);
  double BoundRadius = 1;

  // Sets the bounding sphere from the medium's box and the surfaces' bounds.
  void Bound();

  // Emits one photon (emitter chosen uniformly, its power divided by `photons`, the number
  // emitted in the pass) and traces it, appending its real collisions in the medium to `out`.
  void EmitAndTrace(Rng& rng, double photons, std::vector<Photon>& out, bool& truncated) const;

  // One view sample along the ray (origin, dir): the path tracer's view path (emission and the
  // background at depth 0, next-event estimation and a diffuse bounce at surfaces) where the
  // photons of `grid` within `radius` estimate the in-scattered radiance in the medium.
  // gatherRate 0: at the path's first real collision (delta tracking), where it ends. gatherRate
  // > 0 (1 / world length): at every tentative collision, which come at least at that rate where
  // there is extinction, weighted by their probability of being real, the path going on with the
  // rest (ratio tracking) to the next surface or the background. channel < 0: grey, RGB together;
  // else that channel only.
  Vec3 ViewSample(Vec3 origin, Vec3 dir, int channel, const PhotonGrid& grid, double radius,
    double gatherRate, Rng& rng, bool& truncated) const;

  // Volume of the part of the sphere of radius r around x inside the medium's box.
  double KernelVolume(const Vec3& x, double r) const;

private:
  // The photons of `grid` within `radius` of x, sum f(w_p, toCamera) power_p / sigma_t(x_p) over
  // the kernel's volume, f the HG phase with g (photons with depth + depth + 1 past MaxDepth
  // excluded).
  Vec3 Gather(const Vec3& x, const Vec3& toCamera, double g, double radius, int depth,
    const PhotonGrid& grid) const;

  // Ratio-tracking weight below which a view path plays Russian roulette.
  static constexpr double RouletteWeight = 0.05;
  // Russian roulette on a small ratio-tracking weight `beta` (rescaled when it survives).
  static bool Continue(Vec3& beta, int ch, bool grey, Rng& rng);

  // Traces a photon of RGB power `power` from x in the unit direction d (channel ch; grey when
  // `grey`).
  void Trace(Vec3 x, Vec3 d, const Vec3& power, int ch, bool grey, Rng& rng,
    std::vector<Photon>& out, bool& truncated) const;
};
} // namespace reference
} // namespace refracta

#endif
