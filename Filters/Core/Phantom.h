// A procedural label volume exercising what boundary extraction must get right: nested
// shells (a cavity holding an inner ball), a handle (torus), a plate pierced by holes, a
// hollow frame, and objects touching along an edge and at a corner only (non-manifold
// contacts). Labels 1..5; 0 is background.
#ifndef vbr_Phantom_h
#define vbr_Phantom_h

#include <array>
#include <cstdint>
#include <vector>

namespace vbr
{

/// Labels of an nx * ny * nz volume, x fastest. Every part scales with the volume.
std::vector<std::uint8_t> makePhantom(const std::array<std::int32_t, 3>& dims);

/// The labels of the voxels [first, first + size) of the phantom of `dims`, x fastest: the
/// piece of a distributed image, computed without the rest.
std::vector<std::uint8_t> makePhantomPiece(const std::array<std::int32_t, 3>& dims,
  const std::array<std::int32_t, 3>& first,
  const std::array<std::int32_t, 3>& size);

/// Number of labels makePhantom uses (1..count).
constexpr int PhantomLabelCount = 5;

} // namespace vbr

#endif
