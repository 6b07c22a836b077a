#include "vtkReferenceIntegrator.h"

#include <algorithm>
#include <cmath>

namespace refracta
{
namespace reference
{
void Tracer::CheckSpheres(const Vec3& o, const Vec3& d, double len, double& tHit, int& which) const
{
  if (!Lights)
  {
    return;
  }
  for (size_t i = 0; i < Lights->size(); ++i)
  {
    const Light& l = (*Lights)[i];
    if (l.Directional)
    {
      continue;
    }
    const double t = l.HitSphere(o, d, len);
    if (t < tHit)
    {
      tHit = t;
      which = static_cast<int>(i);
    }
  }
}

Event Tracer::CheckSegment(
  const Vec3& o, const Vec3& d, double len, double& tHit, int& which, RayState& r) const
{
  tHit = Inf;
  which = -1;
  CheckSpheres(o, d, len, tHit, which);
  if (Surf && Surf->Closest(o, d, std::min(len, tHit), r.Surface))
  {
    tHit = r.Surface.T;
    which = -1;
    return Event::HitSurface;
  }
  return tHit < Inf ? Event::HitLight : Event::Reached;
}

// Start a curved ray at x (inside or on the box) with unit direction d.
void Tracer::Start(RayState& r, const Vec3& x, const Vec3& d) const
{
  r.X = x;
  r.Dir = d;
  if (!M->StraightRays)
  {
    double n;
    Vec3 g;
    M->IndexAndGradient(x, n, g);
    r.V = n * d;
  }
  r.H = MaxStep * M->MinSpacing;
}

// Dormand-Prince RK5(4) step of the ray equation in arc length; returns the error norm.
double Tracer::RKStep(const Vec3& x, const Vec3& v, double h, Vec3& xn, Vec3& vn) const
{
  static const double a21 = 1.0 / 5, a31 = 3.0 / 40, a32 = 9.0 / 40, a41 = 44.0 / 45,
                      a42 = -56.0 / 15, a43 = 32.0 / 9, a51 = 19372.0 / 6561, a52 = -25360.0 / 2187,
                      a53 = 64448.0 / 6561, a54 = -212.0 / 729, a61 = 9017.0 / 3168,
                      a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                      a65 = -5103.0 / 18656, b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192,
                      b5 = -2187.0 / 6784, b6 = 11.0 / 84, e1 = 35.0 / 384 - 5179.0 / 57600,
                      e3 = 500.0 / 1113 - 7571.0 / 16695, e4 = 125.0 / 192 - 393.0 / 640,
                      e5 = -2187.0 / 6784 + 92097.0 / 339200, e6 = 11.0 / 84 - 187.0 / 2100,
                      e7 = -1.0 / 40;
  auto f = [this](const Vec3& px, const Vec3& pv, Vec3& dx, Vec3& dv)
  {
    double n;
    M->IndexAndGradient(px, n, dv);
    dx = (1.0 / n) * pv;
  };
  Vec3 kx[7], kv[7];
  f(x, v, kx[0], kv[0]);
  f(x + h * (a21 * kx[0]), v + h * (a21 * kv[0]), kx[1], kv[1]);
  f(x + h * (a31 * kx[0] + a32 * kx[1]), v + h * (a31 * kv[0] + a32 * kv[1]), kx[2], kv[2]);
  f(x + h * (a41 * kx[0] + a42 * kx[1] + a43 * kx[2]),
    v + h * (a41 * kv[0] + a42 * kv[1] + a43 * kv[2]), kx[3], kv[3]);
  f(x + h * (a51 * kx[0] + a52 * kx[1] + a53 * kx[2] + a54 * kx[3]),
    v + h * (a51 * kv[0] + a52 * kv[1] + a53 * kv[2] + a54 * kv[3]), kx[4], kv[4]);
  f(x + h * (a61 * kx[0] + a62 * kx[1] + a63 * kx[2] + a64 * kx[3] + a65 * kx[4]),
    v + h * (a61 * kv[0] + a62 * kv[1] + a63 * kv[2] + a64 * kv[3] + a65 * kv[4]), kx[5], kv[5]);
  xn = x + h * (b1 * kx[0] + b3 * kx[2] + b4 * kx[3] + b5 * kx[4] + b6 * kx[5]);
  vn = v + h * (b1 * kv[0] + b3 * kv[2] + b4 * kv[3] + b5 * kv[4] + b6 * kv[5]);
  f(xn, vn, kx[6], kv[6]);
  const Vec3 ex = h * (e1 * kx[0] + e3 * kx[2] + e4 * kx[3] + e5 * kx[4] + e6 * kx[5] + e7 * kx[6]);
  const Vec3 ev = h * (e1 * kv[0] + e3 * kv[2] + e4 * kv[3] + e5 * kv[4] + e6 * kv[5] + e7 * kv[6]);
  const double sx = Tol * M->MinSpacing, sv = Tol * M->NMax;
  return std::max(std::max(std::abs(ex.x), std::max(std::abs(ex.y), std::abs(ex.z))) / sx,
    std::max(std::abs(ev.x), std::max(std::abs(ev.y), std::abs(ev.z))) / sv);
}

// Move along the ray by arc length `dist` (may be Inf) inside the box. `moved` returns the arc
// length travelled, `hit` the light sphere index for HitLight (a HitSurface's hit is in
// r.Surface), `steps` accumulates accepted steps.
Event Tracer::Advance(RayState& r, double dist, double& moved, int& hit, int64_t& steps) const
{
  moved = 0;
  hit = -1;
  if (M->StraightRays)
  {
    const double tExit = StraightExit(r.X, r.Dir);
    const double len = std::min(dist, tExit);
    double tHit;
    const Event ev = CheckSegment(r.X, r.Dir, len, tHit, hit, r);
    ++steps;
    if (ev != Event::Reached)
    {
      r.X = r.X + tHit * r.Dir;
      moved = tHit;
      return ev;
    }
    r.X = r.X + len * r.Dir;
    moved = len;
    return dist < tExit ? Event::Reached : Event::Exited;
  }
  const double hMin = 1e-4 * M->MinSpacing; // also the tolerance for the exit point
  const double hMax = MaxStep * M->MinSpacing;
  int64_t budget = StepBudget;
  while (moved < dist)
  {
    if (--budget < 0)
    {
      return Event::Stuck;
    }
    const double tExit = StraightExit(r.X, r.Dir);
    double tBlock;
    if (M->FlatBlock(r.X, r.Dir, tBlock))
    {
      // n constant and grad n = 0 here: the ray is exactly straight until it leaves the block
      // (overshooting by hMin / 2 so that it does not stall on the block face, where grad n
      // is still exactly 0).
      const double len = std::min(dist - moved, std::min(tExit, tBlock + 0.5 * hMin));
      ++steps;
      if (Lights || Surf)
      {
        double tHit;
        const Event ev = CheckSegment(r.X, r.Dir, len, tHit, hit, r);
        if (ev != Event::Reached)
        {
          r.X = r.X + tHit * r.Dir;
          moved += tHit;
          return ev;
        }
      }
      r.X = r.X + len * r.Dir;
      moved += len;
      if (len >= tExit)
      {
        return Event::Exited;
      }
      continue;
    }
    double h = std::min(std::min(r.H, hMax), dist - moved);
    h = std::min(h, std::max(tExit, hMin));
    h = std::max(h, std::min(hMin, dist - moved));
    Vec3 xn, vn;
    const double err = RKStep(r.X, r.V, h, xn, vn);
    if (err > 1 && h > hMin)
    {
      r.H = std::max(hMin, h * std::max(0.2, 0.9 * std::pow(err, -0.2)));
      continue;
    }
    const bool outside = !M->Inside(xn, 0);
    if (outside && !M->Inside(xn, hMin) && h > hMin)
    {
      // Overshot the box by more than the exit tolerance: shorter step towards the boundary.
      r.H = std::max(hMin, 0.5 * h);
      continue;
    }
    // Accept.
    ++steps;
    const Vec3 chord = xn - r.X;
    const double clen = glm::length(chord);
    if ((Lights || Surf) && clen > 0)
    {
      // Lights and surfaces are met on the chord of the step (its straight secant, within the
      // integrator's tolerance of the curved path).
      double tHit;
      const Event ev = CheckSegment(r.X, (1.0 / clen) * chord, clen, tHit, hit, r);
      if (ev != Event::Reached)
      {
        const double frac = tHit / clen;
        r.X = r.X + frac * chord;
        r.Dir = (1.0 / clen) * chord;
        moved += frac * h;
        return ev;
      }
    }
    double n;
    Vec3 g;
    M->IndexAndGradient(xn, n, g);
    const double vl = glm::length(vn);
    r.V = vl > 0 ? (n / vl) * vn : n * r.Dir;
    r.X = xn;
    r.Dir = (1.0 / n) * r.V;
    moved += h;
    if (err <= 1)
    {
      r.H = std::min(hMax, h * std::min(5.0, 0.9 * std::pow(std::max(err, 1e-10), -0.2)));
    }
    if (outside)
    {
      return Event::Exited;
    }
  }
  return Event::Reached;
}

// Delta/ratio tracking step with piecewise-constant (per block) majorants: moves the ray until
// the majorant optical length `tau` is used up (Reached: a tentative collision, its majorant in
// `m`) or the ray leaves the box or hits a light.
Event AdvanceOptical(
  const Tracer& tr, RayState& r, double tau, int ch, int& hit, double& m, double floor)
{
  int64_t steps = 0;
  for (int64_t guard = 0; guard < 10000000; ++guard)
  {
    double dSafe, moved;
    tr.M->LocalMajorant(r.X, ch, m, dSafe);
    if (m > 0)
    {
      m = std::max(m, floor);
    }
    if (m > 0 && m * dSafe >= tau)
    {
      return tr.Advance(r, tau / m, moved, hit, steps);
    }
    const Event ev = tr.Advance(r, dSafe, moved, hit, steps);
    if (ev != Event::Reached)
    {
      return ev;
    }
    tau -= m * moved;
  }
  return Event::Stuck;
}
} // namespace reference
} // namespace refracta
