#include "vtkRefractaBVH.h"

#include "vtkObjectFactory.h"

#include "refracta_surfaces.cl" // the flattened layout, shared with the kernels

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

vtkStandardNewMacro(vtkRefractaBVH);

namespace
{
constexpr int SahBins = 16;
constexpr vtkIdType SmallLeaf = 2; // always a leaf at or below this
constexpr vtkIdType LargeLeaf = 8; // a leaf up to this when no split is cheaper
constexpr double Infinity = std::numeric_limits<double>::infinity();

struct Box
{
  double Lo[3] = { Infinity, Infinity, Infinity };
  double Hi[3] = { -Infinity, -Infinity, -Infinity };
  void Grow(const double p[3])
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Lo[a] = std::min(this->Lo[a], p[a]);
      this->Hi[a] = std::max(this->Hi[a], p[a]);
    }
  }
  void Grow(const Box& b)
  {
    this->Grow(b.Lo);
    this->Grow(b.Hi);
  }
  double HalfArea() const
  {
    const double dx = this->Hi[0] - this->Lo[0];
    const double dy = this->Hi[1] - this->Lo[1];
    const double dz = this->Hi[2] - this->Lo[2];
    return dx < 0 ? 0.0 : dx * dy + dy * dz + dz * dx;
  }
};

// Largest float <= x and smallest float >= x: boxes rounded outwards contain the double geometry.
float FloatDown(double x)
{
  float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity())
                                    : f;
}
float FloatUp(double x)
{
  float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

float IntBits(int value)
{
  float f;
  std::memcpy(&f, &value, sizeof(f));
  return f;
}
int FloatBits(float value)
{
  int i;
  std::memcpy(&i, &value, sizeof(i));
  return i;
}

// A ray sheared for the watertight test (Woop, Benthin and Wald 2013), in double.
struct ShearedRay
{
  double O[3];
  double InvD[3];
  int Kx, Ky, Kz;
  double Sx, Sy, Sz;

  ShearedRay(const double origin[3], const double d[3])
  {
    for (int a = 0; a < 3; ++a)
    {
      this->O[a] = origin[a];
      this->InvD[a] = 1.0 / d[a];
    }
    const double ax = std::fabs(d[0]), ay = std::fabs(d[1]), az = std::fabs(d[2]);
    this->Kz = (ax > ay) ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    this->Kx = this->Kz == 2 ? 0 : this->Kz + 1;
    this->Ky = this->Kx == 2 ? 0 : this->Kx + 1;
    if (d[this->Kz] < 0)
    {
      std::swap(this->Kx, this->Ky);
    }
    this->Sx = d[this->Kx] / d[this->Kz];
    this->Sy = d[this->Ky] / d[this->Kz];
    this->Sz = 1.0 / d[this->Kz];
  }

  bool Hit(const double* p0, const double* p1, const double* p2, double tMax, double hit[3]) const
  {
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; ++k)
    {
      a[k] = p0[k] - this->O[k];
      b[k] = p1[k] - this->O[k];
      c[k] = p2[k] - this->O[k];
    }
    const double ax = a[this->Kx] - this->Sx * a[this->Kz];
    const double ay = a[this->Ky] - this->Sy * a[this->Kz];
    const double bx = b[this->Kx] - this->Sx * b[this->Kz];
    const double by = b[this->Ky] - this->Sy * b[this->Kz];
    const double cx = c[this->Kx] - this->Sx * c[this->Kz];
    const double cy = c[this->Ky] - this->Sy * c[this->Kz];
    // Products first, then the difference: the edge shared by two triangles gives exactly
    // opposite values in both (no fused multiply-add may change one of them).
    const double u1 = cx * by, u2 = cy * bx;
    const double v1 = ax * cy, v2 = ay * cx;
    const double w1 = bx * ay, w2 = by * ax;
    const double U = u1 - u2, V = v1 - v2, W = w1 - w2;
    if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0))
    {
      return false;
    }
    const double det = U + V + W;
    if (det == 0)
    {
      return false;
    }
    const double T =
      U * (this->Sz * a[this->Kz]) + V * (this->Sz * b[this->Kz]) + W * (this->Sz * c[this->Kz]);
    const double t = T / det;
    if (!(t > 0) || !(t < tMax))
    {
      return false;
    }
    hit[0] = t;
    hit[1] = V / det;
    hit[2] = W / det;
    return true;
  }

  // Entry distance into the float box of a node when the ray enters before tMax, else infinity.
  double Entry(const float* node, double tMax) const
  {
    double enter = 0.0, leave = Infinity;
    for (int a = 0; a < 3; ++a)
    {
      const double ta = (node[a] - this->O[a]) * this->InvD[a];
      const double tb = (node[4 + a] - this->O[a]) * this->InvD[a];
      enter = std::fmax(enter, std::fmin(ta, tb));
      leave = std::fmin(leave, std::fmax(ta, tb));
    }
    leave *= 1.0 + 1e-12; // conservative: a ray grazing a face is not rejected by rounding
    return (enter <= leave && enter < tMax) ? enter : Infinity;
  }
};
}

//------------------------------------------------------------------------------
struct vtkRefractaBVH::Builder
{
  const double* Vertices;
  std::vector<Box> Boxes;
  std::vector<std::array<double, 3>> Centroids;
  std::vector<vtkIdType> Index;
  std::vector<float>& Nodes;
  int MaxDepth = 0;

  Builder(const double* vertices, vtkIdType n, std::vector<float>& nodes)
    : Vertices(vertices)
    , Boxes(n)
    , Centroids(n)
    , Index(n)
    , Nodes(nodes)
  {
    for (vtkIdType t = 0; t < n; ++t)
    {
      const double* v = vertices + 9 * t;
      for (int k = 0; k < 3; ++k)
      {
        this->Boxes[t].Grow(v + 3 * k);
      }
      for (int a = 0; a < 3; ++a)
      {
        this->Centroids[t][a] = (v[a] + v[3 + a] + v[6 + a]) / 3.0;
      }
      this->Index[t] = t;
    }
  }

  // Appends a node (box rounded outwards) and returns its index.
  vtkIdType EmitNode(const Box& box)
  {
    const vtkIdType k = static_cast<vtkIdType>(this->Nodes.size() / 8);
    for (int a = 0; a < 3; ++a)
    {
      this->Nodes.push_back(FloatDown(box.Lo[a]));
    }
    this->Nodes.push_back(IntBits(0));
    for (int a = 0; a < 3; ++a)
    {
      this->Nodes.push_back(FloatUp(box.Hi[a]));
    }
    this->Nodes.push_back(IntBits(0));
    return k;
  }

  void SetLeaf(vtkIdType node, vtkIdType first, vtkIdType count)
  {
    this->Nodes[8 * node + 3] = IntBits(static_cast<int>(first));
    this->Nodes[8 * node + 7] = IntBits(static_cast<int>(count));
  }

  // Binned SAH split of [begin, end): the partition point, or -1 when a leaf is cheaper.
  vtkIdType SahSplit(vtkIdType begin, vtkIdType end, const Box& bounds)
  {
    Box centroidBox;
    for (vtkIdType i = begin; i < end; ++i)
    {
      centroidBox.Grow(this->Centroids[this->Index[i]].data());
    }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      if (centroidBox.Hi[a] - centroidBox.Lo[a] > centroidBox.Hi[axis] - centroidBox.Lo[axis])
      {
        axis = a;
      }
    }
    const double lo = centroidBox.Lo[axis];
    const double extent = centroidBox.Hi[axis] - lo;
    if (!(extent > 0))
    {
      return -1; // all centroids coincide: the caller splits by order
    }
    const double scale = SahBins / extent;
    auto binOf = [&](vtkIdType t)
    { return std::min(SahBins - 1, static_cast<int>((this->Centroids[t][axis] - lo) * scale)); };
    std::array<Box, SahBins> binBox;
    std::array<vtkIdType, SahBins> binCount{};
    for (vtkIdType i = begin; i < end; ++i)
    {
      const int b = binOf(this->Index[i]);
      binBox[b].Grow(this->Boxes[this->Index[i]]);
      ++binCount[b];
    }
    // Sweep from the right for the right-hand areas, then from the left for the costs.
    std::array<double, SahBins> rightArea{};
    std::array<vtkIdType, SahBins> rightCount{};
    Box acc;
    vtkIdType count = 0;
    for (int b = SahBins - 1; b > 0; --b)
    {
      acc.Grow(binBox[b]);
      count += binCount[b];
      rightArea[b] = acc.HalfArea();
      rightCount[b] = count;
    }
    Box left;
    vtkIdType leftCount = 0;
    double bestCost = Infinity;
    int bestSplit = -1;
    for (int b = 1; b < SahBins; ++b)
    {
      left.Grow(binBox[b - 1]);
      leftCount += binCount[b - 1];
      if (leftCount == 0 || rightCount[b] == 0)
      {
        continue;
      }
      const double cost = left.HalfArea() * leftCount + rightArea[b] * rightCount[b];
      if (cost < bestCost)
      {
        bestCost = cost;
        bestSplit = b;
      }
    }
    const vtkIdType n = end - begin;
    const double area = bounds.HalfArea();
    const double relativeCost = area > 0 ? 1.0 + bestCost / area : Infinity;
    if (bestSplit < 0 || (relativeCost >= static_cast<double>(n) && n <= LargeLeaf))
    {
      return n <= LargeLeaf ? end : -1; // end: a leaf
    }
    auto middle = std::partition(this->Index.begin() + begin, this->Index.begin() + end,
      [&](vtkIdType t) { return binOf(t) < bestSplit; });
    return static_cast<vtkIdType>(middle - this->Index.begin());
  }

  void Build(vtkIdType begin, vtkIdType end, int depth)
  {
    Box bounds;
    for (vtkIdType i = begin; i < end; ++i)
    {
      bounds.Grow(this->Boxes[this->Index[i]]);
    }
    const vtkIdType node = this->EmitNode(bounds);
    this->MaxDepth = std::max(this->MaxDepth, depth);
    const vtkIdType n = end - begin;
    vtkIdType split = end;
    if (n > SmallLeaf && depth < REFRACTA_BVH_MAX_DEPTH)
    {
      split = this->SahSplit(begin, end, bounds);
      if (split < 0)
      {
        split = begin + n / 2; // unbinnable and too many for a leaf: split by order
      }
    }
    if (split <= begin || split >= end)
    {
      this->SetLeaf(node, begin, n);
      return;
    }
    this->Build(begin, split, depth + 1);
    const vtkIdType second = static_cast<vtkIdType>(this->Nodes.size() / 8);
    this->Nodes[8 * node + 3] = IntBits(static_cast<int>(second));
    this->Build(split, end, depth + 1);
  }
};

//------------------------------------------------------------------------------
vtkRefractaBVH::vtkRefractaBVH() = default;
vtkRefractaBVH::~vtkRefractaBVH() = default;

//------------------------------------------------------------------------------
void vtkRefractaBVH::Build(const double* vertices, vtkIdType numberOfTriangles)
{
  const auto start = std::chrono::steady_clock::now();
  this->Nodes.clear();
  this->FloatTriangles.clear();
  this->Triangles.clear();
  this->Order.clear();
  this->Depth = 0;
  this->NumberOfTriangles = std::max<vtkIdType>(numberOfTriangles, 0);
  Box all;
  for (vtkIdType i = 0; i < 3 * this->NumberOfTriangles; ++i)
  {
    all.Grow(vertices + 3 * i);
  }
  for (int a = 0; a < 3; ++a)
  {
    this->Bounds[2 * a] = all.Lo[a];
    this->Bounds[2 * a + 1] = all.Hi[a];
    this->FrameOrigin[a] = this->NumberOfTriangles > 0 ? 0.5 * (all.Lo[a] + all.Hi[a]) : 0.0;
  }
  if (this->NumberOfTriangles > 0)
  {
    // Shift into the frame first, so that node boxes and device triangles share one frame.
    std::vector<double> shifted(vertices, vertices + 9 * this->NumberOfTriangles);
    for (size_t i = 0; i < shifted.size(); ++i)
    {
      shifted[i] -= this->FrameOrigin[i % 3];
    }
    Builder builder(shifted.data(), this->NumberOfTriangles, this->Nodes);
    builder.Build(0, this->NumberOfTriangles, 0);
    this->Depth = builder.MaxDepth;
    this->Order = builder.Index;
    this->Triangles.resize(9 * this->NumberOfTriangles);
    this->FloatTriangles.assign(12 * this->NumberOfTriangles, 0.0f);
    for (vtkIdType k = 0; k < this->NumberOfTriangles; ++k)
    {
      const double* v = shifted.data() + 9 * this->Order[k];
      std::copy(v, v + 9, this->Triangles.begin() + 9 * k);
      for (int c = 0; c < 9; ++c)
      {
        this->FloatTriangles[12 * k + 4 * (c / 3) + c % 3] = static_cast<float>(v[c]);
      }
    }
  }
  this->BuildSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  this->Modified();
}

//------------------------------------------------------------------------------
bool vtkRefractaBVH::IntersectTriangle(const double origin[3], const double direction[3],
  const double p0[3], const double p1[3], const double p2[3], double tMax, double hit[3])
{
  const ShearedRay ray(origin, direction);
  return ray.Hit(p0, p1, p2, tMax, hit);
}

//------------------------------------------------------------------------------
vtkIdType vtkRefractaBVH::IntersectRay(
  const double origin[3], const double direction[3], double tMax, double hit[3]) const
{
  if (this->Nodes.empty())
  {
    return -1;
  }
  const double o[3] = { origin[0] - this->FrameOrigin[0], origin[1] - this->FrameOrigin[1],
    origin[2] - this->FrameOrigin[2] };
  const ShearedRay ray(o, direction);
  const float* nodes = this->Nodes.data();
  const double* tri = this->Triangles.data();
  double best = tMax;
  vtkIdType found = -1;
  int stack[REFRACTA_BVH_STACK_SIZE];
  int top = 0;
  int node = ray.Entry(nodes, best) < Infinity ? 0 : -1;
  while (node >= 0)
  {
    const float* n = nodes + 8 * node;
    const int count = FloatBits(n[7]);
    const int a = FloatBits(n[3]);
    bool descended = false;
    if (count > 0)
    {
      for (int k = a; k < a + count; ++k)
      {
        double h[3];
        if (ray.Hit(tri + 9 * k, tri + 9 * k + 3, tri + 9 * k + 6, best, h))
        {
          best = h[0];
          hit[0] = h[0];
          hit[1] = h[1];
          hit[2] = h[2];
          found = k;
        }
      }
    }
    else
    {
      int nearChild = node + 1, farChild = a;
      double e0 = ray.Entry(nodes + 8 * nearChild, best);
      double e1 = ray.Entry(nodes + 8 * farChild, best);
      if (e1 < e0)
      {
        std::swap(nearChild, farChild);
        std::swap(e0, e1);
      }
      if (e0 < Infinity)
      {
        if (e1 < Infinity)
        {
          stack[top++] = farChild;
        }
        node = nearChild;
        descended = true;
      }
    }
    if (!descended)
    {
      node = -1;
      while (top > 0)
      {
        const int candidate = stack[--top];
        if (ray.Entry(nodes + 8 * candidate, best) < Infinity)
        {
          node = candidate;
          break;
        }
      }
    }
  }
  return found;
}

//------------------------------------------------------------------------------
bool vtkRefractaBVH::Occluded(const double origin[3], const double direction[3], double tMax) const
{
  if (this->Nodes.empty())
  {
    return false;
  }
  const double o[3] = { origin[0] - this->FrameOrigin[0], origin[1] - this->FrameOrigin[1],
    origin[2] - this->FrameOrigin[2] };
  const ShearedRay ray(o, direction);
  const float* nodes = this->Nodes.data();
  const double* tri = this->Triangles.data();
  int stack[REFRACTA_BVH_STACK_SIZE + 2];
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const int node = stack[--top];
    const float* n = nodes + 8 * node;
    if (!(ray.Entry(n, tMax) < Infinity))
    {
      continue;
    }
    const int count = FloatBits(n[7]);
    const int a = FloatBits(n[3]);
    if (count > 0)
    {
      for (int k = a; k < a + count; ++k)
      {
        double h[3];
        if (ray.Hit(tri + 9 * k, tri + 9 * k + 3, tri + 9 * k + 6, tMax, h))
        {
          return true;
        }
      }
    }
    else
    {
      stack[top++] = a;
      stack[top++] = node + 1;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
void vtkRefractaBVH::GetBounds(double bounds[6]) const
{
  std::copy(this->Bounds, this->Bounds + 6, bounds);
}

//------------------------------------------------------------------------------
void vtkRefractaBVH::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfTriangles: " << this->NumberOfTriangles << "\n";
  os << indent << "NumberOfNodes: " << this->GetNumberOfNodes() << "\n";
  os << indent << "Depth: " << this->Depth << "\n";
  os << indent << "BuildSeconds: " << this->BuildSeconds << "\n";
  os << indent << "FrameOrigin: (" << this->FrameOrigin[0] << ", " << this->FrameOrigin[1] << ", "
     << this->FrameOrigin[2] << ")\n";
}
