// vtkRefractaGridFrame: world <-> index <-> grid-local, round trips, non-zero extents, rotated
// direction matrices, agreement with vtkImageData, and SameGrid.
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkRefractaGridFrame.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <utility>

namespace
{
// Rotation by `degrees` about `axis`.
void Rotation(double axisIn[3], double degrees, double r[9])
{
  double axis[3] = { axisIn[0], axisIn[1], axisIn[2] };
  vtkMath::Normalize(axis);
  const double a = vtkMath::RadiansFromDegrees(degrees), c = std::cos(a), s = std::sin(a);
  const double x = axis[0], y = axis[1], z = axis[2];
  const double m[9] = { c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s,
    y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s, z * x * (1 - c) - y * s,
    z * y * (1 - c) + x * s, c + z * z * (1 - c) };
  for (int i = 0; i < 9; ++i)
  {
    r[i] = m[i];
  }
}

vtkNew<vtkImageData> MakeImage(bool rotated)
{
  vtkNew<vtkImageData> image;
  image->SetExtent(10, 17, -3, 2, 5, 9);
  image->SetSpacing(0.5, 0.25, 2.0);
  image->SetOrigin(1.0, -2.0, 3.5);
  if (rotated)
  {
    double axis[3] = { 1, -2, 0.5 }, r[9];
    Rotation(axis, 33.0, r);
    image->SetDirectionMatrix(r);
  }
  return image;
}
} // namespace

TEST(RefractaGridFrame, IdentityExtentZero)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(4, 5, 6);
  image->SetSpacing(0.1, 0.2, 0.3);
  vtkNew<vtkRefractaGridFrame> frame;
  frame->SetImage(image);
  const double w[3] = { 0.25, 0.5, 0.9 };
  double l[3], idx[3];
  frame->WorldToLocalPoint(w, l);
  frame->WorldToIndexPoint(w, idx);
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(l[a], w[a], 1e-15);
  }
  EXPECT_NEAR(idx[0], 2.5, 1e-12);
  EXPECT_NEAR(idx[1], 2.5, 1e-12);
  EXPECT_NEAR(idx[2], 3.0, 1e-12);
}

TEST(RefractaGridFrame, NonZeroExtentAndRotationAgreeWithImageData)
{
  for (bool rotated : { false, true })
  {
    auto image = MakeImage(rotated);
    vtkNew<vtkRefractaGridFrame> frame;
    frame->SetImage(image);
    int extent[6];
    image->GetExtent(extent);
    const double* spacing = image->GetSpacing();
    // Every stored point: index = stored position, world = vtkImageData::GetPoint.
    for (vtkIdType id = 0; id < image->GetNumberOfPoints(); id += 7)
    {
      double world[3], idx[3], local[3], back[3];
      image->GetPoint(id, world);
      frame->WorldToIndexPoint(world, idx);
      frame->WorldToLocalPoint(world, local);
      const int nx = extent[1] - extent[0] + 1, ny = extent[3] - extent[2] + 1;
      const double want[3] = { static_cast<double>(id % nx), static_cast<double>((id / nx) % ny),
        static_cast<double>(id / (nx * ny)) };
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_NEAR(idx[a], want[a], 1e-9) << "point " << id << " axis " << a;
        EXPECT_NEAR(local[a], want[a] * spacing[a], 1e-9) << "point " << id << " axis " << a;
      }
      frame->IndexToWorldPoint(idx, back);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_NEAR(back[a], world[a], 1e-12);
      }
    }
    // Arbitrary points: continuous index = VTK's structured continuous index minus extent min.
    const double probes[3][3] = { { 3.0, -1.0, 12.0 }, { -4.0, 2.5, 7.25 }, { 0, 0, 0 } };
    for (const auto& p : probes)
    {
      double vtkIdx[3], idx[3], local[3], w[3];
      image->TransformPhysicalPointToContinuousIndex(p, vtkIdx);
      frame->WorldToIndexPoint(p, idx);
      frame->WorldToLocalPoint(p, local);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_NEAR(idx[a], vtkIdx[a] - extent[2 * a], 1e-9);
        EXPECT_NEAR(local[a], (vtkIdx[a] - extent[2 * a]) * spacing[a], 1e-9);
      }
      frame->LocalToWorldPoint(local, w);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_NEAR(w[a], p[a], 1e-12);
      }
    }
    // Matrices agree with the helpers, and index matrices with vtkImageData's.
    vtkNew<vtkMatrix4x4> w2i, i2w, w2l, l2w, product;
    frame->GetWorldToIndexMatrix(w2i);
    frame->GetIndexToWorldMatrix(i2w);
    frame->GetWorldToLocalMatrix(w2l);
    frame->GetLocalToWorldMatrix(l2w);
    for (const auto& pair : { std::make_pair(w2i.GetPointer(), i2w.GetPointer()),
           std::make_pair(w2l.GetPointer(), l2w.GetPointer()) })
    {
      vtkMatrix4x4::Multiply4x4(pair.first, pair.second, product);
      for (int r = 0; r < 4; ++r)
      {
        for (int c = 0; c < 4; ++c)
        {
          EXPECT_NEAR(product->GetElement(r, c), r == c ? 1.0 : 0.0, 1e-12);
        }
      }
    }
    const double p[4] = { 3.0, -1.0, 12.0, 1.0 };
    double viaMatrix[4], viaHelper[3], vtkIdx[3];
    w2i->MultiplyPoint(p, viaMatrix);
    frame->WorldToIndexPoint(p, viaHelper);
    image->TransformPhysicalPointToContinuousIndex(p, vtkIdx);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(viaMatrix[a], viaHelper[a], 1e-12);
      EXPECT_NEAR(viaMatrix[a], vtkIdx[a] - extent[2 * a], 1e-9);
    }
    // Vectors: rotation only, lengths kept, round trip.
    const double v[3] = { 0.3, -1.2, 2.0 };
    double lv[3], wv[3], dv[3];
    frame->WorldToLocalVector(v, lv);
    frame->LocalToWorldVector(lv, wv);
    EXPECT_NEAR(vtkMath::Norm(lv), vtkMath::Norm(v), 1e-12);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(wv[a], v[a], 1e-12);
    }
    const double* d = image->GetDirectionMatrix()->GetData();
    for (int r = 0; r < 3; ++r)
    {
      dv[r] = d[r] * v[0] + d[3 + r] * v[1] + d[6 + r] * v[2]; // D^T v
      EXPECT_NEAR(lv[r], dv[r], 1e-12);
    }
    std::ostringstream os;
    frame->Print(os);
    EXPECT_NE(os.str().find("Extent: (10, 17"), std::string::npos);
  }
}

TEST(RefractaGridFrame, SameGrid)
{
  auto a = MakeImage(true);
  vtkNew<vtkImageData> b;
  b->DeepCopy(a);
  EXPECT_TRUE(vtkRefractaGridFrame::SameGrid(a, b));
  // Extent from 0 with the origin moved to the first stored point: same placement.
  vtkNew<vtkRefractaGridFrame> frame;
  frame->SetImage(a);
  double first[3];
  frame->GetFirstPoint(first);
  b->SetExtent(0, 7, 0, 5, 0, 4);
  b->SetOrigin(first);
  EXPECT_TRUE(vtkRefractaGridFrame::SameGrid(a, b));
  // Same dimensions and spacing but not the same placement: the old dimensions-only check
  // accepted these.
  b->SetOrigin(a->GetOrigin());
  EXPECT_FALSE(vtkRefractaGridFrame::SameGrid(a, b));
  b->SetExtent(a->GetExtent());
  b->SetDirectionMatrix(1, 0, 0, 0, 1, 0, 0, 0, 1);
  EXPECT_FALSE(vtkRefractaGridFrame::SameGrid(a, b));
  b->SetDirectionMatrix(a->GetDirectionMatrix());
  b->SetSpacing(0.5, 0.25, 2.1);
  EXPECT_FALSE(vtkRefractaGridFrame::SameGrid(a, b));
  b->SetSpacing(a->GetSpacing());
  EXPECT_TRUE(vtkRefractaGridFrame::SameGrid(a, b));
  b->SetExtent(10, 17, -3, 2, 5, 10);
  EXPECT_FALSE(vtkRefractaGridFrame::SameGrid(a, b));
  EXPECT_FALSE(vtkRefractaGridFrame::SameGrid(a, nullptr));
  EXPECT_NE(vtkRefractaGridFrame::DescribeGrid(a).find("8x6x5"), std::string::npos);
}
