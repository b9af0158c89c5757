// Regularized Boolean operations on EVMs against voxelwise Booleans.
#include "BruteForce.h"
#include "EVM.h"
#include "EVMBoolean.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace
{

bool apply(vbr::BooleanOp op, bool a, bool b)
{
  switch (op)
  {
    case vbr::BooleanOp::Union:
      return a || b;
    case vbr::BooleanOp::Intersection:
      return a && b;
    case vbr::BooleanOp::Difference:
      return a && !b;
    default:
      return a != b;
  }
}

vbr::BitVolume voxelwise(const vbr::BitVolume& a, const vbr::BitVolume& b, vbr::BooleanOp op)
{
  vbr::BitVolume out(a.size(0), a.size(1), a.size(2));
  for (int z = 0; z < a.size(2); ++z)
    for (int y = 0; y < a.size(1); ++y)
      for (int x = 0; x < a.size(0); ++x)
        if (apply(op, a.get(x, y, z), b.get(x, y, z)))
          out.set(x, y, z);
  return out;
}

const vbr::BooleanOp Ops[] = { vbr::BooleanOp::Union,
  vbr::BooleanOp::Intersection,
  vbr::BooleanOp::Difference,
  vbr::BooleanOp::Xor };

} // namespace

TEST(Booleans, ThreeDimensionalAgainstVoxelwise)
{
  unsigned seed = 500;
  for (const vbr::Point3 d :
    { vbr::Point3{ 6, 5, 4 }, vbr::Point3{ 12, 11, 10 }, vbr::Point3{ 1, 9, 3 } })
    for (double da : { 0.2, 0.5, 0.9 })
    {
      const vbr::BitVolume a = bf::randomVolume(d, da, seed++);
      const vbr::BitVolume b = bf::randomVolume(d, 0.5, seed++);
      for (const char* name : { "XYZ", "ZYX", "YZX", "XZY" })
      {
        const vbr::AxisOrder order = vbr::axisOrderFromName(name);
        const vbr::EVM ea = vbr::extractEVM(a).sortedAs(order);
        const vbr::EVM eb = vbr::extractEVM(b).sortedAs(order);
        for (vbr::BooleanOp op : Ops)
        {
          const vbr::BitVolume expected = voxelwise(a, b, op);
          const vbr::EVM r = vbr::booleanOp(ea, eb, op);
          // The result is the canonical EVM of the expected voxels, in the same sorting.
          EXPECT_EQ(r, vbr::extractEVM(expected).sortedAs(order)) << name;
          EXPECT_EQ(r.toVoxels(d), expected) << name;
        }
      }
    }
}

TEST(Booleans, TwoDimensionalAgainstPixelwise)
{
  unsigned seed = 900;
  for (int trial = 0; trial < 12; ++trial)
  {
    const vbr::Point3 d{ 3 + trial * 5, 2 + trial * 3, 1 };
    const vbr::BitVolume a = bf::randomVolume(d, 0.5, seed++);
    const vbr::BitVolume b = bf::randomVolume(d, 0.3 + 0.05 * trial, seed++);
    for (vbr::BooleanOp op : Ops)
    {
      const vbr::BitVolume expected = voxelwise(a, b, op);
      const vbr::EVM r = vbr::booleanOp(vbr::extractEVM2D(a), vbr::extractEVM2D(b), op);
      EXPECT_EQ(r, vbr::extractEVM2D(expected));
    }
  }
}

TEST(Booleans, XorIsSymmetricDifferenceOfVertices)
{
  const vbr::BitVolume a = bf::randomVolume({ 8, 8, 8 }, 0.5, 1);
  const vbr::BitVolume b = bf::randomVolume({ 8, 8, 8 }, 0.5, 2);
  const vbr::EVM ea = vbr::extractEVM(a), eb = vbr::extractEVM(b);
  EXPECT_EQ(vbr::xorVertices(ea.vertices(), eb.vertices()),
    vbr::extractEVM(voxelwise(a, b, vbr::BooleanOp::Xor)).vertices());
}

TEST(Booleans, MismatchedOperandsAreRejected)
{
  const vbr::BitVolume a = bf::randomVolume({ 4, 4, 4 }, 0.5, 1);
  const vbr::EVM e = vbr::extractEVM(a);
  EXPECT_THROW(vbr::booleanOp(e, e.sortedAs(vbr::axisOrderFromName("XYZ")), vbr::BooleanOp::Union),
    std::invalid_argument);
}
