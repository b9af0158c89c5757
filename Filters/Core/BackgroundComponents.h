// The background components inside the convex hull CH(S) classified as section 4.1 of FZD-514
// defines them: the face-connected components of the background centres in the closed hull,
// each a cavity (no corner of its voxels outside or on CH(S)), a concavity (the hull faces seen
// from such corners one edge-connected set) or a tunnel (more than one). Only the counts are
// reported (ModifiedHull::concavities, cavities, tunnels); the modification does not use them.
#ifndef vbr_BackgroundComponents_h
#define vbr_BackgroundComponents_h

#include "HullModifierContext.h"

namespace vbr
{
namespace detail
{

/// Section 4.1: the background components in the closed hull (CUDB, face-connected), each a
/// cavity, concavity or tunnel by the faces seen from (or coplanar with) its voxels' corners.
void classifyBackgroundComponents(const BitVolume& objects, const CellList& hull, ModifiedHull& r);

} // namespace detail
} // namespace vbr

#endif
