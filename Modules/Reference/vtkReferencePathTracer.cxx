#include "vtkReferencePathTracer.h"

#include "vtkRefractaEnvironmentMap.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace refracta
{
namespace reference
{
Vec3 Scene::BackgroundRadiance(const Vec3& dLocal) const
{
  if (Env.empty())
  {
    return Background;
  }
  const Vec3 d = M.ToWorldVector(dLocal);
  const double dw[3] = { d.x, d.y, d.z };
  double uv[2], rgb[3];
  vtkRefractaEnvironmentMap::DirectionToTexture(dw, EnvUp, EnvRight, uv);
  vtkRefractaEnvironmentMap::Sample(Env.data(), EnvW, EnvH, uv[0], uv[1], rgb);
  return ToVec3(rgb);
}

// Radiance arriving from lights along a ray that left the box at x with direction d
// (straight from here on): the first light sphere in the way, else every directional disc
// containing d.
Vec3 Scene::EscapedLightRadiance(const Vec3& x, const Vec3& d) const
{
  double tHit = Inf;
  int which = -1;
  for (size_t i = 0; i < Lights.size(); ++i)
  {
    if (!Lights[i].Directional)
    {
      const double t = Lights[i].HitSphere(x, d, Inf);
      if (t < tHit)
      {
        tHit = t;
        which = static_cast<int>(i);
      }
    }
  }
  if (which >= 0)
  {
    const Light& l = Lights[which];
    return (l.SphereFactor(-d)) * l.Colour;
  }
  Vec3 r(0.0);
  for (const Light& l : Lights)
  {
    if (l.Directional && OneMinusCos(d, l.Towards) <= l.OmcDelta)
    {
      r += l.Radiance * l.Colour;
    }
  }
  return r;
}

// Light arriving at x (inside the box) along the curved ray leaving x in direction w, times the
// transmittance to the light, estimated by ratio tracking (the tentative-collision weights
// (1 - sigma_t / majorant) multiply; Russian roulette once the weight is small). Only the
// channel `ch` matters for the transmittance (all three when grey).
Vec3 Scene::Connect(const Vec3& x, const Vec3& w, int ch, Rng& rng, bool& truncated) const
{
  double weight = 1;
  RayState ray;
  TLight.Start(ray, x, w);
  for (;;)
  {
    double majorant;
    int hit;
    const Event ev = AdvanceOptical(TLight, ray, -std::log(1 - rng.Uniform()), ch, hit, majorant);
    if (ev == Event::Stuck)
    {
      truncated = true;
      return Vec3(0.0);
    }
    if (ev == Event::HitLight)
    {
      const Light& l = Lights[hit];
      return (weight * l.SphereFactor(-ray.Dir)) * l.Colour;
    }
    if (ev == Event::Exited)
    {
      return weight * EscapedLightRadiance(ray.X, ray.Dir);
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

// One path from a view ray. channel < 0: grey medium, RGB carried together; else only that
// channel is estimated (returned in that component). `truncated` is set when the path hit a
// safety limit.
//
// At every scattering vertex the light that reaches the vertex without a further collision is
// estimated by one connection ray whose direction is drawn from the one-sample MIS mixture
// 0.5 HG + 0.5 (cone of a uniformly chosen light), weighted HG / mixture, its transmittance by
// ratio tracking; the path itself continues in an HG direction and only its later collisions
// contribute (light it reaches unscattered was already counted by the connection).
Vec3 Scene::Trace(Vec3 origin, Vec3 dir, int channel, Rng& rng, bool& truncated) const
{
  Vec3 result(0.0);
  const int ch = channel < 0 ? 0 : channel;
  const Vec3 mask = channel < 0 ? Vec3(1, 1, 1) : Vec3(channel == 0, channel == 1, channel == 2);
  double t0, t1;
  if (!M.Inside(origin, 0))
  {
    if (!M.Intersect(origin, dir, t0, t1))
    {
      return mask * BackgroundRadiance(dir);
    }
    origin = origin + t0 * dir;
  }
  const bool lightsPresent = !Lights.empty();
  const double nLights = static_cast<double>(Lights.size());
  double beta = 1;
  int depth = 0;
  RayState ray;
  T.Start(ray, origin, dir);
  for (;;)
  {
    double majorant;
    int hit;
    // The path's own rays never test light spheres: lights are not seen by view rays, and
    // scattered light reaching a light unscattered is the connections' business.
    const Event ev = AdvanceOptical(T, ray, -std::log(1 - rng.Uniform()), ch, hit, majorant);
    if (ev == Event::Stuck)
    {
      truncated = true;
      return result;
    }
    if (ev == Event::Exited)
    {
      if (depth == 0)
      {
        result += beta * (mask * BackgroundRadiance(ray.Dir));
      }
      return result;
    }
    // Tentative collision.
    Medium::Stencil st;
    M.MakeStencil(ray.X, st);
    const Vec3 sigma = M.Sample3(M.Sigma, st);
    if (depth == 0 && M.HasEmission)
    {
      // Emission is physical radiance per length; the camera (in n = 1) sees the basic
      // radiance L / n^2, which is what the paths carry.
      const double n = M.Sample1(M.Index, st);
      result += (beta / (majorant * n * n)) * (mask * M.Sample3(M.Emission, st));
    }
    if (rng.Uniform() * majorant >= sigma[ch])
    {
      continue; // null collision
    }
    // Real collision: the scattered part carries on with weight albedo.
    const double albedo = M.Sample3(M.Albedo, st)[ch];
    if (!lightsPresent || albedo <= 0 || (MaxDepth >= 0 && depth + 1 > MaxDepth))
    {
      return result;
    }
    if (depth + 1 > MaxVertices)
    {
      truncated = true;
      return result;
    }
    beta *= albedo;
    if (depth >= RouletteDepth)
    {
      const double q = std::min(1.0, beta);
      if (rng.Uniform() >= q)
      {
        return result;
      }
      beta /= q;
    }
    ++depth;
    const double g = M.Sample1(M.G, st);
    // Light reaching this vertex: one-sample MIS connection.
    {
      Vec3 w;
      if (rng.Uniform() < 0.5)
      {
        w = SampleHG(g, ray.Dir, rng.Uniform(), rng.Uniform());
      }
      else
      {
        const size_t j = std::min(Lights.size() - 1, static_cast<size_t>(rng.Uniform() * nLights));
        Vec3 axis;
        double omc;
        Lights[j].Cone(ray.X, axis, omc);
        w = SampleCone(axis, omc, rng.Uniform(), rng.Uniform());
      }
      const double p = HGPhase(g, OneMinusCos(ray.Dir, w));
      double lightPdf = 0;
      for (const Light& l : Lights)
      {
        lightPdf += l.ConePdf(ray.X, w);
      }
      const double q = 0.5 * p + 0.5 * lightPdf / nLights;
      if (q > 0 && p > 0)
      {
        const Vec3 li = Connect(ray.X, w, ch, rng, truncated);
        result += (beta * p / q) * (mask * li);
      }
    }
    if (MaxDepth >= 0 && depth + 1 > MaxDepth)
    {
      return result;
    }
    // Continue the path in an HG direction (weight HG / HG = 1).
    T.Start(ray, ray.X, SampleHG(g, ray.Dir, rng.Uniform(), rng.Uniform()));
  }
}
} // namespace reference
} // namespace refracta
