#include "vtkRefractaDielectric.h"

#include "vtkObjectFactory.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkRefractaDielectric);

namespace
{
double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void Normalize(double a[3])
{
  const double l = std::sqrt(Dot(a, a));
  if (l > 0)
  {
    a[0] /= l;
    a[1] /= l;
    a[2] /= l;
  }
}
}

//------------------------------------------------------------------------------
double vtkRefractaDielectric::FresnelReflectance(double cosI, double etaI, double etaT)
{
  const double c = std::min(1.0, std::max(0.0, cosI));
  const double eta = etaI / etaT;
  const double sin2T = eta * eta * std::max(0.0, 1.0 - c * c);
  if (sin2T >= 1.0)
  {
    return 1.0;
  }
  const double cosT = std::sqrt(1.0 - sin2T);
  const double rs = (etaI * c - etaT * cosT) / (etaI * c + etaT * cosT);
  const double rp = (etaI * cosT - etaT * c) / (etaI * cosT + etaT * c);
  return 0.5 * (rs * rs + rp * rp);
}

//------------------------------------------------------------------------------
void vtkRefractaDielectric::Reflect(const double d[3], const double n[3], double r[3])
{
  const double k = 2.0 * Dot(d, n);
  for (int a = 0; a < 3; ++a)
  {
    r[a] = d[a] - k * n[a];
  }
}

//------------------------------------------------------------------------------
bool vtkRefractaDielectric::Refract(const double d[3], const double nf[3], double eta, double t[3])
{
  const double cosI = -Dot(d, nf);
  const double sin2T = eta * eta * std::max(0.0, 1.0 - cosI * cosI);
  if (sin2T >= 1.0)
  {
    return false;
  }
  const double cosT = std::sqrt(1.0 - sin2T);
  for (int a = 0; a < 3; ++a)
  {
    t[a] = eta * d[a] + (eta * cosI - cosT) * nf[a];
  }
  Normalize(t);
  return true;
}

//------------------------------------------------------------------------------
vtkRefractaDielectric::Event vtkRefractaDielectric::Sample(const double d[3], const double ng[3],
  const double ns[3], double nInside, double nOutside, double xi)
{
  Event e;
  const bool entering = Dot(d, ng) < 0.0;
  e.EtaFrom = entering ? nOutside : nInside;
  e.EtaTo = entering ? nInside : nOutside;
  const double sign = entering ? 1.0 : -1.0;
  const double fg[3] = { sign * ng[0], sign * ng[1], sign * ng[2] };
  const double fs[3] = { sign * ns[0], sign * ns[1], sign * ns[2] };
  const double* nf = Dot(d, fs) < 0.0 ? fs : fg;
  std::copy(d, d + 3, e.Direction);
  for (int attempt = 0; attempt < 2; ++attempt)
  {
    e.Reflectance = FresnelReflectance(-Dot(d, nf), e.EtaFrom, e.EtaTo);
    e.Transmitted = !(xi < e.Reflectance) && Refract(d, nf, e.EtaFrom / e.EtaTo, e.Direction);
    if (!e.Transmitted)
    {
      Reflect(d, nf, e.Direction);
    }
    const double side = Dot(e.Direction, fg);
    if ((e.Transmitted ? side < 0.0 : side > 0.0) || attempt == 1)
    {
      break;
    }
    nf = fg;
  }
  return e;
}

//------------------------------------------------------------------------------
void vtkRefractaDielectric::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
