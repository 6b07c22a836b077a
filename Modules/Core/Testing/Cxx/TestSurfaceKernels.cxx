// Tests of Kernels/refracta_surfaces.cl on the OpenCL device: the texel index is bit-identical to
// vtkRefractaSurfaceSet::TexelIndex; the float BVH traversal finds the same closest triangle as
// the host's double traversal (a different one only on a near-tie at the same distance), and its
// any-hit query agrees; float rays aimed exactly at the shared edges and vertices of closed meshes
// never slip through.
#include "SurfaceTestMeshes.h"

#include "vtkOpenCLContext.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace
{
const std::vector<std::string> Files = { "refracta_surfaces.cl", "refracta_surfaces_tests.cl" };

struct DeviceHits
{
  std::vector<float> Hits; // t, u, v, triangle bits
  std::vector<int> Occluded;
  int Triangle(size_t i) const
  {
    int t;
    std::memcpy(&t, &this->Hits[4 * i + 3], sizeof(t));
    return t;
  }
};

// Traces rays (surface frame, float4 each) through the BVH on the device.
DeviceHits Trace(vtkOpenCLContext* context, vtkRefractaBVH* bvh, const std::vector<float>& origins,
  const std::vector<float>& directions, const std::vector<float>& tMax)
{
  DeviceHits result;
  cl_program program = context->GetProgram(Files, "");
  EXPECT_NE(program, nullptr) << context->GetLastErrorMessage();
  if (!program)
  {
    return result;
  }
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_test_trace");
  const cl_uint n = static_cast<cl_uint>(tMax.size());
  const auto& nodes = bvh->GetNodes();
  const auto& tri = bvh->GetFloatTriangles();
  vtkOpenCLBuffer nb =
    context->CreateBuffer(CL_MEM_READ_ONLY, nodes.size() * 4, (void*)nodes.data(), "nodes");
  vtkOpenCLBuffer tb =
    context->CreateBuffer(CL_MEM_READ_ONLY, tri.size() * 4, (void*)tri.data(), "triangles");
  vtkOpenCLBuffer ob =
    context->CreateBuffer(CL_MEM_READ_ONLY, origins.size() * 4, (void*)origins.data(), "o");
  vtkOpenCLBuffer db =
    context->CreateBuffer(CL_MEM_READ_ONLY, directions.size() * 4, (void*)directions.data(), "d");
  vtkOpenCLBuffer mb = context->CreateBuffer(CL_MEM_READ_ONLY, n * 4, (void*)tMax.data(), "tmax");
  vtkOpenCLBuffer hb = context->CreateBuffer(CL_MEM_WRITE_ONLY, n * 16, nullptr, "hits");
  vtkOpenCLBuffer cb = context->CreateBuffer(CL_MEM_WRITE_ONLY, n * 4, nullptr, "occluded");
  const cl_int nodeCount = static_cast<cl_int>(bvh->GetNumberOfNodes());
  EXPECT_EQ(vtkOpenCLSetKernelArgs(kernel.Get(), nb.Get(), nodeCount, tb.Get(), ob.Get(), db.Get(),
              mb.Get(), hb.Get(), cb.Get(), n),
    CL_SUCCESS);
  const size_t global = n;
  EXPECT_TRUE(context->RunKernel(kernel.Get(), 1, &global, nullptr, "trace"));
  result.Hits.resize(4 * size_t(n));
  result.Occluded.resize(n);
  EXPECT_TRUE(context->ReadBuffer(hb.Get(), result.Hits.size() * 4, result.Hits.data()));
  EXPECT_TRUE(context->ReadBuffer(cb.Get(), result.Occluded.size() * 4, result.Occluded.data()));
  return result;
}

vtkSmartPointer<vtkRefractaBVH> BuildBVH(const std::vector<double>& tri)
{
  auto bvh = vtkSmartPointer<vtkRefractaBVH>::New();
  bvh->Build(tri.data(), static_cast<vtkIdType>(tri.size() / 9));
  return bvh;
}
}

TEST(SurfaceKernels, TexelIndexMatchesHost)
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  ASSERT_TRUE(context->Initialize());
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> subdivision(1, 300);
  std::uniform_real_distribution<float> unit(-0.05f, 1.05f);
  const cl_uint n = 200000;
  std::vector<float> uv(2 * n);
  std::vector<int> sub(n);
  for (cl_uint i = 0; i < n; ++i)
  {
    sub[i] = subdivision(rng);
    if (i % 4 == 0)
    {
      // Exactly on texel boundaries: u = k / n and u + v = m / n.
      std::uniform_int_distribution<int> k(0, sub[i]);
      const float u = float(k(rng)) / float(sub[i]);
      uv[2 * i] = u;
      uv[2 * i + 1] = std::max(0.0f, float(k(rng)) / float(sub[i]) - (i % 8 == 0 ? u : 0.0f));
    }
    else
    {
      const float u = unit(rng), v = unit(rng);
      uv[2 * i] = u;
      uv[2 * i + 1] = (i % 3 == 0) ? 1.0f - u : v; // on the hypotenuse, or anywhere
    }
  }
  cl_program program = context->GetProgram(Files, "");
  ASSERT_NE(program, nullptr) << context->GetLastErrorMessage();
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_test_texel");
  vtkOpenCLBuffer ub = context->CreateBuffer(CL_MEM_READ_ONLY, uv.size() * 4, uv.data(), "uv");
  vtkOpenCLBuffer sb = context->CreateBuffer(CL_MEM_READ_ONLY, n * 4, sub.data(), "n");
  vtkOpenCLBuffer out = context->CreateBuffer(CL_MEM_WRITE_ONLY, n * 4, nullptr, "texel");
  ASSERT_EQ(vtkOpenCLSetKernelArgs(kernel.Get(), ub.Get(), sb.Get(), out.Get(), n), CL_SUCCESS);
  const size_t global = n;
  ASSERT_TRUE(context->RunKernel(kernel.Get(), 1, &global, nullptr, "texel"));
  std::vector<int> device(n);
  ASSERT_TRUE(context->ReadBuffer(out.Get(), n * 4, device.data()));
  int mismatches = 0;
  for (cl_uint i = 0; i < n; ++i)
  {
    const int host = vtkRefractaSurfaceSet::TexelIndex(uv[2 * i], uv[2 * i + 1], sub[i]);
    mismatches += host != device[i] ? 1 : 0;
    ASSERT_GE(device[i], 0);
    ASSERT_LT(device[i], sub[i] * sub[i]);
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(SurfaceKernels, ClosestHitMatchesHost)
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  ASSERT_TRUE(context->Initialize());
  const double offset[3] = { 500.0, -20.0, 7.0 };
  const auto soup = surface_test::RandomSoup(4000, 0.15, offset, 23);
  auto bvh = BuildBVH(soup);
  const double* frame = bvh->GetFrameOrigin();
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> box(-1.5, 1.5);
  std::normal_distribution<double> gauss;
  const int n = 20000;
  std::vector<float> origins(4 * n, 0.0f), dirs(4 * n, 0.0f), tMax(n);
  for (int i = 0; i < n; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      origins[4 * i + a] = static_cast<float>(offset[a] + box(rng) - frame[a]);
      dirs[4 * i + a] = static_cast<float>(gauss(rng));
    }
    tMax[i] = (i % 2 == 0) ? std::numeric_limits<float>::infinity() : 0.5f;
  }
  const DeviceHits device = Trace(context, bvh, origins, dirs, tMax);
  ASSERT_EQ(device.Occluded.size(), size_t(n));
  int hits = 0, sameTriangle = 0, disagreements = 0;
  for (int i = 0; i < n; ++i)
  {
    const double o[3] = { origins[4 * i] + frame[0], origins[4 * i + 1] + frame[1],
      origins[4 * i + 2] + frame[2] };
    const double d[3] = { dirs[4 * i], dirs[4 * i + 1], dirs[4 * i + 2] };
    double hit[3];
    const vtkIdType host = bvh->IntersectRay(o, d, tMax[i], hit);
    const int dev = device.Triangle(i);
    EXPECT_EQ(device.Occluded[i], dev >= 0 ? 1 : 0)
      << "any hit and closest hit disagree, ray " << i;
    if (host < 0 && dev < 0)
    {
      continue;
    }
    ++hits;
    if (host == dev)
    {
      ++sameTriangle;
      EXPECT_NEAR(device.Hits[4 * i], hit[0], 1e-5 * (1 + hit[0])) << "ray " << i;
      EXPECT_NEAR(device.Hits[4 * i + 1], hit[1], 1e-3) << "ray " << i;
      EXPECT_NEAR(device.Hits[4 * i + 2], hit[2], 1e-3) << "ray " << i;
    }
    else if (host >= 0 && dev >= 0 && std::fabs(device.Hits[4 * i] - hit[0]) < 1e-5 * (1 + hit[0]))
    {
      ++sameTriangle; // a near-tie between two triangles at the same distance
    }
    else
    {
      ++disagreements; // a grazing hit or a hit at tMax decided differently in float
    }
  }
  EXPECT_GT(hits, n / 4);
  EXPECT_LE(disagreements, n / 5000) << "of " << hits << " hits";
  std::cout << "device/host closest hits: " << sameTriangle << " agree, " << disagreements
            << " differ (of " << hits << ")\n";
}

TEST(SurfaceKernels, WatertightInFloat)
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  ASSERT_TRUE(context->Initialize());
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(3.25, 100.5, -7);
  sphere->SetRadius(1.5);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(13);
  sphere->Update();
  const double lo[3] = { -1, -2, -0.5 }, hi[3] = { 1, 2, 0.5 };
  auto box = surface_test::ClosedBox(lo, hi);
  for (vtkPolyData* mesh : { sphere->GetOutput(), box.GetPointer() })
  {
    auto bvh = BuildBVH(surface_test::Triangles(mesh));
    const auto& tri = bvh->GetFloatTriangles();
    // Targets: every float vertex and the float midpoint of every edge (surface frame).
    std::vector<float> targets;
    for (size_t t = 0; t < tri.size(); t += 12)
    {
      for (int k = 0; k < 3; ++k)
      {
        const float* p = &tri[t + 4 * k];
        const float* q = &tri[t + 4 * ((k + 1) % 3)];
        targets.insert(targets.end(), p, p + 3);
        for (int a = 0; a < 3; ++a)
        {
          targets.push_back(0.5f * (p[a] + q[a]));
        }
      }
    }
    std::vector<float> origins, dirs, tMax;
    std::mt19937 rng(5);
    std::normal_distribution<float> gauss;
    for (int o = 0; o < 12; ++o)
    {
      // Four origins near the centre (inside), eight far outside (then only the targets where
      // the ray crosses into the mesh, not its silhouette, count).
      const bool inside = o < 4;
      float origin[3];
      for (int a = 0; a < 3; ++a)
      {
        origin[a] = (inside ? 0.1f : 10.0f) * gauss(rng);
      }
      const double od[3] = { origin[0], origin[1], origin[2] };
      for (size_t i = 0; i < targets.size(); i += 3)
      {
        const double target[3] = { targets[i], targets[i + 1], targets[i + 2] };
        if (!inside && !surface_test::CrossesAt(tri, 12, target, od))
        {
          continue;
        }
        origins.insert(origins.end(), { origin[0], origin[1], origin[2], 0.0f });
        dirs.insert(dirs.end(),
          { targets[i] - origin[0], targets[i + 1] - origin[1], targets[i + 2] - origin[2], 0.0f });
        tMax.push_back(std::numeric_limits<float>::infinity());
      }
    }
    EXPECT_GT(tMax.size(), targets.size() / 3 * 6);
    // Axis-aligned rays (zero direction components) exactly through the shared diagonal of the
    // box's bottom face (the box is centred on the frame origin).
    if (mesh == box.GetPointer())
    {
      for (float s : { 0.25f, 0.5f, 0.75f })
      {
        const float x = s * float(lo[0]) + (1 - s) * float(hi[0]);
        const float y = s * float(lo[1]) + (1 - s) * float(hi[1]);
        origins.insert(origins.end(), { x, y, -5.0f, 0.0f });
        dirs.insert(dirs.end(), { 0.0f, 0.0f, 1.0f, 0.0f });
        tMax.push_back(std::numeric_limits<float>::infinity());
      }
    }
    const DeviceHits device = Trace(context, bvh, origins, dirs, tMax);
    int leaks = 0;
    for (size_t i = 0; i < tMax.size(); ++i)
    {
      leaks += (device.Triangle(i) < 0 || device.Occluded[i] == 0) ? 1 : 0;
    }
    EXPECT_EQ(leaks, 0) << "of " << tMax.size() << " rays";
  }
}
