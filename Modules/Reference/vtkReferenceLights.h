/**
 * Internal to RefractaReference (a private header: not wrapped, not installed). The lights of the
 * reference renderer in the grid-local frame, with their finite extent: directional lights are
 * discs at infinity, point and spot lights spheres (see vtkReferenceRenderer.h).
 */
#ifndef vtkReferenceLights_h
#define vtkReferenceLights_h

#include "vtkReferenceMath.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

class vtkCamera;
class vtkLightCollection;

namespace refracta
{
namespace reference
{
struct Medium;

// A light in the grid-local frame, with its finite extent.
struct Light
{
  bool Directional = true;
  Vec3 Colour = Vec3(0.0);  // E (directional) or I (point / spot) per channel
  Vec3 Towards = Vec3(0.0); // directional: unit direction from the scene towards the light
  double OmcDelta = 0;      // directional: 1 - cos(delta)
  double Radiance = 0;      // directional: 1 / (pi sin^2 delta) ; sphere: 1 / (pi r^2)
  Vec3 Centre = Vec3(0.0);  // point / spot
  double Radius = 0;
  bool Spot = false;
  Vec3 Axis = Vec3(0.0); // spot axis (unit, from the light towards its focal point)
  double CosCone = -1;
  double Exponent = 0;

  // Radiance (per unit colour) leaving the sphere in the unit direction `w` (travel direction of
  // the emitted light).
  double SphereFactor(const Vec3& w) const
  {
    if (!Spot)
    {
      return Radiance;
    }
    const double c = glm::dot(w, Axis);
    if (c < CosCone || c <= 0)
    {
      return 0;
    }
    return Radiance * std::pow(c, Exponent);
  }

  // The cone of directions this light subtends from x (its axis and 1 - cos of its half-angle),
  // sampled uniformly by the connections. False when x is inside the sphere: then the whole
  // sphere of directions (pdf positive, no contribution).
  bool Cone(const Vec3& x, Vec3& axis, double& omcMax) const
  {
    if (Directional)
    {
      axis = Towards;
      omcMax = OmcDelta;
      return true;
    }
    const Vec3 d = Centre - x;
    const double dist2 = glm::dot(d, d);
    if (dist2 <= Radius * Radius)
    {
      // Inside the sphere: the whole sphere of directions (pdf positive, no contribution).
      axis = Vec3(0, 0, 1);
      omcMax = 2;
      return false;
    }
    axis = (1.0 / std::sqrt(dist2)) * d;
    const double sin2 = Radius * Radius / dist2;
    const double cosMax = std::sqrt(std::max(0.0, 1 - sin2));
    omcMax = sin2 / (1 + cosMax);
    return true;
  }
  // Solid-angle pdf of the uniform cone of Cone(x) at the unit direction w.
  double ConePdf(const Vec3& x, const Vec3& w) const
  {
    Vec3 axis;
    double omcMax;
    Cone(x, axis, omcMax);
    if (OneMinusCos(w, axis) > omcMax)
    {
      return 0;
    }
    return 1.0 / (2 * Pi * omcMax);
  }
  // Distance along the segment o + t d (unit d), t in [0, tMax], to the outer surface of the
  // sphere, or Inf.
  double HitSphere(const Vec3& o, const Vec3& d, double tMax) const
  {
    const Vec3 oc = o - Centre;
    const double b = glm::dot(oc, d);
    const double c = glm::dot(oc, oc) - Radius * Radius;
    if (c <= 0)
    {
      return Inf; // starts inside: the outer surface cannot be hit from inside
    }
    const double disc = b * b - c;
    if (disc < 0)
    {
      return Inf;
    }
    const double t = -b - std::sqrt(disc);
    return (t >= 0 && t <= tMax) ? t : Inf;
  }
};
// True when a switched-on light of the collection is positional (point or spot).
bool HasPositionalLight(vtkLightCollection* lights);

// Converts the renderer's lights to the grid-local frame of `m` (directional lights of angular
// radius deltaDeg degrees, point and spot light spheres of the given radius). Returns an error
// message for a light whose direction is undefined or whose intensity is invalid (empty when all
// are usable).
std::string BuildLights(const Medium& m, vtkLightCollection* lights, vtkCamera* camera,
  double deltaDeg, double radius, std::vector<Light>& out);
} // namespace reference
} // namespace refracta

#endif
