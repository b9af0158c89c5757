// Union-find (disjoint sets) over consecutive numbers, the one every part of the core uses:
// the umbrellas and components of the surfel graph, the label equivalences of CUDB's
// connected-component labelling (Algorithm 4 of Cruz-Matias & Ayala) and the section intervals that
// the 2D plane sweep merges into faces.
//
// The root of a class is always its smallest element (the larger root is linked below the
// smaller one), so that roots follow creation order: the first label, box or interval of a
// class stands for it. Finding compresses the path by halving.
#ifndef vbr_UnionFind_h
#define vbr_UnionFind_h

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace vbr
{

class UnionFind
{
public:
  /// Elements 0 .. n - 1, each alone in its class.
  explicit UnionFind(std::size_t n = 0)
    : Parent(n)
  {
    std::iota(this->Parent.begin(), this->Parent.end(), 0u);
  }

  /// Elements 0 .. n - 1, each alone in its class, in the memory of `storage` (its values are
  /// replaced): a caller labelling one image after another hands the same memory back (release)
  /// rather than having the pages of a new block faulted in again.
  UnionFind(std::vector<std::uint32_t>&& storage, std::size_t n)
    : Parent(std::move(storage))
  {
    this->Parent.resize(n);
    std::iota(this->Parent.begin(), this->Parent.end(), 0u);
  }

  /// The memory of the elements, for another UnionFind; this one is left empty.
  std::vector<std::uint32_t> release()
  {
    std::vector<std::uint32_t> storage = std::move(this->Parent);
    this->Parent.clear();
    return storage;
  }

  /// A new element, alone in its class; its number is size() - 1.
  std::uint32_t add()
  {
    const auto x = static_cast<std::uint32_t>(this->Parent.size());
    this->Parent.push_back(x);
    return x;
  }

  std::size_t size() const { return this->Parent.size(); }

  /// Room for n elements in all, so that add() does not reallocate up to there.
  void reserve(std::size_t n) { this->Parent.reserve(n); }

  /// Appends the elements of `other` with their classes, numbered after this one's (element
  /// i of `other` becomes size() + i): roots stay the smallest elements of their classes.
  void append(UnionFind&& other)
  {
    if (this->Parent.empty())
    {
      this->Parent = std::move(other.Parent);
      return;
    }
    const auto offset = static_cast<std::uint32_t>(this->Parent.size());
    this->Parent.reserve(this->Parent.size() + other.Parent.size());
    for (std::uint32_t p : other.Parent)
      this->Parent.push_back(offset + p);
  }

  /// The smallest element of the class of x. Halves the path on the way, but writes nothing
  /// where x's parent is the root already (most finds of a labelling in scan order): a store
  /// of the value already there, and the load after it, were most of the time of a find.
  std::uint32_t find(std::uint32_t x)
  {
    std::uint32_t parent = this->Parent[x];
    while (parent != x)
    {
      const std::uint32_t grandparent = this->Parent[parent];
      if (grandparent == parent)
        return parent;
      this->Parent[x] = grandparent;
      x = grandparent;
      parent = this->Parent[x];
    }
    return x;
  }

  /// Joins the classes of a and b; returns the root of the union (the smaller root).
  std::uint32_t unite(std::uint32_t a, std::uint32_t b)
  {
    a = this->find(a);
    b = this->find(b);
    if (b < a)
      std::swap(a, b);
    this->Parent[b] = a;
    return a;
  }

  /// Joins the class of x with the class whose root is `root` (a root: the result of the last
  /// unite, with no union since); returns the root of the union, with one find fewer than unite.
  /// Without a branch on whether the classes differ (a root linked to itself when they do
  /// not): on noisy images that branch went either way.
  std::uint32_t uniteWithRoot(std::uint32_t x, std::uint32_t root)
  {
    assert(this->Parent[root] == root);
    x = this->find(x);
    const std::uint32_t smaller = x < root ? x : root, larger = x < root ? root : x;
    this->Parent[larger] = smaller;
    return smaller;
  }

  /// Consecutive numbers first, first + 1, ... for the classes, in order of their smallest
  /// element, written to number[0 .. size() - 1]; returns the number of classes. One pass in
  /// increasing order from the parents alone, without a find: the parent of an element is a
  /// smaller element of its class, numbered already (roots are the smallest elements, links go
  /// from the larger root to the smaller, and halving only shortens them).
  std::uint32_t numberClasses(std::uint32_t* number, std::uint32_t first) const
  {
    const std::uint32_t* parent = this->Parent.data();
    const auto n = static_cast<std::uint32_t>(this->Parent.size());
    std::uint32_t next = first;
    for (std::uint32_t i = 0; i < n; ++i)
    {
      const std::uint32_t p = parent[i];
      number[i] = p == i ? next++ : number[p];
    }
    return next - first;
  }

  /// Consecutive numbers 0 .. count - 1 for the classes, in order of their smallest element.
  std::vector<std::uint32_t> numberClasses(std::uint32_t& count) const
  {
    std::vector<std::uint32_t> number(this->Parent.size());
    count = this->numberClasses(number.data(), 0);
    return number;
  }

private:
  std::vector<std::uint32_t> Parent;
};

} // namespace vbr

#endif
