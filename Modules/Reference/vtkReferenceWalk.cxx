#include "vtkReferenceWalk.h"

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
  this->D = this->S.Surf.Interface(hit, this->D, rng.Uniform(), this->X);
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
      const Event ev =
        AdvanceOptical(this->T, this->Ray, -std::log(1 - rng.Uniform()), ch, light, this->Majorant);
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
