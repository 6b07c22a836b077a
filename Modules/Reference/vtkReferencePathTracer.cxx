#include "vtkReferencePathTracer.h"
#include "vtkReferenceWalk.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

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

} // namespace

Vec3 Scene::BackgroundRadiance(const Vec3& dLocal) const
{
  return Env.Radiance(M.ToWorldVector(dLocal));
}

Vec3 Scene::EscapedRadiance(const Vec3& d) const
{
  Vec3 r(0.0);
  for (const Light& l : Lights)
  {
    if (l.Directional && OneMinusCos(d, l.Towards) <= l.OmcDelta)
    {
      r += l.Radiance * l.Colour;
    }
  }
  if (EnvLight)
  {
    r += BackgroundRadiance(d);
  }
  return r;
}

Scene::Outside Scene::FlyOutside(
  Vec3& x, const Vec3& d, bool enterBox, bool lights, int& light, SurfaceHit& hit) const
{
  double tBox = Inf, t0, t1;
  // A ray on the box's boundary that only touches it (a chord shorter than 1e-12 of the
  // diagonal) does not enter: that is the ray leaving it.
  if (enterBox && M.Intersect(x, d, t0, t1) && t1 > t0 + 1e-12 * M.Diagonal)
  {
    tBox = t0;
  }
  double t = tBox;
  light = -1;
  if (lights)
  {
    for (size_t i = 0; i < Lights.size(); ++i)
    {
      if (!Lights[i].Directional)
      {
        const double ti = Lights[i].HitSphere(x, d, t);
        if (ti < t)
        {
          t = ti;
          light = static_cast<int>(i);
        }
      }
    }
  }
  if (!Surf.Empty() && Surf.Closest(x, d, t, hit))
  {
    x = x + hit.T * d;
    return Outside::Surface;
  }
  if (light >= 0)
  {
    x = x + t * d;
    return Outside::Light;
  }
  if (tBox < Inf)
  {
    x = x + tBox * d;
    return Outside::Entered;
  }
  return Outside::Escaped;
}

Vec3 Scene::Connect(const Vec3& x, const Vec3& w, int ch, Rng& rng, bool& truncated) const
{
  double weight = 1;
  Vec3 p = x, d = w;
  bool inBox = M.Inside(p, 0), mayEnter = true;
  RayState ray;
  if (inBox)
  {
    TLight.Start(ray, p, d);
  }
  for (;;)
  {
    if (!inBox)
    {
      int light;
      SurfaceHit hit;
      switch (FlyOutside(p, d, mayEnter, true, light, hit))
      {
        case Outside::Surface:
          return Vec3(0.0);
        case Outside::Light:
          return (weight * Lights[light].SphereFactor(-d)) * Lights[light].Colour;
        case Outside::Escaped:
          return weight * EscapedRadiance(d);
        case Outside::Entered:
          inBox = true;
          TLight.Start(ray, p, d);
          continue;
      }
    }
    double majorant;
    int hit;
    const Event ev = AdvanceOptical(TLight, ray, -std::log(1 - rng.Uniform()), ch, hit, majorant);
    switch (ev)
    {
      case Event::Stuck:
        truncated = true;
        return Vec3(0.0);
      case Event::HitSurface:
        return Vec3(0.0);
      case Event::HitLight:
        return (weight * Lights[hit].SphereFactor(-ray.Dir)) * Lights[hit].Colour;
      case Event::Exited:
        // Straight from here on; a convex box is not entered again.
        inBox = false;
        mayEnter = false;
        p = ray.X;
        d = ray.Dir;
        continue;
      case Event::Reached:
        break;
    }
    Medium::Stencil st;
    M.MakeStencil(ray.X, st);
    const double sigma = M.Sample3(M.Sigma, st)[ch];
    weight *= std::max(0.0, 1 - sigma / majorant);
    if (weight < 0.1)
    {
      if (weight <= 0 || rng.Uniform() >= 0.5)
      {
        return Vec3(0.0);
      }
      weight *= 2;
    }
  }
}

Vec3 Scene::SampleEmitter(const Vec3& x, Rng& rng) const
{
  const int n = NumEmitters();
  const int j = std::min(n - 1, static_cast<int>(rng.Uniform() * n));
  if (j < static_cast<int>(Lights.size()))
  {
    Vec3 axis;
    double omc;
    Lights[j].Cone(x, axis, omc);
    return SampleCone(axis, omc, rng.Uniform(), rng.Uniform());
  }
  const double u1 = rng.Uniform(), u2 = rng.Uniform(), u3 = rng.Uniform(), u4 = rng.Uniform();
  const Vec3 dw = Env.Sample(u1, u2, u3, u4);
  const double a[3] = { dw.x, dw.y, dw.z };
  return Normalized(M.ToLocalVector(a));
}

double Scene::EmitterPdf(const Vec3& x, const Vec3& w) const
{
  double pdf = 0;
  for (const Light& l : Lights)
  {
    pdf += l.ConePdf(x, w);
  }
  if (EnvLight)
  {
    pdf += Env.Pdf(M.ToWorldVector(w));
  }
  return pdf / NumEmitters();
}

bool Scene::Scatter(
  int& depth, Vec3& beta, const Vec3& albedo, int ch, bool grey, Rng& rng, bool& truncated) const
{
  if (NumEmitters() == 0 || Largest(albedo, ch, grey) <= 0 ||
    (MaxDepth >= 0 && depth + 1 > MaxDepth))
  {
    return false;
  }
  if (depth + 1 > MaxVertices)
  {
    truncated = true;
    return false;
  }
  beta *= albedo;
  if (depth >= RouletteDepth)
  {
    const double q = std::min(1.0, Largest(beta, ch, grey));
    if (rng.Uniform() >= q)
    {
      return false;
    }
    beta /= q;
  }
  ++depth;
  return true;
}

Vec3 Scene::SurfaceDirect(const Vec3& x, const Vec3& n, int ch, Rng& rng, bool& truncated) const
{
  const Vec3 w =
    rng.Uniform() < 0.5 ? SampleCosine(n, rng.Uniform(), rng.Uniform()) : SampleEmitter(x, rng);
  const double c = glm::dot(n, w);
  if (!(c > 0))
  {
    return Vec3(0.0); // below the surface: the cosine (and the BRDF term) is 0
  }
  const double q = 0.5 * c / Pi + 0.5 * EmitterPdf(x, w);
  return (c / (Pi * q)) * Connect(Surf.Leave(x, n, w), w, ch, rng, truncated);
}

Vec3 Scene::MediumDirect(
  const Vec3& x, const Vec3& dir, double g, int ch, Rng& rng, bool& truncated) const
{
  const Vec3 w =
    rng.Uniform() < 0.5 ? SampleHG(g, dir, rng.Uniform(), rng.Uniform()) : SampleEmitter(x, rng);
  const double p = HGPhase(g, OneMinusCos(dir, w));
  const double q = 0.5 * p + 0.5 * EmitterPdf(x, w);
  if (!(q > 0 && p > 0))
  {
    return Vec3(0.0);
  }
  return (p / q) * Connect(x, w, ch, rng, truncated);
}

//------------------------------------------------------------------------------
bool Scene::ViewSurfaceVertex(Walk& walk, int& depth, Vec3& beta, Vec3& result, const Vec3& mask,
  int ch, bool grey, Rng& rng, bool& truncated) const
{
  const Vec3 n = walk.FacingNormal();
  if (!Scatter(depth, beta, Surf.Albedo(walk.Hit), ch, grey, rng, truncated))
  {
    return false;
  }
  result += beta * (mask * SurfaceDirect(walk.X, n, ch, rng, truncated));
  if (MaxDepth >= 0 && depth + 1 > MaxDepth)
  {
    return false;
  }
  walk.LeaveSurface(n, SampleCosine(n, rng.Uniform(), rng.Uniform()));
  return true;
}

//------------------------------------------------------------------------------
Vec3 Scene::Trace(Vec3 origin, Vec3 dir, int channel, Rng& rng, bool& truncated) const
{
  Vec3 result(0.0);
  const bool grey = channel < 0;
  const int ch = grey ? 0 : channel;
  const Vec3 mask = grey ? Vec3(1, 1, 1) : Vec3(channel == 0, channel == 1, channel == 2);
  Vec3 beta(1.0);
  int depth = 0;
  // Glass is crossed inside the walk (one Fresnel choice, its probability its weight: beta
  // unchanged, and the path stays "unscattered", depth 0, so the background it reaches counts).
  Walk walk(*this, T, origin, dir);
  for (;;)
  {
    switch (walk.Next(ch, rng, truncated))
    {
      case Walk::Stop::Ended:
        return result;
      case Walk::Stop::Escaped:
        if (depth == 0)
        {
          result += beta * (mask * BackgroundRadiance(walk.D));
        }
        return result;
      case Walk::Stop::Surface:
        // Next-event estimation, then a cosine-weighted bounce.
        if (!ViewSurfaceVertex(walk, depth, beta, result, mask, ch, grey, rng, truncated))
        {
          return result;
        }
        break;
      case Walk::Stop::Collision:
      {
        // Tentative collision.
        const RayState& ray = walk.Ray;
        const Walk::Local here = walk.Here(); // the grid's medium, or a glass body's
        const Vec3& sigma = here.Sigma;
        if (depth == 0 && here.Emits)
        {
          // Emission is physical radiance per length; the camera (in n = 1) sees the basic
          // radiance L / n^2, which is what the paths carry.
          const double n = here.N;
          result += (beta / (walk.Majorant * n * n)) * (mask * here.Emission);
        }
        if (rng.Uniform() * walk.Majorant >= sigma[ch])
        {
          break; // null collision
        }
        // Real collision: the scattered part carries on with weight albedo.
        if (!Scatter(depth, beta, here.Albedo, ch, grey, rng, truncated))
        {
          return result;
        }
        const double g = here.G;
        result += beta * (mask * MediumDirect(ray.X, ray.Dir, g, ch, rng, truncated));
        if (MaxDepth >= 0 && depth + 1 > MaxDepth)
        {
          return result;
        }
        // Continue the path in an HG direction (weight HG / HG = 1).
        walk.ScatterInto(SampleHG(g, ray.Dir, rng.Uniform(), rng.Uniform()));
        break;
      }
    }
  }
}
} // namespace reference
} // namespace refracta
