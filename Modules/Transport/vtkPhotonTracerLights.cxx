// vtkPhotonTracer's lights: the medium read (or reused), then every VTK light converted to the
// grid-local frame in double precision with the cone its photons are emitted into.
#include "vtkPhotonTracer.h"
#include "vtkPhotonTracerInternals.h"

#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMediumValidator.h"
#include "vtkRefractaGridFrame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>

namespace
{
// Corner `corner` (bit a: the upper bound along axis a) of the box [lo, hi].
void BoxCorner(int corner, const double lo[3], const double hi[3], double q[3])
{
  for (int a = 0; a < 3; ++a)
  {
    q[a] = (corner >> a) & 1 ? hi[a] : lo[a];
  }
}
}

using namespace vtkPhotonTracerDetail;

namespace vtkPhotonTracerDetail
{
bool ReadLocalLight(
  vtkLight* light, int index, vtkRefractaGridFrame* grid, LocalLight& out, std::string& error)
{
  if (!vtkMediumValidator::CheckLight(light, index, error))
  {
    return false;
  }
  double pw[3], fw[3], colour[3];
  light->GetTransformedPosition(pw);
  light->GetTransformedFocalPoint(fw);
  light->GetDiffuseColor(colour);
  const double intensity = light->GetIntensity();
  out.Positional = light->GetPositional() != 0;
  out.Spot = out.Positional && light->GetConeAngle() < 90.0;
  const double axisWorld[3] = { fw[0] - pw[0], fw[1] - pw[1], fw[2] - pw[2] };
  grid->WorldToLocalPoint(pw, out.Position);
  grid->WorldToLocalVector(axisWorld, out.Axis);
  for (int c = 0; c < 3; ++c)
  {
    out.Colour[c] = colour[c] * intensity;
  }
  std::ostringstream why;
  if ((!out.Positional || out.Spot) && !Normalize(out.Axis))
  {
    why << "Light " << index
        << " is directional or a spot but its position equals its focal point; they must differ "
           "to give a direction.";
  }
  else if (out.Spot && !(light->GetConeAngle() > 0.0))
  {
    why << "Light " << index << " has cone angle " << light->GetConeAngle()
        << "; a spot needs (0, 90) degrees, a point light >= 90.";
  }
  error = why.str();
  return error.empty();
}
}

//------------------------------------------------------------------------------
// Lights, converted to the grid-local frame in double precision.
bool vtkPhotonTracer::SetUpLights(Internals& run)
{
  vtkImageData* input = run.Input;
  Medium& m = run.M;
  if (!run.ReusedMedium)
  {
    LoadMedium(input, this->UseProxyBounds, m);
    bool bodyAttenuates, bodyScatters;
    BodyMedia(this->Surfaces, bodyAttenuates, bodyScatters);
    m.Attenuates = m.Attenuates || bodyAttenuates;
    m.Scatters = m.Scatters || bodyScatters;
  }
  if (!this->PrepareSurfaces(run))
  {
    return false;
  }
  // The box the lights aim at: the proxy box, grown by the surfaces' bounds.
  const double* emitLo = run.EmitLo;
  const double* emitHi = run.EmitHi;
  vtkNew<vtkRefractaGridFrame> grid;
  grid->SetImage(input);
  const double boxCentre[3] = { 0.5 * (emitLo[0] + emitHi[0]), 0.5 * (emitLo[1] + emitHi[1]),
    0.5 * (emitLo[2] + emitHi[2]) };
  const double halfDiag[3] = { 0.5 * (emitHi[0] - emitLo[0]), 0.5 * (emitHi[1] - emitLo[1]),
    0.5 * (emitHi[2] - emitLo[2]) };
  const double boxRadius = std::sqrt(Dot(halfDiag, halfDiag));

  std::vector<LightSetup>& lights = run.Lights;
  vtkLight* light;
  vtkCollectionSimpleIterator it;
  int lightIndex = 0;
  for (this->Lights->InitTraversal(it); (light = this->Lights->GetNextLight(it)); ++lightIndex)
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    LocalLight local;
    std::string lightError;
    if (!ReadLocalLight(light, lightIndex, grid, local, lightError))
    {
      vtkErrorMacro(<< lightError);
      return false;
    }
    LightSetup ls;
    ls.Positional = local.Positional;
    std::copy(local.Colour, local.Colour + 3, ls.Colour);
    const double* p = local.Position;
    const double* axis = local.Axis;
    const bool isSpot = local.Spot;
    const double maxColour = std::max({ ls.Colour[0], ls.Colour[1], ls.Colour[2] });
    if (!ls.Positional)
    {
      // Rectangle perpendicular to the direction covering the box's projection.
      double b1[3], b2[3];
      Basis(axis, b1, b2);
      double umin = 1e300, umax = -1e300, wmin = 1e300, wmax = -1e300, dmin = 1e300;
      for (int corner = 0; corner < 8; ++corner)
      {
        double q[3];
        BoxCorner(corner, emitLo, emitHi, q);
        umin = std::min(umin, Dot(q, b1));
        umax = std::max(umax, Dot(q, b1));
        wmin = std::min(wmin, Dot(q, b2));
        wmax = std::max(wmax, Dot(q, b2));
        dmin = std::min(dmin, Dot(q, axis));
      }
      const double back = dmin - 0.01 * boxRadius - 1e-6;
      // A disc of angular radius delta tilts rays by up to delta: widen the rectangle by what
      // they drift sideways across the box.
      const double delta = vtkMath::RadiansFromDegrees(this->DirectionalLightAngularRadius);
      ls.Extent = std::sin(delta);
      const double margin = std::tan(delta) * (2.0 * boxRadius + 0.01 * boxRadius);
      umin -= margin;
      wmin -= margin;
      umax += margin;
      wmax += margin;
      for (int c = 0; c < 3; ++c)
      {
        ls.Origin[c] = b1[c] * umin + b2[c] * wmin + axis[c] * back;
        ls.Axis[c] = axis[c];
        ls.Basis1[c] = b1[c] * (umax - umin);
        ls.Basis2[c] = b2[c] * (wmax - wmin);
      }
      ls.Measure = (umax - umin) * (wmax - wmin);
    }
    else
    {
      std::copy(p, p + 3, ls.Origin);
      double toBox[3] = { boxCentre[0] - p[0], boxCentre[1] - p[1], boxCentre[2] - p[2] };
      const double distance = std::sqrt(Dot(toBox, toBox));
      bool inside = true;
      for (int c = 0; c < 3; ++c)
      {
        inside = inside && p[c] >= emitLo[c] && p[c] <= emitHi[c];
      }
      double capAxis[3] = { 0, 0, 1 };
      ls.OneMinusCos = 2.0; // whole sphere
      // A sphere light reaches the box from anywhere on its disc: widen the cap by its radius.
      ls.Extent = this->LightRadius;
      const double reach = boxRadius + this->LightRadius;
      if (!inside && distance > reach * (1 + 1e-9))
      {
        const double s = reach / distance;
        ls.OneMinusCos = s * s / (1.0 + std::sqrt(1.0 - s * s));
        for (int c = 0; c < 3; ++c)
        {
          capAxis[c] = toBox[c] / distance;
        }
      }
      if (!inside && this->LightRadius == 0.0 && distance > 0.0)
      {
        // The cone towards the box's centre through its farthest corner: it holds the box (the
        // box is the convex hull of its corners, and a cone narrower than a hemisphere is
        // convex) and is often far narrower than the bounding sphere's cone, or than the whole
        // sphere when the light is inside that sphere (a light over a wide floor): the photons
        // that would miss the box are not generated.
        const double towards[3] = { toBox[0] / distance, toBox[1] / distance, toBox[2] / distance };
        double cosMin = 1.0;
        for (int corner = 0; corner < 8; ++corner)
        {
          double d[3];
          BoxCorner(corner, emitLo, emitHi, d);
          vtkMath::Subtract(d, p, d);
          const double length = std::sqrt(Dot(d, d));
          cosMin = std::min(cosMin, length > 0.0 ? Dot(d, towards) / length : -1.0);
        }
        // Slightly wider than exact, so that rounding never loses a corner's photons.
        const double cornerOmc = 1.0 - cosMin + 1e-9;
        if (cosMin > 0.0 && cornerOmc < ls.OneMinusCos)
        {
          ls.OneMinusCos = cornerOmc;
          std::copy(towards, towards + 3, capAxis);
        }
      }
      if (isSpot)
      {
        const double half = vtkMath::RadiansFromDegrees(light->GetConeAngle());
        const double spotOmc = 2.0 * std::sin(0.5 * half) * std::sin(0.5 * half);
        std::copy(axis, axis + 3, ls.SpotAxis);
        ls.SpotCos = std::cos(half);
        ls.Exponent = light->GetExponent();
        if (spotOmc < ls.OneMinusCos)
        {
          ls.OneMinusCos = spotOmc;
          std::copy(axis, axis + 3, capAxis);
        }
      }
      std::copy(capAxis, capAxis + 3, ls.Axis);
      Basis(ls.Axis, ls.Basis1, ls.Basis2);
      ls.Measure = 2.0 * vtkMath::Pi() * ls.OneMinusCos;
      // No ray from the light comes within `reach` of the box's centre before distance - reach:
      // the photons start there (photon_generate), in float near the box instead of at a
      // far light's position, where rounding lost the box (a light 1e8 away emitted nothing).
      ls.Lead = inside ? 0.0 : std::max(0.0, distance - reach);
      for (int c = 0; c < 3; ++c)
      {
        ls.Origin[c] = p[c] + ls.Lead * ls.Axis[c];
      }
    }
    ls.Bound = maxColour * ls.Measure;
    if (ls.Bound > 0)
    {
      lights.push_back(ls);
    }
  }
  return this->SetUpEnvironment(run);
}

//------------------------------------------------------------------------------
// Lobes only where they change the image: two lights or more (the sky counting as one) over a
// medium that scatters with g != 0. A light's direction is its travel direction towards the box
// the lights aim at (the sky's: down its up axis), its strength the power it sends there.
void vtkPhotonTracer::AssignLobes(Internals& run)
{
  const auto& lights = run.Lights;
  const int count = static_cast<int>(lights.size());
  run.Lobes = count >= 2 && run.M.Scatters && ScattersAnisotropically(run.M)
    ? std::min(this->MaximumRadianceLobes, count)
    : 1;
  this->LastNumberOfLobes = run.Lobes;
  run.LightLobes.assign(count, 0);
  if (run.Lobes < 2)
  {
    return;
  }
  std::vector<std::array<double, 3>> travel(count);
  std::vector<double> strength(count);
  for (int l = 0; l < count; ++l)
  {
    const LightSetup& ls = lights[l];
    for (int c = 0; c < 3; ++c)
    {
      const double position = ls.Origin[c] - ls.Lead * ls.Axis[c];
      travel[l][c] = ls.Environment ? -run.Env.Up[c]
        : ls.Positional             ? 0.5 * (run.EmitLo[c] + run.EmitHi[c]) - position
                                    : ls.Axis[c];
    }
    if (!Normalize(travel[l].data()))
    {
      travel[l] = { 0.0, 0.0, -1.0 }; // a light at the centre: any direction
    }
    strength[l] = ls.Bound;
  }
  run.LightLobes = GroupLightsByDirection(travel, strength, run.Lobes);
}
