/**
 * Internal to RefractaReference (a private header: not wrapped, not installed). Curved rays of the
 * reference renderer: d/ds(n dx/ds) = grad n integrated in arc length by an adaptive
 * Dormand-Prince RK5(4) step with error control on (x, v = n dx/ds), straight moves through flat
 * blocks and for media without a gradient, light spheres and surfaces tested on each chord, and the
 * delta/ratio tracking step against the per block majorants.
 */
#ifndef vtkReferenceIntegrator_h
#define vtkReferenceIntegrator_h

#include "vtkReferenceLights.h"
#include "vtkReferenceMath.h"
#include "vtkReferenceMedium.h"
#include "vtkReferenceSurfaces.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace refracta
{
namespace reference
{
// Tracing along a (possibly curved) ray inside the box.
struct RayState
{
  Vec3 X = Vec3(0.0);   // position, grid-local
  Vec3 V = Vec3(0.0);   // n dx/ds, |V| = n (curved rays); unused for straight rays
  Vec3 Dir = Vec3(0.0); // unit travel direction
  double H = 0;         // integrator step proposal
  SurfaceHit Surface;   // the surface hit of the last HitSurface event
};

enum class Event
{
  Reached,    // moved the requested arc length, still inside the box
  Exited,     // left the box; X on the boundary, Dir the exit direction
  HitLight,   // reached a light sphere inside the box (HitIndex)
  HitSurface, // reached a surface (RayState::Surface); X on it, Dir the incoming direction
  Stuck       // integrator step limit reached (path dropped)
};

struct Tracer
{
  const Medium* M = nullptr;
  double Tol = 1e-7;
  double MaxStep = 1;
  const std::vector<Light>* Lights = nullptr; // spheres to test, or nullptr
  const Surfaces* Surf = nullptr;             // triangles to test, or nullptr
  int64_t StepBudget = 1000000;               // steps per Advance call: bounds trapped (TIR) rays

  double StraightExit(const Vec3& x, const Vec3& d) const
  {
    double t0, t1;
    if (!M->Intersect(x, d, t0, t1))
    {
      return 0;
    }
    return std::max(t1, 0.0);
  }

  // Nearest light sphere (of Lights) hit by the segment o + t d, t in [0, len], closer than tHit:
  // updates tHit and which.
  void CheckSpheres(const Vec3& o, const Vec3& d, double len, double& tHit, int& which) const;

  // Nearest light sphere or surface on the straight segment o + t d (unit d), t in [0, len]:
  // Reached when there is none, else HitLight (light index in `which`) or HitSurface (the hit in
  // r.Surface), the distance in tHit.
  Event CheckSegment(
    const Vec3& o, const Vec3& d, double len, double& tHit, int& which, RayState& r) const;

  // Start a curved ray at x (inside or on the box) with unit direction d.
  void Start(RayState& r, const Vec3& x, const Vec3& d) const;

  // Dormand-Prince RK5(4) step of the ray equation in arc length; returns the error norm.
  double RKStep(const Vec3& x, const Vec3& v, double h, Vec3& xn, Vec3& vn) const;

  // Move along the ray by arc length `dist` (may be Inf) inside the box. `moved` returns the arc
  // length travelled, `hit` the light sphere index for HitLight, `steps` accumulates accepted
  // steps.
  Event Advance(RayState& r, double dist, double& moved, int& hit, int64_t& steps) const;
};

// Delta/ratio tracking step with piecewise-constant (per block) majorants: moves the ray until
// the majorant optical length `tau` is used up (Reached: a tentative collision, its majorant in
// `m`) or the ray leaves the box or hits a light or a surface. Where the medium has extinction
// the majorant is raised to at least `floor` (1 / world length; 0: the blocks' own): more
// tentative collisions, for estimators that use each of them (ratio tracking, gathering).
Event AdvanceOptical(
  const Tracer& tr, RayState& r, double tau, int ch, int& hit, double& m, double floor = 0);
} // namespace reference
} // namespace refracta

#endif
