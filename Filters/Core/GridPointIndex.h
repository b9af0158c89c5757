// An index of packed grid points (see KeyPacker): open addressing with linear probing, kept
// at most half full. Gives each distinct point a consecutive number in order of insertion.
// A slot holds its key and its number side by side, so that a lookup, which lands on a
// random slot of a table far larger than the cache, misses the cache once and not twice.
#ifndef vbr_GridPointIndex_h
#define vbr_GridPointIndex_h

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace vbr
{

class GridPointIndex
{
public:
  explicit GridPointIndex(std::size_t expected = 0) { this->rehash(2 * expected); }

  std::size_t size() const { return this->Count; }

  /// Forgets every point; keeps the memory of a small table.
  void clear()
  {
    if (this->Slots.size() > 4096)
    {
      *this = GridPointIndex();
      return;
    }
    std::fill(this->Slots.begin(), this->Slots.end(), Slot());
    this->Count = 0;
  }

  /// The number of `key`, and whether it was new (then it is size() - 1).
  std::pair<std::int64_t, bool> insert(std::uint64_t key)
  {
    if (2 * (this->Count + 1) > this->Slots.size())
      this->rehash(2 * this->Slots.size());
    std::size_t i = this->slot(key);
    for (; this->Slots[i].key != Empty; i = (i + 1) & this->Mask)
      if (this->Slots[i].key == key)
        return { this->Slots[i].number, false };
    this->Slots[i] = { key, static_cast<std::int64_t>(this->Count++) };
    return { this->Slots[i].number, true };
  }

  /// The number of `key`, or -1 when absent.
  std::int64_t find(std::uint64_t key) const
  {
    for (std::size_t i = this->slot(key); this->Slots[i].key != Empty; i = (i + 1) & this->Mask)
      if (this->Slots[i].key == key)
        return this->Slots[i].number;
    return -1;
  }

private:
  static constexpr std::uint64_t Empty = ~std::uint64_t(0);

  struct Slot
  {
    std::uint64_t key = Empty;
    std::int64_t number = -1;
  };

  std::size_t slot(std::uint64_t key) const
  {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> 17) & this->Mask;
  }

  void rehash(std::size_t capacity)
  {
    std::size_t size = 16;
    while (size < capacity)
      size *= 2;
    std::vector<Slot> old(size);
    old.swap(this->Slots);
    this->Mask = size - 1;
    for (const Slot& s : old)
    {
      if (s.key == Empty)
        continue;
      std::size_t j = this->slot(s.key);
      while (this->Slots[j].key != Empty)
        j = (j + 1) & this->Mask;
      this->Slots[j] = s;
    }
  }

  std::vector<Slot> Slots;
  std::size_t Mask = 0;
  std::size_t Count = 0;
};

} // namespace vbr

#endif
