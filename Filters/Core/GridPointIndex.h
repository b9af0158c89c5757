// An index of packed grid points (see KeyPacker): open addressing with linear probing, kept
// at most half full. Gives each distinct point a consecutive number in order of insertion.
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
    if (this->Keys.size() > 4096)
    {
      *this = GridPointIndex();
      return;
    }
    std::fill(this->Keys.begin(), this->Keys.end(), Empty);
    this->Count = 0;
  }

  /// The number of `key`, and whether it was new (then it is size() - 1).
  std::pair<std::int64_t, bool> insert(std::uint64_t key)
  {
    if (2 * (this->Count + 1) > this->Keys.size())
      this->rehash(2 * this->Keys.size());
    std::size_t i = this->slot(key);
    for (; this->Keys[i] != Empty; i = (i + 1) & this->Mask)
      if (this->Keys[i] == key)
        return { this->Numbers[i], false };
    this->Keys[i] = key;
    this->Numbers[i] = static_cast<std::int64_t>(this->Count++);
    return { this->Numbers[i], true };
  }

  /// The number of `key`, or -1 when absent.
  std::int64_t find(std::uint64_t key) const
  {
    for (std::size_t i = this->slot(key); this->Keys[i] != Empty; i = (i + 1) & this->Mask)
      if (this->Keys[i] == key)
        return this->Numbers[i];
    return -1;
  }

private:
  static constexpr std::uint64_t Empty = ~std::uint64_t(0);

  std::size_t slot(std::uint64_t key) const
  {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> 17) & this->Mask;
  }

  void rehash(std::size_t capacity)
  {
    std::size_t size = 16;
    while (size < capacity)
      size *= 2;
    std::vector<std::uint64_t> keys(size, Empty);
    std::vector<std::int64_t> numbers(size, -1);
    keys.swap(this->Keys);
    numbers.swap(this->Numbers);
    this->Mask = size - 1;
    for (std::size_t i = 0; i < keys.size(); ++i)
    {
      if (keys[i] == Empty)
        continue;
      std::size_t j = this->slot(keys[i]);
      while (this->Keys[j] != Empty)
        j = (j + 1) & this->Mask;
      this->Keys[j] = keys[i];
      this->Numbers[j] = numbers[i];
    }
  }

  std::vector<std::uint64_t> Keys;
  std::vector<std::int64_t> Numbers;
  std::size_t Mask = 0;
  std::size_t Count = 0;
};

} // namespace vbr

#endif
