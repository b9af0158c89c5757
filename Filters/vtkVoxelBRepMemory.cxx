#include "vtkVoxelBRepMemory.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#if defined(__unix__)
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace vbr
{
namespace vtk
{
namespace
{

constexpr std::uint64_t Unknown = std::numeric_limits<std::uint64_t>::max();

/// Below this size an allocation is checked against the address-space limit only. Reading
/// /proc/meminfo takes tens of microseconds, which every update of a small image would pay
/// several times, and the system does not refuse so little memory: it overcommits.
constexpr double SmallAllocationBytes = 64.0 * 1024 * 1024;

/// Below this size an allocation is not checked at all. A process whose address space cannot
/// take one more mebibyte fails in its next allocation anywhere, checked or not; and a small
/// image's update made up to a dozen such checks, each a system call (getrlimit).
constexpr double TinyAllocationBytes = 1024.0 * 1024;

/// The value of `key` (in kiB) in /proc/meminfo, in bytes; Unknown when absent.
std::uint64_t memInfoBytes(const std::string& key)
{
  std::ifstream in("/proc/meminfo");
  std::string name;
  std::uint64_t kib = 0;
  std::string unit;
  while (in >> name >> kib)
  {
    std::getline(in, unit);
    if (name == key + ":")
      return kib * 1024;
  }
  return Unknown;
}

/// Physical memory of the machine; Unknown when not known.
std::uint64_t physicalBytes()
{
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGESIZE)
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
  if (pages > 0 && size > 0)
    return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(size);
#endif
  return Unknown;
}

/// What the address-space limit (RLIMIT_AS) leaves above the process's virtual size.
std::uint64_t addressSpaceLeft()
{
#if defined(__unix__)
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY)
    return Unknown;
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  const long size = sysconf(_SC_PAGESIZE);
  if (!(statm >> pages) || size <= 0)
    return static_cast<std::uint64_t>(limit.rlim_cur);
  const std::uint64_t used = pages * static_cast<std::uint64_t>(size);
  const std::uint64_t cap = static_cast<std::uint64_t>(limit.rlim_cur);
  return used >= cap ? 0 : cap - used;
#else
  return Unknown;
#endif
}

/// Whether `bytes` is a tiny allocation (no system call), or a small one within the
/// address-space limit (ulimit -v; without a limit that is one system call).
bool fitsWithoutAsking(double bytes)
{
  if (!std::isfinite(bytes) || bytes < 0.0 || bytes >= SmallAllocationBytes)
    return false;
  if (bytes < TinyAllocationBytes)
    return true;
  const std::uint64_t left = addressSpaceLeft();
  return left == Unknown || bytes <= double(left);
}

std::atomic<void (*)()> reclaimer{ nullptr };

/// Whether `bytes` fit in `available` (not Unknown).
bool fits(double bytes, std::uint64_t available)
{
  return std::isfinite(bytes) && bytes >= 0.0 &&
    (available == Unknown || bytes <= double(available));
}

} // namespace

void setMemoryReclaimer(void (*reclaim)())
{
  reclaimer.store(reclaim);
}

void reclaimMemory()
{
  if (void (*reclaim)() = reclaimer.load())
    reclaim();
}

std::uint64_t availableMemoryBytes()
{
  std::uint64_t system = memInfoBytes("MemAvailable");
  if (system == Unknown)
    system = physicalBytes();
  const std::uint64_t left = addressSpaceLeft();
  return system < left ? system : left;
}

std::string formatBytes(double bytes)
{
  const char* units[] = { "bytes", "kiB", "MiB", "GiB", "TiB", "PiB", "EiB" };
  int u = 0;
  while (bytes >= 1024.0 && u < 6)
  {
    bytes /= 1024.0;
    ++u;
  }
  char text[64];
  std::snprintf(text, sizeof(text), u == 0 ? "%.0f %s" : "%.1f %s", bytes, units[u]);
  return text;
}

std::string checkAllocation(double bytes, const std::string& what)
{
  if (fitsWithoutAsking(bytes))
    return std::string();
  std::uint64_t available = availableMemoryBytes();
  if (fits(bytes, available))
    return std::string();
  if (std::isfinite(bytes) && bytes >= 0.0 && reclaimer.load())
  {
    reclaimMemory(); // memory kept for reuse counts as used until given back
    available = availableMemoryBytes();
    if (fits(bytes, available))
      return std::string();
  }
  const bool known = available != Unknown;
  std::ostringstream message;
  message << what << " needs ";
  if (std::isfinite(bytes) && bytes >= 0.0)
    message << "about " << formatBytes(bytes);
  else
    message << "more memory than can be counted";
  if (known)
    message << ", but only " << formatBytes(double(available)) << " can be allocated";
  message << " (available memory and ulimit -v). Use a smaller input or a sub-extent.";
  return message.str();
}

} // namespace vtk
} // namespace vbr
