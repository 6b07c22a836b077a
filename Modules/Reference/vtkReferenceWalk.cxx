#include "vtkReferenceWalk.h"

#include <algorithm>
#include <cmath>

namespace refracta
{
namespace reference
{
//------------------------------------------------------------------------------
Walk::Walk(const Scene& scene, const Tracer& tracer, const Vec3& x, const Vec3& d)
  : X(x)
  , D(d)
  , S(scene)
  , T(tracer)
{
  this->Body = scene.Surf.StartBody(x, d);
  this->Restart();
}

//------------------------------------------------------------------------------
void Walk::Restart()
{
  this->InBox = this->S.M.Inside(this->X, 0);
  this->MayEnter = true;
  if (this->InBox)
  {
    this->T.Start(this->Ray, this->X, this->D);
  }
}

//------------------------------------------------------------------------------
bool Walk::CrossInterface(const SurfaceHit& hit, Rng& rng, bool& truncated)
{
  if (++this->Interfaces > this->S.MaxInterfaces)
  {
    truncated = true;
    return false;
  }
  const Vec3 incoming = this->D;
  this->D = this->S.Surf.Interface(hit, this->D, rng.Uniform(), this->X);
  this->Body = this->S.Surf.BodyAfter(hit, incoming, this->D, this->Body);
  this->Restart();
  return true;
}

//------------------------------------------------------------------------------
Vec3 Walk::FacingNormal() const
{
  const Vec3 n = this->S.Surf.Normal(this->Hit);
  return glm::dot(n, this->D) > 0 ? -n : n;
}

//------------------------------------------------------------------------------
void Walk::LeaveSurface(const Vec3& n, const Vec3& dir)
{
  this->D = dir;
  this->X = this->S.Surf.Leave(this->X, n, dir);
  this->Restart();
}

//------------------------------------------------------------------------------
void Walk::ScatterInto(const Vec3& dir)
{
  this->T.Start(this->Ray, this->Ray.X, dir);
}

//------------------------------------------------------------------------------
Event Walk::AdvanceInBody(double tau, int ch, int& light)
{
  // A homogeneous medium: the free path is exponential in sigma_t itself (every collision real).
  // (A raised majorant, MinimumMajorant, adds null collisions.)
  const double sigma = this->S.Surf.BodyMedium(this->Body)[ch];
  this->Majorant = sigma > 0 ? std::max<double>(sigma, this->MinimumMajorant) : 0;
  double moved;
  int64_t steps = 0;
  return this->T.Advance(
    this->Ray, this->Majorant > 0 ? tau / this->Majorant : Inf, moved, light, steps);
}

//------------------------------------------------------------------------------
Walk::Local Walk::Here() const
{
  Local l;
  if (this->Body >= 0)
  {
    const float* b = this->S.Surf.BodyMedium(this->Body);
    l.Sigma = Vec3(b[0], b[1], b[2]);
    l.Albedo = Vec3(b[4], b[5], b[6]);
    l.G = b[7];
    l.Emission = Vec3(b[8], b[9], b[10]);
    l.N = this->S.Surf.BodyIndex(this->Body);
    l.Emits = true;
    return l;
  }
  const Medium& m = this->S.M;
  Medium::Stencil st;
  m.MakeStencil(this->Ray.X, st);
  l.Sigma = m.Sample3(m.Sigma, st);
  l.Albedo = m.Sample3(m.Albedo, st);
  l.G = m.Sample1(m.G, st);
  l.N = m.Sample1(m.Index, st);
  l.Emits = m.HasEmission;
  l.Emission = m.HasEmission ? m.Sample3(m.Emission, st) : Vec3(0.0);
  return l;
}

//------------------------------------------------------------------------------
Walk::Stop Walk::Next(int ch, Rng& rng, bool& truncated)
{
  for (;;)
  {
    SurfaceHit hit;
    if (!this->InBox)
    {
      int light;
      const Scene::Outside o =
        this->S.FlyOutside(this->X, this->D, this->MayEnter, false, light, hit);
      if (o == Scene::Outside::Escaped)
      {
        return Stop::Escaped;
      }
      if (o == Scene::Outside::Entered)
      {
        this->InBox = true;
        this->T.Start(this->Ray, this->X, this->D);
        continue;
      }
    }
    else
    {
      // The path's own rays never test light spheres: lights are not seen by view rays, and
      // scattered light reaching a light unscattered is the connections' business.
      int light;
      const double tau = -std::log(1 - rng.Uniform());
      const Event ev = this->Body >= 0
        ? this->AdvanceInBody(tau, ch, light)
        : AdvanceOptical(this->T, this->Ray, tau, ch, light, this->Majorant, this->MinimumMajorant);
      if (ev == Event::Stuck)
      {
        truncated = true;
        return Stop::Ended;
      }
      if (ev == Event::Exited)
      {
        this->InBox = false;
        this->MayEnter = false; // a convex box is not entered again by a straight ray
        this->X = this->Ray.X;
        this->D = this->Ray.Dir;
        continue;
      }
      if (ev != Event::HitSurface)
      {
        return Stop::Collision;
      }
      this->X = this->Ray.X;
      this->D = this->Ray.Dir;
      hit = this->Ray.Surface;
    }
    // A surface: glass is crossed here, an opaque one is the owner's.
    if (!this->S.Surf.IsDielectric(hit))
    {
      this->Hit = hit;
      return Stop::Surface;
    }
    if (!this->CrossInterface(hit, rng, truncated))
    {
      return Stop::Ended;
    }
  }
}
} // namespace reference
} // namespace refracta
