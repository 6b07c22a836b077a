// SharpSphereTrace.h: an independent geometric-optics trace of a sharp glass ball (Snell's law
// in vector form, written apart from the passes and vtkRefractaDielectric), shared by the photon
// tests of the smoothed-index and of the exact-interface ball lens.
#ifndef SharpSphereTrace_h
#define SharpSphereTrace_h

#include <cmath>

namespace photontest
{
// Exact trace of a ray parallel to -z at height rho through the sharp sphere (radius R, index n,
// centre 0): its distance from the axis where it crosses the plane z = -D.
inline double SharpSphereRadiusAt(double rho, double radius, double n, double D)
{
  // Entry point and normal; refraction by Snell's law in vector form.
  auto refract = [](const double d[3], const double nn[3], double eta, double out[3])
  {
    const double c = -(d[0] * nn[0] + d[1] * nn[1] + d[2] * nn[2]);
    const double k = 1 - eta * eta * (1 - c * c);
    for (int a = 0; a < 3; ++a)
    {
      out[a] = eta * d[a] + (eta * c - std::sqrt(k)) * nn[a];
    }
  };
  const double p[3] = { rho, 0, std::sqrt(radius * radius - rho * rho) };
  const double d0[3] = { 0, 0, -1 };
  const double n1[3] = { p[0] / radius, 0, p[2] / radius };
  double d1[3];
  refract(d0, n1, 1.0 / n, d1);
  // Second intersection: p + t d1 on the sphere, t = -2 p.d1.
  const double t = -2 * (p[0] * d1[0] + p[2] * d1[2]);
  const double q[3] = { p[0] + t * d1[0], 0, p[2] + t * d1[2] };
  const double n2[3] = { -q[0] / radius, 0, -q[2] / radius }; // inward normal at the exit
  double d2[3];
  refract(d1, n2, n, d2);
  const double s = (-D - q[2]) / d2[2];
  return std::fabs(q[0] + s * d2[0]);
}

// RMS spot radius on the plane z = -D of a uniform beam of radius a through the sharp sphere.
inline double SharpSphereRms(double a, double radius, double n, double D)
{
  double sum = 0, weight = 0;
  for (int i = 0; i < 2000; ++i)
  {
    const double rho = a * (i + 0.5) / 2000;
    const double r = SharpSphereRadiusAt(rho, radius, n, D);
    sum += r * r * rho;
    weight += rho;
  }
  return std::sqrt(sum / weight);
}

// Vertex of the parabola through three points (x, y).
inline double ParabolaVertex(const double x[3], const double y[3])
{
  const double d1 = (y[1] - y[0]) / (x[1] - x[0]), d2 = (y[2] - y[1]) / (x[2] - x[1]);
  const double c = (d2 - d1) / (x[2] - x[0]);
  return 0.5 * (x[0] + x[1]) - d1 / (2 * c);
}
}

#endif
