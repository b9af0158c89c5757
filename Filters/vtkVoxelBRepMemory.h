// What a filter may allocate: the memory the system has available to this process, so that a
// filter refuses an input that cannot fit with a clear error instead of dying on a failed
// allocation.
#ifndef vtkVoxelBRepMemory_h
#define vtkVoxelBRepMemory_h

#include <cstdint>
#include <string>

namespace vbr
{
namespace vtk
{

/// Bytes this process can still allocate: the smaller of the system's available memory
/// (MemAvailable of /proc/meminfo, else the physical memory) and what the address-space
/// limit (ulimit -v) leaves above the process's current size. The maximum of uint64 when
/// nothing is known.
std::uint64_t availableMemoryBytes();

/// An empty string when `bytes` fit in availableMemoryBytes() (always below 1 MiB, unchecked:
/// a small image's update makes several such requests), if need be once the memory kept
/// for reuse is given back (reclaimMemory); otherwise an error message
/// naming `what`, the bytes needed and the limit. A negative or non-finite estimate (an
/// overflowing product) never fits.
std::string checkAllocation(double bytes, const std::string& what);

/// Memory a filter keeps for reuse that it can give back when an allocation would be refused:
/// `reclaim` frees it. One function for the process (the last set replaces the earlier one;
/// null removes it).
void setMemoryReclaimer(void (*reclaim)());

/// Gives back the memory kept for reuse (setMemoryReclaimer), before an allocation is refused
/// or after one failed.
void reclaimMemory();

/// `bytes` for a message: "1.5 GiB", "640 MiB", "12 kiB", "100 bytes".
std::string formatBytes(double bytes);

} // namespace vtk
} // namespace vbr

#endif
