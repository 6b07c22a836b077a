#include "RefractaIdealGlass.h"

#include <algorithm>
#include <cmath>

namespace RefractaIdealGlass
{
const V3 BallCentre = { 0.0, 0.05, 0.0 };
const double BallRadius = 0.42;
const double Index = 1.5;
const double FloorY = -0.8;
const V3 LightPosition = { 0.0, 3.0, 0.0 };
const double ConeDegrees = 12.0;
const double BoxMin[3] = { -1.0, -0.9, -1.0 };
const double BoxMax[3] = { 1.0, 1.0, 1.0 };

namespace
{
const double Pi = 3.14159265358979323846;

// Follows a ray of power w through the ball (both Fresnel branches, up to `depth` interfaces).
void Follow(const V3& o, const V3& d, double w, bool inside, int depth,
  const std::function<void(const Beam&)>& visit)
{
  const double t = HitBall(o, d, inside);
  if (t < 0 || depth == 0)
  {
    if (!inside)
    {
      visit(Beam{ o, d, w });
    }
    return;
  }
  const V3 p = Add(o, d, t);
  V3 n = Unit(Add(p, BallCentre, -1.0));
  if (inside)
  {
    n = { -n[0], -n[1], -n[2] };
  }
  const double etaI = inside ? Index : 1.0, etaT = inside ? 1.0 : Index;
  const double cosI = -Dot(d, n);
  const double r = Fresnel(cosI, etaI, etaT);
  Follow(p, Add(d, n, 2 * cosI), w * r, inside, depth - 1, visit);
  if (r < 1)
  {
    const double eta = etaI / etaT;
    const double k = 1 - eta * eta * (1 - cosI * cosI);
    const V3 refracted =
      Unit(Add(V3{ eta * d[0], eta * d[1], eta * d[2] }, n, eta * cosI - std::sqrt(k)));
    Follow(p, refracted, w * (1 - r), !inside, depth - 1, visit);
  }
}
}

V3 Add(const V3& a, const V3& b, double s)
{
  return { a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2] };
}

double Dot(const V3& a, const V3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

V3 Unit(V3 a)
{
  const double l = std::sqrt(Dot(a, a));
  return { a[0] / l, a[1] / l, a[2] / l };
}

double Fresnel(double cosI, double etaI, double etaT)
{
  const double sinT = etaI / etaT * std::sqrt(std::max(0.0, 1.0 - cosI * cosI));
  if (sinT >= 1.0)
  {
    return 1.0;
  }
  const double cosT = std::sqrt(1.0 - sinT * sinT);
  const double rs = (etaI * cosI - etaT * cosT) / (etaI * cosI + etaT * cosT);
  const double rp = (etaI * cosT - etaT * cosI) / (etaI * cosT + etaT * cosI);
  return 0.5 * (rs * rs + rp * rp);
}

double HitBall(const V3& o, const V3& d, bool inside)
{
  const V3 oc = Add(o, BallCentre, -1.0);
  const double b = Dot(oc, d), c = Dot(oc, oc) - BallRadius * BallRadius;
  const double disc = b * b - c;
  if (disc <= 0)
  {
    return -1;
  }
  const double t = inside ? -b + std::sqrt(disc) : -b - std::sqrt(disc);
  return t > 1e-9 ? t : -1;
}

double SpotIntensity(const V3& d)
{
  return -d[1] >= std::cos(ConeDegrees * Pi / 180.0) ? -d[1] : 0.0;
}

double LengthInBox(const V3& o, const V3& d, double tMax)
{
  double t0 = 0, t1 = tMax;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0)
    {
      if (o[a] < BoxMin[a] || o[a] > BoxMax[a])
      {
        return 0;
      }
      continue;
    }
    double ta = (BoxMin[a] - o[a]) / d[a], tb = (BoxMax[a] - o[a]) / d[a];
    if (ta > tb)
    {
      std::swap(ta, tb);
    }
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return std::max(0.0, t1 - t0);
}

void TraceThroughBall(
  int rays, int depth, double fogExtinction, const std::function<void(const Beam&)>& visit)
{
  const double cosCone = std::cos(ConeDegrees * Pi / 180.0);
  const double domega = 2 * Pi * (1 - cosCone) / (double(rays) * rays);
  for (int a = 0; a < rays; ++a)
  {
    const double c = 1 - (a + 0.5) / rays * (1 - cosCone);
    const double sn = std::sqrt(1 - c * c);
    for (int b = 0; b < rays; ++b)
    {
      const double phi = 2 * Pi * (b + 0.5) / rays;
      const V3 d = { sn * std::cos(phi), -c, sn * std::sin(phi) };
      const double t = HitBall(LightPosition, d, false);
      if (t > 0)
      {
        const double fog = std::exp(-fogExtinction * LengthInBox(LightPosition, d, t));
        Follow(LightPosition, d, SpotIntensity(d) * domega * fog, false, depth, visit);
      }
    }
  }
}
}

namespace RefractaIdealGlass
{
double PhaseHG(double g, double cosTheta)
{
  const double denominator = 1 + g * g - 2 * g * cosTheta;
  return (1 - g * g) / (4 * 3.14159265358979323846 * denominator * std::sqrt(denominator));
}

V3 Pinhole::Ray(double x, double y) const
{
  const double sx = (2.0 * x / this->Size - 1.0) * this->Tan;
  const double sy = (2.0 * y / this->Size - 1.0) * this->Tan;
  return Unit(Add(Add(this->Forward, this->Right, sx), this->Up, sy));
}

bool Pinhole::Project(const V3& p, double& x, double& y) const
{
  const V3 v = Add(p, this->Eye, -1.0);
  const double z = Dot(v, this->Forward);
  if (z <= 0)
  {
    return false;
  }
  x = (Dot(v, this->Right) / (z * this->Tan) + 1.0) * 0.5 * this->Size;
  y = (Dot(v, this->Up) / (z * this->Tan) + 1.0) * 0.5 * this->Size;
  return true;
}

double Pinhole::PixelSolidAngle(int i, int j) const
{
  // The pixel spans 2 Tan / Size on the image plane at unit distance; it is seen at cos(alpha)
  // from the axis, and its solid angle is that area times cos^3(alpha).
  const double side = 2.0 * this->Tan / this->Size;
  const double c = Dot(this->Ray(i + 0.5, j + 0.5), this->Forward);
  return side * side * c * c * c;
}

IdealShaft::IdealShaft(const Pinhole& camera, const Fog& fog, const std::vector<double>& heights,
  double cell, double halfWidth, double halfDepth)
  : Image(static_cast<size_t>(camera.Size) * camera.Size, 0.0)
  , Heights(heights)
  , Cell(cell)
  , Nx(2 * static_cast<int>(std::ceil(halfWidth / cell)) + 1)
  , Nz(2 * static_cast<int>(std::ceil(halfDepth / cell)) + 1)
  , Camera(camera)
  , Medium(fog)
{
  this->Planes.assign(
    heights.size(), std::vector<double>(static_cast<size_t>(this->Nx) * this->Nz));
  this->Rings.assign(
    heights.size(), std::vector<double>(static_cast<size_t>(std::ceil(halfWidth / RingWidth))));
}

double IdealShaft::Length(const Beam& beam)
{
  // The origin lies on the ball, inside the box.
  const double length = LengthInBox(beam.Origin, beam.Direction, 1e9);
  return beam.Direction[1] < 0 ? std::min(length, (FloorY - beam.Origin[1]) / beam.Direction[1])
                               : length;
}

void IdealShaft::AddToPlanes(const Beam& beam)
{
  const V3& o = beam.Origin;
  const V3& d = beam.Direction;
  const double length = Length(beam);
  for (size_t k = 0; k < this->Heights.size(); ++k)
  {
    const double s = d[1] != 0 ? (this->Heights[k] - o[1]) / d[1] : -1.0;
    if (s >= 0 && s <= length)
    {
      const double x = o[0] + s * d[0], z = o[2] + s * d[2];
      const double phiArea = beam.Power * std::exp(-this->Medium.Extinction * s) / std::abs(d[1]);
      const int i = static_cast<int>(std::lround(x / this->Cell)) + this->Nx / 2;
      const int m = static_cast<int>(std::lround(z / this->Cell)) + this->Nz / 2;
      if (i >= 0 && i < this->Nx && m >= 0 && m < this->Nz)
      {
        this->Planes[k][i + static_cast<size_t>(this->Nx) * m] += phiArea;
      }
      const size_t ring = static_cast<size_t>(std::hypot(x, z) / this->RingWidth);
      if (ring < this->Rings[k].size())
      {
        this->Rings[k][ring] += phiArea;
      }
    }
  }
}

void IdealShaft::AddToImage(const Beam& beam)
{
  // Only below the ball's centre: rows below the ball see nothing higher inside the box.
  double length = Length(beam);
  if (beam.Direction[1] > 0)
  {
    length = std::min(length, (BallCentre[1] - beam.Origin[1]) / beam.Direction[1]);
  }
  if (length > 0)
  {
    this->Splat(beam, length);
  }
}

void IdealShaft::Splat(const Beam& beam, double length)
{
  const Pinhole& c = this->Camera;
  // Steps of at most half a pixel seen from 2 units (every point of the box below the ball is
  // farther from the eye).
  const int steps = static_cast<int>(std::ceil(length / (c.Tan / c.Size * 2.0))) + 1;
  const double ds = length / steps;
  const double sigmaT = this->Medium.Extinction;
  const double sigmaS = this->Medium.Albedo * sigmaT;
  const double stepTransmittance = std::exp(-sigmaT * ds);
  double light = beam.Power * std::exp(-sigmaT * 0.5 * ds);
  for (int n = 0; n < steps; ++n, light *= stepTransmittance)
  {
    const V3 p = Add(beam.Origin, beam.Direction, (n + 0.5) * ds);
    double x, y;
    if (!c.Project(p, x, y) || x < 0 || y < 0 || x >= c.Size || y >= c.Size)
    {
      continue;
    }
    const V3 toEye = Add(c.Eye, p, -1.0);
    const double r = std::sqrt(Dot(toEye, toEye));
    const V3 w = { toEye[0] / r, toEye[1] / r, toEye[2] / r };
    const double view = std::exp(-sigmaT * LengthInBox(p, w, r));
    const double phase = PhaseHG(this->Medium.Anisotropy, Dot(beam.Direction, w));
    this->Image[static_cast<size_t>(x) + static_cast<size_t>(c.Size) * static_cast<size_t>(y)] +=
      sigmaS * phase * light * view * ds / (r * r);
  }
}

void IdealShaft::Finish()
{
  for (int j = 0; j < this->Camera.Size; ++j)
  {
    for (int i = 0; i < this->Camera.Size; ++i)
    {
      this->Image[i + static_cast<size_t>(this->Camera.Size) * j] /=
        this->Camera.PixelSolidAngle(i, j);
    }
  }
  for (auto& plane : this->Planes)
  {
    for (double& phi : plane)
    {
      phi /= this->Cell * this->Cell;
    }
  }
}
}

namespace RefractaIdealGlass
{
double IdealShaft::EncircledRadius(int plane, double fraction) const
{
  const std::vector<double>& rings = this->Rings[plane];
  double total = 0;
  for (double r : rings)
  {
    total += r;
  }
  double sum = 0;
  for (size_t k = 0; k < rings.size(); ++k)
  {
    if (sum + rings[k] >= fraction * total && rings[k] > 0)
    {
      return (k + (fraction * total - sum) / rings[k]) * this->RingWidth;
    }
    sum += rings[k];
  }
  return rings.size() * this->RingWidth;
}
}

namespace RefractaIdealGlass
{
std::vector<double> IdealShaft::ProfileOnLattice(int plane, double h) const
{
  auto boxMean = [&](double x, double z)
  {
    double sum = 0;
    int count = 0;
    for (int m = 0; m < this->Nz; ++m)
    {
      if (std::abs((m - this->Nz / 2) * this->Cell - z) >= 0.5 * h)
      {
        continue;
      }
      for (int i = 0; i < this->Nx; ++i)
      {
        const double xc = (i - this->Nx / 2) * this->Cell;
        if (std::abs(xc - x) < 0.5 * h)
        {
          sum += this->Phi(plane, i, m);
          ++count;
        }
      }
    }
    return count ? sum / count : 0.0;
  };
  const int half = static_cast<int>((this->Nx / 2) * this->Cell / h) - 1;
  std::vector<double> line;
  for (int i = -half; i < half; ++i)
  {
    const double x = (i + 0.5) * h;
    line.push_back((boxMean(x, -1.5 * h) + 3 * boxMean(x, -0.5 * h) + 3 * boxMean(x, 0.5 * h) +
                     boxMean(x, 1.5 * h)) /
      8);
  }
  std::vector<double> smoothed(line.size(), 0.0);
  for (size_t i = 1; i + 1 < line.size(); ++i)
  {
    smoothed[i] = 0.25 * line[i - 1] + 0.5 * line[i] + 0.25 * line[i + 1];
  }
  return smoothed;
}
}
