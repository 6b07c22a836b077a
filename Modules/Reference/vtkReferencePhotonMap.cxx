#include "vtkReferencePhotonMap.h"
#include "vtkReferenceWalk.h"

#include "vtkRefractaSurfaceSet.h"

#include <algorithm>
#include <cmath>

namespace refracta
{
namespace reference
{
namespace
{
// Largest component of v that the estimate uses (all three when grey, else channel ch).
double Largest(const Vec3& v, int ch, bool grey)
{
  return grey ? std::max(v.x, std::max(v.y, v.z)) : v[ch];
}

// Volume of the cap a plane at distance h from the centre cuts off a sphere of radius r.
double CapVolume(double r, double h)
{
  const double c = std::min(std::max(r - h, 0.0), 2 * r);
  return Pi * c * c * (3 * r - c) / 3;
}
} // namespace

double PhotonScene::KernelVolume(const Vec3& x, double r) const
{
  // The medium (and so every photon) ends at the box: the kernel counts only its part inside.
  // Per axis the caps beyond the two faces, the axes combined as a product: exact when one face
  // cuts the sphere, at an edge and at a corner.
  const double v = 4.0 / 3.0 * Pi * r * r * r;
  double fraction = 1;
  for (int a = 0; a < 3; ++a)
  {
    const double out = CapVolume(r, x[a] - S->M.Lo[a]) + CapVolume(r, S->M.Hi[a] - x[a]);
    fraction *= std::max(1 - out / v, 1e-3);
  }
  return v * fraction;
}

//------------------------------------------------------------------------------
void PhotonGrid::Build(std::vector<Photon>&& photons, const Vec3& lo, double radius)
{
  Lo = lo;
  Radius = radius;
  InvCell = 1.0 / (2 * radius);
  uint64_t buckets = 1;
  while (buckets < 2 * photons.size())
  {
    buckets <<= 1;
  }
  Mask = buckets - 1;
  Start.assign(buckets + 1, 0);
  std::vector<size_t> bucketOf(photons.size());
  for (size_t p = 0; p < photons.size(); ++p)
  {
    const Vec3& x = photons[p].X;
    bucketOf[p] = Bucket(Cell(x.x, 0), Cell(x.y, 1), Cell(x.z, 2));
    ++Start[bucketOf[p] + 1];
  }
  for (size_t b = 0; b < buckets; ++b)
  {
    Start[b + 1] += Start[b];
  }
  // Stable counting sort: the order within a bucket is the emission order (deterministic).
  std::vector<uint32_t> next(Start.begin(), Start.end() - 1);
  Sorted.resize(photons.size());
  for (size_t p = 0; p < photons.size(); ++p)
  {
    Sorted[next[bucketOf[p]]++] = photons[p];
  }
  photons.clear();
}

//------------------------------------------------------------------------------
void PhotonScene::Bound()
{
  const Medium& m = S->M;
  Vec3 lo = m.Lo, hi = m.Hi;
  if (!S->Surf.Empty())
  {
    double b[6];
    S->Surf.Set->GetBounds(b);
    if (b[0] <= b[1])
    {
      for (int c = 0; c < 8; ++c)
      {
        const double w[3] = { b[c & 1], b[2 + ((c >> 1) & 1)], b[4 + ((c >> 2) & 1)] };
        const Vec3 p = m.ToLocalPoint(w);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
    }
  }
  BoundCentre = 0.5 * (lo + hi);
  BoundRadius = std::max(0.5 * glm::length(hi - lo), 1e-9 * m.Diagonal) * (1 + 1e-9);
}

//------------------------------------------------------------------------------
void PhotonScene::EmitAndTrace(
  Rng& rng, double photons, std::vector<Photon>& out, bool& truncated) const
{
  const int emitters = S->NumEmitters();
  const int j = std::min(emitters - 1, static_cast<int>(rng.Uniform() * emitters));
  const bool grey = S->M.Grey;
  // Non-grey media: one channel per photon, chosen uniformly (power x 3 in that channel).
  const int ch = grey ? 0 : std::min(2, static_cast<int>(rng.Uniform() * 3));
  const Vec3 mask = grey ? Vec3(1.0) : Vec3(3 * (ch == 0), 3 * (ch == 1), 3 * (ch == 2));
  const double share = emitters / photons;
  Vec3 x, d, power;
  // A launch disc of the bounding sphere's radius perpendicular to the travel direction d,
  // outside the sphere: every line along d through the sphere crosses it once.
  auto launchOnDisc = [&](const Vec3& travel)
  {
    Vec3 t, b;
    Basis(travel, t, b);
    const double r = BoundRadius * std::sqrt(rng.Uniform()), phi = 2 * Pi * rng.Uniform();
    x =
      BoundCentre - (2 * BoundRadius) * travel + (r * std::cos(phi)) * t + (r * std::sin(phi)) * b;
    d = travel;
    return Pi * BoundRadius * BoundRadius;
  };
  if (j < static_cast<int>(S->Lights.size()))
  {
    const Light& l = S->Lights[j];
    if (l.Directional)
    {
      // Uniform radiance over the disc's cone (solid angle 2 pi (1 - cos delta)).
      const double u1 = rng.Uniform(), u2 = rng.Uniform();
      const Vec3 travel = -SampleCone(l.Towards, l.OmcDelta, u1, u2);
      const double area = launchOnDisc(travel);
      power = (l.Radiance * 2 * Pi * l.OmcDelta * area * share) * l.Colour;
    }
    else
    {
      // Uniform point on the sphere, cosine-weighted direction: pdf 1 / (4 pi r^2) x cos / pi.
      const double u1 = rng.Uniform(), u2 = rng.Uniform();
      const double z = 1 - 2 * u1, s = std::sqrt(std::max(0.0, 1 - z * z));
      const Vec3 n(s * std::cos(2 * Pi * u2), s * std::sin(2 * Pi * u2), z);
      d = SampleCosine(n, rng.Uniform(), rng.Uniform());
      x = l.Centre + (l.Radius * (1 + 1e-9)) * n;
      power = (l.SphereFactor(d) * Pi * 4 * Pi * l.Radius * l.Radius * share) * l.Colour;
    }
  }
  else
  {
    const double u1 = rng.Uniform(), u2 = rng.Uniform(), u3 = rng.Uniform(), u4 = rng.Uniform();
    const Vec3 dw = S->Env.Sample(u1, u2, u3, u4);
    const double pdf = S->Env.Pdf(dw);
    if (!(pdf > 0))
    {
      return;
    }
    const double a[3] = { dw.x, dw.y, dw.z };
    const double area = launchOnDisc(-Normalized(S->M.ToLocalVector(a)));
    power = (area * share / pdf) * S->Env.Radiance(dw);
  }
  if (!(Largest(power * mask, ch, grey) > 0))
  {
    return;
  }
  Trace(x, d, power * mask, ch, grey, rng, out, truncated);
}

//------------------------------------------------------------------------------
void PhotonScene::Trace(Vec3 x, Vec3 d, const Vec3& power, int ch, bool grey, Rng& rng,
  std::vector<Photon>& out, bool& truncated) const
{
  Vec3 beta(1.0);
  int depth = 0;
  // Glass is crossed inside the walk (one Fresnel choice, its probability its weight).
  Walk walk(*S, S->T, x, d);
  for (;;)
  {
    switch (walk.Next(ch, rng, truncated))
    {
      case Walk::Stop::Ended:
      case Walk::Stop::Escaped:
        return;
      case Walk::Stop::Surface:
      {
        // Diffuse reflection: albedo, roulette, cosine bounce.
        const Vec3 n = walk.FacingNormal();
        if (!S->Scatter(depth, beta, S->Surf.Albedo(walk.Hit), ch, grey, rng, truncated))
        {
          return;
        }
        walk.LeaveSurface(n, SampleCosine(n, rng.Uniform(), rng.Uniform()));
        break;
      }
      case Walk::Stop::Collision:
      {
        const RayState& ray = walk.Ray;
        const Walk::Local here = walk.Here(); // the grid's medium, or a glass body's
        const Vec3& sigma = here.Sigma;
        if (rng.Uniform() * walk.Majorant >= sigma[ch])
        {
          break; // null collision
        }
        // A real collision: the photon is stored (if a view vertex may still use it) ...
        if (S->MaxDepth < 0 || depth + 1 <= S->MaxDepth)
        {
          Photon p;
          p.X = ray.X;
          p.Dir = ray.Dir;
          p.Fluence = grey ? (1.0 / sigma[0]) * (beta * power) : Vec3(0.0);
          if (!grey)
          {
            p.Fluence[ch] = beta[ch] * power[ch] / sigma[ch];
          }
          p.Depth = depth;
          out.push_back(p);
        }
        // ... and scatters on with weight albedo.
        if (!S->Scatter(depth, beta, here.Albedo, ch, grey, rng, truncated))
        {
          return;
        }
        const double g = here.G;
        walk.ScatterInto(SampleHG(g, ray.Dir, rng.Uniform(), rng.Uniform()));
        break;
      }
    }
  }
}

//------------------------------------------------------------------------------
Vec3 PhotonScene::Gather(const Vec3& x, const Vec3& toCamera, double g, double radius, int depth,
  const PhotonGrid& grid) const
{
  // sigma_s (1/n^2) int f L dw at x is albedo / (V n^2) sum_p f(w_p, w) power_p / sigma_t(x_p)
  // times sigma_t(x) (each photon carries its power / sigma_t at its own collision: fluence x
  // volume). The caller applies sigma_t(x) (or the collision pdf that cancels it), albedo and
  // 1/n^2: 1/n^2 turns the photons' physical radiance into the basic radiance L/n^2 that is
  // conserved along the view ray.
  Vec3 sum(0.0);
  grid.ForEachWithin(x,
    [&](const Photon& p)
    {
      if (S->MaxDepth < 0 || p.Depth + depth + 1 <= S->MaxDepth)
      {
        sum += HGPhase(g, OneMinusCos(p.Dir, toCamera)) * p.Fluence;
      }
    });
  return (1.0 / KernelVolume(x, radius)) * sum;
}

//------------------------------------------------------------------------------
Vec3 PhotonScene::ViewSample(Vec3 origin, Vec3 dir, int channel, const PhotonGrid& grid,
  double radius, double gatherRate, Rng& rng, bool& truncated) const
{
  Vec3 result(0.0);
  const bool grey = channel < 0;
  const int ch = grey ? 0 : channel;
  const Vec3 mask = grey ? Vec3(1, 1, 1) : Vec3(channel == 0, channel == 1, channel == 2);
  const bool ratioTracking = gatherRate > 0;
  Vec3 beta(1.0);
  int depth = 0;
  Walk walk(*S, S->T, origin, dir);
  walk.MinimumMajorant = gatherRate;
  for (;;)
  {
    switch (walk.Next(ch, rng, truncated))
    {
      case Walk::Stop::Ended:
        return result;
      case Walk::Stop::Escaped:
        if (depth == 0)
        {
          result += beta * (mask * S->BackgroundRadiance(walk.D));
        }
        return result;
      case Walk::Stop::Surface:
        // The path tracer's next-event estimation, then a cosine-weighted bounce.
        if (!S->ViewSurfaceVertex(walk, depth, beta, result, mask, ch, grey, rng, truncated))
        {
          return result;
        }
        break;
      case Walk::Stop::Collision:
      {
        const RayState& ray = walk.Ray;
        const Walk::Local here = walk.Here(); // the grid's medium, or a glass body's
        const double n = here.N;
        const double real = here.Sigma[ch] / walk.Majorant; // probability of a real collision
        const bool gathers = S->MaxDepth < 0 || depth + 1 <= S->MaxDepth;
        if (depth == 0 && here.Emits)
        {
          result += (beta / (walk.Majorant * n * n)) * (mask * here.Emission);
        }
        if (ratioTracking)
        {
          // Every tentative collision gathers, weighted by its probability of being real, and
          // the path goes on with the probability of a null one (ratio tracking, Novak et al.
          // 2014): the in-scattered light is summed along the whole ray, not sampled at one
          // point of it.
          if (gathers && real > 0)
          {
            const Vec3 s = Gather(ray.X, -ray.Dir, here.G, radius, depth, grid);
            result += (real / (n * n)) * (beta * here.Albedo * (mask * s));
          }
          beta *= std::max(0.0, 1 - real);
          if (!Continue(beta, ch, grey, rng))
          {
            return result;
          }
          break;
        }
        if (rng.Uniform() >= real)
        {
          break; // null collision
        }
        // The first real collision: the collision's pdf sigma_t cancels the source's.
        if (gathers)
        {
          const Vec3 s = Gather(ray.X, -ray.Dir, here.G, radius, depth, grid);
          result += (1.0 / (n * n)) * (beta * here.Albedo * (mask * s));
        }
        return result;
      }
    }
  }
}

//------------------------------------------------------------------------------
bool PhotonScene::Continue(Vec3& beta, int ch, bool grey, Rng& rng)
{
  // Russian roulette once the ratio-tracking weight is small: unbiased, and it ends rays deep in
  // dense media after a few optical depths instead of at the box.
  const double w = Largest(beta, ch, grey);
  if (w >= RouletteWeight)
  {
    return true;
  }
  const double q = w / RouletteWeight;
  if (!(q > 0) || rng.Uniform() >= q)
  {
    return false;
  }
  beta /= q;
  return true;
}
} // namespace reference
} // namespace refracta
